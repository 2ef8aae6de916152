"""What every ball-state result shares: the power and the ball-to-ball (B2B) fields, and the total loss.

The four quasi-static solutions (:class:`lowmodel.linear_bearing.ball.BallState`,
:class:`lowmodel.linear_bearing.b2b_traction.TractionState`,
:class:`lowmodel.screw.ball.ScrewBallState`, :class:`lowmodel.screw.b2b_traction.ScrewTractionState`)
derive from :class:`BallStateBase`: their own kinematic and contact fields first (positional),
these fields after them (keyword-only), so a report, a sweep or a figure reads the losses and
the B2B forces of any model the same way.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

__all__ = ["BallStateBase", "friction_increase"]


@dataclass(frozen=True, kw_only=True)
class BallStateBase:
    """Shared fields of a quasi-static state of ``n`` balls (``p`` B2B pairs: n - 1 in a row, n in a ring).

    friction_loss : (n, c) W, ball-to-groove friction loss of each contact (or sampled patch)
    input_power : W, put in by the driven body (top groove, nut): ``P_in = sum P_loss`` at equilibrium
    b2b_force : (p,) N, ball-to-ball normal force of each pair (0 where open)
    b2b_friction_loss : (p,) W, ``mu F_B2B |slip|`` (lin2019 eqs 7, 58)
    b2b_slip : (p,) m/s, slip speed at each B2B contact
    iterations : Newton iterations;  residual : final max residual (the model's scaled units)
    """

    friction_loss: np.ndarray
    input_power: float
    b2b_force: np.ndarray
    b2b_friction_loss: np.ndarray
    b2b_slip: np.ndarray
    iterations: int
    residual: float

    @property
    def groove_loss(self) -> float:
        """Ball-to-groove friction loss [W]."""
        return float(self.friction_loss.sum())

    @property
    def total_loss(self) -> float:
        """Ball-to-groove plus ball-to-ball friction loss [W]."""
        return float(self.friction_loss.sum() + self.b2b_friction_loss.sum())


def friction_increase(touching, free) -> float:
    """lin2019's friction increase by B2B contact (Sec 2.4, Table 3; Sec 3.3, Table 5) as a fraction [-]: the total
    loss of the balls touching over that of the same balls free, less one (``x 100`` for the printed %).  Any two
    states with a ``total_loss`` [W] (every model's state, full-slip or stick/slip)."""
    return touching.total_loss / free.total_loss - 1.0
