"""Ball screws: contact kinematics (wang2022) and lin2019 Sec 3.

Modules: ``kinematics`` (wang2022 Frenet-frame velocities), ``ball`` (one ball,
lin2019 eqs 34-55), ``b2b`` (2 to N balls with ball-to-ball contact, eqs 56-61),
``load_distribution`` (static axial load of each ball), ``whole_screw`` (Sec 3.4
simulation), ``preload`` (the preload loss of four-point contacts, where lin2019's
model stops applying), ``b2b_traction`` (the B2B solve with sampled contact tractions, e.g. from
FE).  docs/ball_screw.md.  ``friction_torque``: sun2021 eq 20 with wang2022
entrainment and sliding (docs/mixed_lubrication.md).  Harris's ball-bearing
kinematics, wang2022's lead-0 check, is :mod:`lowmodel.ball_bearing.harris`.
"""
