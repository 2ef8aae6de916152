"""Contact mechanics: exact Hertz point contact (``hertz``), friction over a contact ellipse
(``ellipse_friction``), half-space contact on an arbitrary gap by the boundary-element method
(``halfspace``), a ball in the exact helical groove against Hertz (``screw_contact``) and the
elastohydrodynamic point contact of sun2021 (``ehl``)."""
