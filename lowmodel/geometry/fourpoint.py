"""Four-point contact geometry of a ball between two gothic-arch grooves (lin2017 eq 1).

Frame (lin2017 Figs 1-2, lin2019 Fig 2): ball centre at the origin, ``z`` along
the grooves, ``y`` up, ``x`` to the right; the bottom groove below.  Contacts
in the order :data:`CONTACT_NAMES` = ``(BL, BR, TR, TL)`` (bottom/top,
left/right; the project-wide convention, docs/developing.md).  Contact ``i``
has the contact angle ``beta_i`` measured from ``-y`` (bottom) or ``+y`` (top)
and sits at ``R_B n_i`` with the outward unit normal (lin2017 eq 1)::

    n_BL = (-sin b, -cos b),  n_BR = (sin b, -cos b),
    n_TR = ( sin b,  cos b),  n_TL = (-sin b,  cos b)      (b = beta_i)

The models (:mod:`lowmodel.linear_bearing.fourpoint`, :mod:`lowmodel.linear_bearing.ball`)
and the mesh builders take the normals and points from here.
"""
from __future__ import annotations

import numpy as np

from ballbench.lowmodel import checks

__all__ = ["CONTACT_NAMES", "SIGN_X", "SIGN_Y", "contact_normals", "contact_normal", "contact_points",
           "contact_limits"]

CONTACT_NAMES = ("BL", "BR", "TR", "TL")  # lin2017 Fig 2 order
SIGN_X = np.array([-1.0, 1.0, 1.0, -1.0])  # n_x / sin(beta): left -, right +
SIGN_Y = np.array([-1.0, -1.0, 1.0, 1.0])  # n_y / cos(beta): bottom -, top +


def contact_normals(contact_angles) -> np.ndarray:
    """Outward unit normals ``(n_x, n_y)`` of the four contacts, shape ``(..., 4, 2)`` (lin2017 eq 1).

    ``contact_angles`` (..., 4) rad, ``(BL, BR, TR, TL)``.  No range check
    (the models check their angles once); see :func:`contact_points`.
    """
    angles = np.asarray(contact_angles, dtype=float)
    return np.stack([SIGN_X * np.sin(angles), SIGN_Y * np.cos(angles)], axis=-1)  # lin2017 eq 1


def contact_normal(name: str, contact_angle: float) -> np.ndarray:
    """Outward unit normal ``(n_x, n_y)`` of the contact ``name`` (one of :data:`CONTACT_NAMES`), shape (2,)."""
    index = CONTACT_NAMES.index(checks.choice("name", name, CONTACT_NAMES))
    return contact_normals(np.full(4, float(contact_angle)))[index]


def contact_points(ball_radius: float, contact_angles) -> np.ndarray:
    """Contact points ``(BL, BR, TR, TL)`` of a ball centred at the origin, shape (4, 2) [m] (lin2017 eq 1).

    ``ball_radius`` R_B [m] > 0, ``contact_angles`` (4,) rad, each in (0, pi/2).
    """
    radius = checks.positive("ball_radius", ball_radius, "m")
    angles = checks.trailing_axis("contact_angles", contact_angles, 4, "(BL, BR, TR, TL)", "rad")
    checks.contact_angle("contact_angles", angles)
    return radius * contact_normals(angles)


def contact_limits(contact_angles) -> tuple[np.ndarray, np.ndarray]:
    """Range of the side-force ratio ``rho = N_x / N_y`` with four-point contact (lin2017 eq 37).

    ``contact_angles`` (..., 4) rad.  Returns ``(rho_min, rho_max)``, each (...);
    contact needs ``rho_min < rho < rho_max`` (equality: a force is zero).  Here, with the contact geometry, so
    that the case files check it without loading the models (lowmodel.model_inputs); the models import it from
    :mod:`lowmodel.linear_bearing.fourpoint`.
    """
    angles = checks.trailing_axis("contact_angles", contact_angles, 4, "(BL, BR, TR, TL)", "rad")
    bl, br, tr, tl = np.moveaxis(checks.contact_angle("contact_angles", angles), -1, 0)  # lin2017 Sec 2.1
    return -np.minimum(np.tan(bl), np.tan(tr)), np.minimum(np.tan(br), np.tan(tl))  # lin2017 eq 37
