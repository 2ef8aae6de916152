"""Independent references for the validation scenes, kept apart from the models they judge.

Every function here computes its reference from the raw inputs a paper states
(Young's modulus, Poisson's ratio, radii, conformity, load, velocities) by code
that never calls ``ballbench.lowmodel``: a wrong model (a wrong E*, a wrong
groove radius, a missing friction term) cannot move its own reference.

* :mod:`.hertz`: Hertz closed forms (sphere), curvature sums of the bearing
  geometries, the Boussinesq quadrature of a Hertz pressure field;
* :mod:`.lin2019`: eq 30 of lin2019 by an exact-quadrature route (friction
  integrals of the contact ellipse by adaptive quadrature, not the model's map).
"""
