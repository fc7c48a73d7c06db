"""Shared paths of the test suite: the repository's scenes and model files."""

from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]


@pytest.fixture
def root() -> Path:
    """The repository's top folder."""
    return ROOT


@pytest.fixture
def dsl_examples() -> Path:
    """The DSL's example model files."""
    return ROOT / "model-macros" / "examples"
