"""Low-order and analytical models of ball bearings and ball screws.

numpy/scipy only; importing this package must stay light (no gmsh, pyvista,
vtk or matplotlib at import time).  One module per model:

- ``lowmodel.contact.hertz``: exact Hertz point contact (Johnson 1985; lin2019 eqs 15, 53)
- ``lowmodel.linear_bearing.fourpoint``: rigid four-point rolling/sliding (lin2017)
- ``lowmodel.contact.ellipse_friction``: friction over a Hertz ellipse with an offset
  velocity centre (lin2019 Appendix A4-A7), tabulated and cached
- ``lowmodel.linear_bearing.ball``: single-ball quasi-static friction solver (lin2019 eqs 1-4)
- ``lowmodel.linear_bearing.b2b``: two- and N-ball ball-to-ball contact (lin2019 eqs 5-10)
- ``lowmodel.linear_bearing.b2b_analytical``: analytical B2B model (lin2019 eqs 11-33)
- ``lowmodel.geometry``: the geometry core shared by models and mesh builders:
  ``helix`` (ball-centre helix, lead angle, Frenet frame CS1 and lin2019's CS3),
  ``groove`` (gothic-arch profiles, exact helical groove surface and its principal
  curvatures), ``fourpoint`` (lin2017 eq 1 contact normals/points, ``CONTACT_NAMES``)
- ``lowmodel.screw.kinematics``: contact kinematics, slide-roll ratio,
  entrainment velocity (wang2022), Wei's absolute-velocity measures
- ``lowmodel.ball_bearing.harris``: ball-bearing kinematics relative to the cage (Harris)

Shared: ``lowmodel.checks`` (input checks: one ValueError naming parameter, unit,
range and value), ``lowmodel.solvers`` (damped Newton), ``lowmodel.errors``
(ConvergenceError), ``lowmodel.cache``.
"""
