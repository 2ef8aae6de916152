"""Folders the tests read: the repository root, and the stored test data and baseline images."""
from pathlib import Path

TESTS = Path(__file__).resolve().parent
ROOT = TESTS.parent
DATA = TESTS / "data"
BASELINE_IMAGES = TESTS / "baseline_images"
