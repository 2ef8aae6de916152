"""Rotary ball bearings: Harris's ball kinematics relative to the cage (``harris``).

wang2022 Sec 3.1 checks its ball-screw kinematics (Frenet frame as a virtual cage,
:mod:`lowmodel.screw.kinematics`) on a deep-groove ball bearing, a ball screw of lead
0, against Harris's method (wang2022 ref [20], Table 1); that bearing is neither a
linear guide (:mod:`lowmodel.linear_bearing`) nor a screw, so its model lives here.
"""
