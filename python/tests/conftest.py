"""Shared paths of the test suite: the repository's scenes and model files."""

from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]


@pytest.fixture(autouse=True)
def cache_home(tmp_path_factory: pytest.TempPathFactory, monkeypatch: pytest.MonkeyPatch) -> Path:
    """A cache folder of the test's own (``XDG_CACHE_HOME``): no test reads or writes the
    user's cache of compiled models."""
    home = tmp_path_factory.mktemp("cache")
    monkeypatch.setenv("XDG_CACHE_HOME", str(home))
    return home


@pytest.fixture
def root() -> Path:
    """The repository's top folder."""
    return ROOT


@pytest.fixture
def dsl_examples() -> Path:
    """The DSL's example model files."""
    return ROOT / "model-macros" / "examples"
