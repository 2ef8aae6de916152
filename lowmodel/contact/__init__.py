"""Contact mechanics: exact Hertz point contact and friction over a contact ellipse.

Modules: ``hertz``, ``ellipse_friction`` (velocity centre on the major axis, lin2019
eqs A4-A7), ``ellipse_friction_offset`` (offset in both directions, lin2019 eqs 44-47, A9-A11).
"""
