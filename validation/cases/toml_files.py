"""TOML spec files of ``ballbench sweep`` and ``ballbench calibrate``: reading with errors that name the file."""
from __future__ import annotations

import tomllib
from pathlib import Path


def read_toml(path: str | Path) -> dict:
    """The table of the TOML file ``path``; ValueError naming the file if it is missing or not valid TOML."""
    path = Path(path)
    try:
        return tomllib.loads(path.read_text())
    except FileNotFoundError:
        raise ValueError(f"{path}: no such file") from None
    except IsADirectoryError:
        raise ValueError(f"{path} is a folder; give a TOML file") from None
    except UnicodeDecodeError:
        raise ValueError(f"{path}: not a text file (TOML)") from None
    except OSError as error:
        raise ValueError(f"{path}: cannot read: {error.strerror or error}") from None
    except tomllib.TOMLDecodeError as error:
        raise ValueError(f"{path}: not valid TOML: {error}") from None
