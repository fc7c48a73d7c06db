"""Checks that CI's build of the Python package can reuse the workspace's compiled crates.

CI builds the package into the workspace's `target/` after `cargo test --workspace`. Cargo
reuses a compiled crate only when it is built with the same features (and the same features
of everything below it), so one crate whose features differ between the two builds makes
every crate above it compile a second time: a differing `syn` feature once rebuilt almost
the whole graph. This compares, crate by crate, the features the two builds resolve, and
names every crate of the package's build whose features the workspace's build does not have.
The package is a member of the workspace, so this holds for the workspace's own crates too.
"""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent


def resolved(cwd: Path, *args: str) -> dict[str, set[str]]:
    """Every crate (`name vX.Y.Z`) of a build and the feature sets it is built with."""
    out = subprocess.run(
        [
            os.environ.get("CARGO", "cargo"),
            "tree",
            "--locked",
            "-f",
            "{p}|{f}",
            "--prefix",
            "none",
            *args,
        ],
        cwd=cwd,
        check=True,
        capture_output=True,
        text=True,
    ).stdout
    crates: dict[str, set[str]] = {}
    for line in out.splitlines():
        if "|" not in line:
            continue
        package, features = line.removesuffix(" (*)").split("|", 1)
        name = " ".join(package.split()[:2])  # drop a path crate's `(path)`
        crates.setdefault(name, set()).add(features)
    return crates


def main() -> int:
    workspace = resolved(ROOT, "--workspace", "-e", "normal,build,dev")
    package = resolved(ROOT, "-p", "eulerdisk-python", "-e", "normal,build")
    differing = [
        f"{name}: package {sorted(features - workspace[name])}, workspace {sorted(workspace[name])}"
        for name, features in sorted(package.items())
        if name in workspace and not features <= workspace[name]
    ]
    if differing:
        print(
            "crates the Python package builds with features the workspace's tests do not "
            "(pin them in python/Cargo.toml or the workspace):",
            file=sys.stderr,
        )
        print("\n".join(f"  {d}" for d in differing), file=sys.stderr)
        return 1
    shared = sum(1 for name in package if name in workspace)
    print(f"the Python package's {shared} shared crates have the workspace's features")
    return 0


if __name__ == "__main__":
    sys.exit(main())
