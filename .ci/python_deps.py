"""Prints the Python package's requirements with its `test` extra, one per line.

CI installs them into the package's virtual environment while the Rust build runs (the
downloads need no CPU), so that installing the package later builds only the package. They
are read from `python/pyproject.toml`, so the two lists cannot drift apart; the build
backend is among them, because the package is then built without build isolation.
"""

from __future__ import annotations

import tomllib
from pathlib import Path

PYPROJECT = Path(__file__).resolve().parent.parent / "python" / "pyproject.toml"


def requirements() -> list[str]:
    """The build backend, the run-time dependencies and the `test` extra."""
    project = tomllib.loads(PYPROJECT.read_text())
    return [
        *project["build-system"]["requires"],
        *project["project"]["dependencies"],
        *project["project"]["optional-dependencies"]["test"],
    ]


if __name__ == "__main__":
    print("\n".join(requirements()))
