"""Low-order and analytical models of ball bearings and ball screws.

numpy/scipy only; importing this package must stay light (no gmsh, pyvista,
vtk or matplotlib at import time).  One module per model:

- ``lowmodel.contact.hertz``: exact Hertz point contact (Johnson 1985; lin2019 eqs 15, 53)
- ``lowmodel.contact.ellipse_friction``: friction over a Hertz ellipse with an offset
  velocity centre (lin2019 Appendix A4-A7), tabulated and cached
- ``lowmodel.linear_bearing``: ``fourpoint`` (rigid four-point rolling/sliding, lin2017),
  ``contacts`` and ``ball`` (single-ball quasi-static friction, lin2019 eqs 1-4), ``b2b``
  (two- and N-ball ball-to-ball contact, eqs 5-10), ``b2b_analytical`` (eqs 11-33),
  ``b2b_traction`` (the B2B solve with sampled, e.g. FE, contact tractions), ``rolling_contacts`` and
  ``b2b_rolling`` (the contacts of a ball as steady rolling contacts; the B2B solve with stick/slip contacts)
- ``lowmodel.screw``: ``kinematics`` (wang2022), ``contacts`` and ``ball`` (lin2019 eqs 34-55),
  ``b2b`` (eqs 56-61), ``load_distribution``, ``whole_screw`` (Sec 3.4), ``b2b_traction``, ``b2b_rolling``
  (stick/slip contacts), ``friction_torque`` (sun2021 eq 20)
- ``lowmodel.ball_bearing.harris``: ball-bearing kinematics relative to the cage (Harris, wang2022 Table 1)
- ``lowmodel.geometry``: the geometry core shared by models and mesh builders:
  ``helix`` (ball-centre helix, lead angle, Frenet frame CS1 and lin2019's CS3),
  ``groove`` (gothic-arch profiles, exact helical groove surface and its principal
  curvatures), ``fourpoint`` (lin2017 eq 1 contact normals/points, ``CONTACT_NAMES``)

Shared: ``lowmodel.b2b_chain`` (the B2B chain complementarity of every B2B model), ``lowmodel.full_slip_validity``
(where lin2019's full slip holds: stick/slip against full slip),
``lowmodel.solvers`` (damped Newton, continuation), ``lowmodel.state`` (the fields every ball
state shares), ``lowmodel.dual`` (forward-mode derivatives), ``lowmodel.quadrature``
(tanh-sinh, Gauss-Legendre), ``lowmodel.checks`` (input checks: one ValueError naming
parameter, unit, range and value), ``lowmodel.model_inputs`` (what lin2019's models need beyond each field's
range, checked by the models and the case files), ``lowmodel.errors`` (ConvergenceError), ``lowmodel.cache``.
docs/architecture.md maps papers, sections and equations to modules.
"""
