"""Contact mechanics: exact Hertz point contact (``hertz``), friction over a contact ellipse
(``ellipse_friction``: velocity centre on the major axis, lin2019 eqs A4-A7;
``ellipse_friction_offset``: offset in both directions, lin2019 eqs 44-47, A9-A11), half-space
contact on an arbitrary gap by the boundary-element method (``halfspace``), a ball in the exact
helical groove against Hertz (``screw_contact``), sampled contact tractions with pointwise
Coulomb friction (``traction``, the FE-informed B2B models), the elastohydrodynamic point contact of
sun2021 (``ehl``), its fractal raceway roughness (``roughness``) and mixed lubrication with the
friction of sun2021 eqs 21-23 (``mixed``); steady rolling with stick and slip (Kalker's exact theory on a grid,
``rolling``, with its input ``rolling_input``, operators ``rolling_operators`` and solver ``rolling_newton``;
its tangential influence coefficients, ``influence``; Kalker's simplified theory FASTSIM, ``fastsim``;
docs/rolling_contact.md); ball-groove contacts on rolling grids with the rolling solve as a ball's friction law
(``rolling_friction``, docs/b2b_rolling.md)."""
