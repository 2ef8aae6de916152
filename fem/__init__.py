"""scikit-fem contact solvers and post-processing (3D elasticity, unilateral contact).

Modules: ``elasticity`` (mesh loading, P1/P2 stiffness), ``linsolve`` (pardiso
Schur-complement condensation), ``surface`` (nodal areas, projection along the
contact normal), ``contact`` (node-to-surface P1 contact, the primal-dual
active-set solver), ``mortar`` (mortar contact, P1/P2),
``postprocess`` (Hertz ellipse fit, approach convention), ``hertz_case`` (one
FE Hertz case end to end).  See docs/fem.md.
"""
