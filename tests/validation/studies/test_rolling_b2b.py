"""The stick/slip ladders of lin2019's two-ball cases without the FE rungs (validation.studies.rolling_b2b) and the
levels' data (validation.cases.stick_slip)."""
from __future__ import annotations

import math

import pytest

from ballbench.validation.cases import stick_slip
from ballbench.validation.cases.case import MeshLevels
from ballbench.validation.studies import rolling_b2b


def test_linear_ladder_without_fe_holds_the_analytical_low_order_and_stick_slip_rungs():
    rungs = rolling_b2b.linear_ladder("a", "quick", with_fe=False)
    assert [r.family for r in rungs] == ["analytical", "low-order numerical", "BEM"]
    stick_slip_rung = rungs[-1]
    assert stick_slip_rung.level == "16 x 64 cells"
    assert stick_slip_rung.b2b_force == pytest.approx(rungs[1].b2b_force, rel=0.02)
    assert stick_slip_rung.power_balance < 1e-6 and not math.isnan(stick_slip_rung.full_slip_force)


def test_levels_refuse_a_bad_cover_or_tail_share():
    hertz, compliance = stick_slip.LINEAR.hertz_cells, stick_slip.LINEAR.compliance
    assert isinstance(hertz, MeshLevels)
    with pytest.raises(ValueError, match="cover"):
        stick_slip.StickSlipLevels(hertz, compliance, cover=(1.4, -1.0))
    with pytest.raises(ValueError, match="outside"):
        stick_slip.StickSlipLevels(hertz, compliance, cover=(1.4, 1.2), outside=0.5)


def test_ladders_refuse_an_unknown_case_or_level():
    with pytest.raises(ValueError, match="case"):
        rolling_b2b.linear_ladder("c", "quick", with_fe=False)
    with pytest.raises(ValueError, match="level"):
        rolling_b2b.screw_ladder("a", "coarse", with_fe=False)
