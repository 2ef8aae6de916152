"""What lin2019's low-order friction models need of their inputs beyond each field's own range
(:data:`lowmodel.bearing.FIELDS`): a friction coefficient > 0, a nonzero speed, a screw groove inside the pitch
radius, four-point contact of every guide ball.

Each check is defined once, here, and called by the model that needs it when it is built
(:func:`lowmodel.linear_bearing.contacts.contacts_from_forces`, :func:`lowmodel.screw.contacts.module`,
:func:`lowmodel.linear_bearing.b2b_rolling.solve`) and by the case files when they are read
(``validation.cases.case_file``: before any work, the message then naming file, line and key).  Four-point contact
is the exception: the guide models check it on lin2017 eq 36's forces as they compute them
(:func:`lowmodel.linear_bearing.fourpoint.normal_forces`), the case files by :func:`four_point_contact` on the range
those forces give, lin2017 eq 37 (:func:`lowmodel.geometry.fourpoint.contact_limits`, which the models' message
quotes).  numpy and the geometry core only, so that reading a case file loads no model.  Each function raises
ValueError naming ``name`` and the range; the others than :func:`four_point_contact` return the value as a float.
"""
from __future__ import annotations

import numpy as np

from ballbench.lowmodel import checks
from ballbench.lowmodel.geometry.fourpoint import CONTACT_NAMES, contact_limits
from ballbench.lowmodel.geometry.groove import groove_radius

__all__ = ["FRICTION_COEFFICIENT_MAX", "NUT_SPEED_RANGE", "guide_friction_coefficient", "groove_velocity",
           "screw_friction_coefficient", "nut_speed", "screw_pitch_radius", "four_point_contact",
           "RANGES"]

FRICTION_COEFFICIENT_MAX = 2.0  # mu in (0, 2]: residuals are scaled by mu F (friction would swamp the normal forces)
NUT_SPEED_RANGE = (1e-100, 1e100)  # |omega_N| [rad/s]: quasi-static, any speed; the floats set the range
# each check's range in words (a case file's template and docs/cases.md's table)
RANGES = {"guide_friction_coefficient": "> 0", "groove_velocity": "nonzero",
          "screw_friction_coefficient": f"in (0, {FRICTION_COEFFICIENT_MAX:g}]", "nut_speed": "nonzero"}


def guide_friction_coefficient(value, name: str = "friction_coefficient") -> float:
    """mu of lin2019 Sec 2's linear-guide models: finite and > 0 (mu = 0 leaves the ball motion undetermined)."""
    return float(checks.positive(name, value, note="mu = 0 leaves the ball motion undetermined"))


def groove_velocity(value, name: str = "groove_velocity") -> float:
    """v [m/s] of the top groove against the bottom one (lin2019 Sec 2): finite and nonzero (the ball motion is
    undetermined at rest)."""
    velocity = float(checks.finite(name, value, "m/s"))
    if velocity == 0.0:
        raise ValueError(f"{name} must be finite and nonzero m/s, got {value!r}")
    return velocity


def screw_friction_coefficient(value, name: str = "friction_coefficient") -> float:
    """mu of lin2019 Sec 3's ball-screw models: in (0, :data:`FRICTION_COEFFICIENT_MAX`]."""
    return float(checks.bounded(name, value, 0.0, FRICTION_COEFFICIENT_MAX, upper_closed=True,
                                note="Coulomb friction of steel contacts; equilibrium is solved to a tolerance in "
                                     "mu F"))


def nut_speed(value, name: str = "nut_speed") -> float:
    """omega_N [rad/s] of lin2019 Sec 3 (the nut drives): ``|omega_N|`` in :data:`NUT_SPEED_RANGE`."""
    speed = float(checks.finite(name, value, "rad/s"))
    if not NUT_SPEED_RANGE[0] <= abs(speed) <= NUT_SPEED_RANGE[1]:
        raise ValueError(f"{name} must satisfy {NUT_SPEED_RANGE[0]:g} <= |{name}| <= {NUT_SPEED_RANGE[1]:g} rad/s "
                         "(nonzero: the ball motion is undetermined at rest; the friction Jacobian scales like "
                         f"1 / speed and leaves the float range near 1e-300), got {value!r}")
    return speed


def screw_pitch_radius(pitch_radius, ball_radius, conformity, name: str = "pitch_radius") -> float:
    """R_P [m] of lin2019 Sec 3's screw module: beyond the groove radius ``r_g = 2 f R_B``
    (:func:`lowmodel.geometry.groove.groove_radius`; the screw groove must not reach the axis, as
    :func:`lowmodel.geometry.groove.helical_groove` checks for the groove alone)."""
    flank = groove_radius(ball_radius, conformity)
    if not float(pitch_radius) > flank:
        raise ValueError(f"{name} must exceed the groove radius 2 conformity ball_radius = {flank!r} m (the screw "
                         f"groove must not reach the axis), got {pitch_radius!r}")
    return float(pitch_radius)


def four_point_contact(side_forces, vertical_force: float, contact_angles, name: str = "side_force_ratio") -> None:
    """ValueError unless every ball keeps four-point contact: its ``N_x / N_y`` inside the range of lin2017 eq 37
    (:func:`lowmodel.geometry.fourpoint.contact_limits`) at the ``contact_angles`` (BL, BR, TR, TL) [rad].

    ``side_forces`` (n,) [N]: N_x of each ball (``lowmodel.bearing.GuideLoadCase.side_forces``); ``vertical_force``
    N_y [N] > 0.  Equality (a contact force of zero) is refused, as lin2017 eq 36 gives the models no four-point
    state there."""
    vertical = float(checks.positive("vertical_force", vertical_force, "N"))
    angles = np.asarray(contact_angles, dtype=float)
    lower, upper = (float(v) for v in contact_limits(angles))
    for ball, side in enumerate(np.atleast_1d(np.asarray(side_forces, dtype=float)), start=1):
        with np.errstate(over="ignore"):  # a ratio beyond the float range is inf, outside the range
            ratio = float(side / vertical)
        if not lower < ratio < upper:
            raise ValueError(
                f"{name}: loss of four-point contact (lin2017 eq 37): ball {ball} carries N_x/N_y = {ratio:.6g}, "
                f"which must lie in ({lower:.6g}, {upper:.6g}) = (-min(tan beta_BL, tan beta_TR), "
                f"min(tan beta_BR, tan beta_TL)) at the contact angles ({', '.join(CONTACT_NAMES)}) = "
                f"({', '.join(f'{a:.4g}' for a in np.degrees(angles))}) deg")
