"""Helpers shared by the command-line tests (test_harness.py, test_sweep.py, test_cli_audit.py)."""
from __future__ import annotations


def one_error_line(capsys, code) -> str:
    """The one ``ballbench: error: ...`` line of a wrong use (exit code 2, no traceback)."""
    captured = capsys.readouterr()
    lines = [x for x in captured.err.splitlines() if x.strip()]
    assert code == 2, captured
    assert len(lines) == 1 and lines[0].startswith("ballbench: error: "), lines
    assert "Traceback" not in captured.err + captured.out
    return lines[0]


def helper_module(tmp_path, monkeypatch, name: str, source: str):
    """Write ``source`` as module ``name`` into ``tmp_path/helpers`` and put that folder on sys.path (sweep specs
    name their function as ``module:function``); returns the folder."""
    directory = tmp_path / "helpers"
    directory.mkdir(exist_ok=True)
    (directory / f"{name}.py").write_text(source)
    monkeypatch.syspath_prepend(str(directory))
    return directory
