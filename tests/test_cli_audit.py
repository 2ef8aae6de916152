"""What a new user trips over on the command line (issue 15 audit): each test fails on the behaviour found."""
from __future__ import annotations

import pytest

from ballbench.validation import cli


def _one_error_line(capsys, code):
    captured = capsys.readouterr()
    lines = [x for x in captured.err.splitlines() if x.strip()]
    assert code == 2, captured
    assert len(lines) == 1 and lines[0].startswith("ballbench: error: "), lines
    assert "Traceback" not in captured.err + captured.out
    return lines[0]


@pytest.fixture
def no_work(monkeypatch):
    from ballbench.validation import runner, show

    monkeypatch.setattr(runner, "run_scenes", lambda *a, **k: pytest.fail("work started before the check"))
    monkeypatch.setattr(show, "show", lambda *a, **k: pytest.fail("show started on a scene it cannot draw"))


def test_misspelt_scene_name_suggests_the_close_ones(capsys, no_work, tmp_path):
    line = _one_error_line(capsys, cli.main(["validate", "fe-hertz-groove56", "--out", str(tmp_path / "r")]))
    assert "did you mean 'fe-hertz-groove-056'" in line
    line = _one_error_line(capsys, cli.main(["show", "fe-hertz-groove56", "--out", str(tmp_path / "r")]))
    assert "did you mean 'fe-hertz-groove-056'" in line


def test_show_of_an_fe_scene_without_fields_is_wrong_use_not_a_damaged_file(capsys, no_work, tmp_path):
    # sun2021-fe-bem is an FE scene but saves no fields.vtu: 'show' used to start, fail with exit 1 and advise
    # deleting a fields.vtu that never existed
    line = _one_error_line(capsys, cli.main(["show", "sun2021-fe-bem", "--out", str(tmp_path / "r")]))
    assert "saves no fields" in line and "fe-hertz-groove-056" in line and "fe-b2b-linear-a" in line
    assert "sun2021-fe-bem," not in line.split("show draws:")[1]
    assert not (tmp_path / "r").exists()


def test_show_names_the_kind_with_the_right_article(capsys, no_work, tmp_path):
    line = _one_error_line(capsys, cli.main(["show", "hertz-sphere-flat", "--out", str(tmp_path / "r")]))
    assert "is an analytical scene" in line
