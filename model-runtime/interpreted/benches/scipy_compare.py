"""A model read from a file by ``eulerdisk model solve`` against SciPy's ``solve_ivp`` with a
NumPy right-hand side: the same method (DOP853) at the same tolerances (rtol 1e-8, atol 1e-10).

1. The 20-link pendulum chain (``model-macros/examples/pendulum_chain.dsl``, 40 states) for 5 s
   from a bent chain at rest: SciPy's solve alone against ``model solve``'s whole process
   (reading the file, compiling it, solving, writing the CSV), with an empty cache of compiled
   models (cold) and with the file already in it (warm), and warm with ``--no-jit``.
2. The heavy top (``model-macros/examples/heavy_top.dsl``) for 1 s sampled at 10^6 + 1 times:
   SciPy with ``t_eval`` against the whole ``model solve --dt 1e-6`` process (CSV written).

Each time is the median of ``--repeat`` runs, wall clock and CPU time (SciPy's: this process's;
the command line's: its own, as a child of this process); on a shared machine the CPU times are
the ones to compare. The cache lives in a temporary folder
(``XDG_CACHE_HOME``), so the user's is never touched. Prints Markdown tables for
BENCHMARKS.md, section "Models read at run time".

    python3 -m venv target/venv && target/venv/bin/pip install numpy scipy
    cargo build --release --bin eulerdisk
    target/venv/bin/python model-runtime/interpreted/benches/scipy_compare.py --cli target/release/eulerdisk
"""

from __future__ import annotations

import argparse
import math
import os
import resource
import statistics
import subprocess
import tempfile
import time
from collections.abc import Callable
from pathlib import Path

import numpy as np
from scipy.integrate import solve_ivp

ROOT = Path(__file__).resolve().parents[3]
CHAIN = ROOT / "model-macros" / "examples" / "pendulum_chain.dsl"
HEAVY_TOP = ROOT / "model-macros" / "examples" / "heavy_top.dsl"
RTOL, ATOL = 1e-8, 1e-10
LINKS = 20


def children_cpu() -> float:
    usage = resource.getrusage(resource.RUSAGE_CHILDREN)
    return usage.ru_utime + usage.ru_stime


def median_of(
    work: Callable[[], object], repeat: int, cpu: Callable[[], float] = children_cpu
) -> tuple[float, float]:
    """Median wall and CPU seconds of ``work`` (CPU: of this process's children, or ``cpu``)."""
    walls, cpus = [], []
    for _ in range(repeat):
        c0, w0 = cpu(), time.perf_counter()
        work()
        walls.append(time.perf_counter() - w0)
        cpus.append(cpu() - c0)
    return statistics.median(walls), statistics.median(cpus)


# The chain as the file writes it: with c_ij = 21 - max(i, j) (1-based),
# sum_j c_ij cos(q_i - q_j) a_j = -sum_j c_ij sin(q_i - q_j) w_j^2 - (g / l) c_ii sin(q_i).
_index = np.arange(1, LINKS + 1)
C = (LINKS + 1 - np.maximum.outer(_index, _index)).astype(float)
G_OVER_L = 9.81


def chain_rhs(_t: float, y: np.ndarray) -> np.ndarray:
    q, w = y[:LINKS], y[LINKS:]
    d = q[:, None] - q[None, :]
    mass = C * np.cos(d)
    force = -(C * np.sin(d)) @ (w * w) - G_OVER_L * np.diag(C) * np.sin(q)
    return np.concatenate([w, np.linalg.solve(mass, force)])


def chain_start() -> dict[str, float]:
    """A bent chain at rest: link i at 0.6 sin(i) from the vertical."""
    return {f"q{i}": 0.6 * math.sin(i) for i in range(1, LINKS + 1)}


# The heavy top of heavy_top.dsl in NumPy (the momenta p_phi and p_psi are conserved).
M, G, L, I1, I3 = 0.5, 9.81, 0.04, 0.0012, 0.0009


def heavy_top_rhs(_t: float, y: np.ndarray) -> np.ndarray:
    _phi, th, _psi, wphi, wth, wpsi = y
    s, c = math.sin(th), math.cos(th)
    w3 = wpsi + wphi * c
    dwphi = (I3 * w3 * s * wth - 2 * I1 * wphi * s * c * wth) / (I1 * s * s)
    dwth = (I1 * wphi**2 * s * c - I3 * w3 * wphi * s + M * G * L * s) / I1
    dwpsi = -(dwphi * c - wphi * s * wth)
    return np.array([wphi, wth, wpsi, dwphi, dwth, dwpsi])


def model_solve(cli: Path, cache: Path, out: Path, args: list[str]) -> Callable[[], None]:
    env = dict(os.environ, XDG_CACHE_HOME=str(cache))
    command = [str(cli), "model", "solve", *args, "--out", str(out)]
    return lambda: subprocess.run(command, check=True, capture_output=True, env=env)


def chain(cli: Path, repeat: int, scratch: Path) -> list[str]:
    start = chain_start()
    y0 = np.array([start.get(f"q{i}", 0.0) for i in range(1, LINKS + 1)] + [0.0] * LINKS)
    solved = {}

    def scipy() -> None:
        solved["scipy"] = solve_ivp(
            chain_rhs, (0.0, 5.0), y0, method="DOP853", rtol=RTOL, atol=ATOL
        )

    scipy_wall, scipy_cpu = median_of(scipy, repeat, time.process_time)
    nfev = solved["scipy"].nfev
    args = [str(CHAIN), "--t-end", "5"]
    for name, value in start.items():
        args += ["--state", f"{name}={value!r}"]
    out = scratch / "chain.csv"
    rows = []
    for label, flags, cold in [
        ("cold cache (compiled, cache written)", [], True),
        ("warm cache", [], False),
        ("warm cache, `--no-jit`", ["--no-jit"], False),
    ]:
        walls, cpus = [], []
        for k in range(repeat):
            cache = scratch / (f"cold{k}" if cold else "warm")
            run = model_solve(cli, cache, out, args + flags)
            if not cold and not cache.exists():
                run()  # fills the cache
            wall, cpu = median_of(run, 1)
            walls.append(wall)
            cpus.append(cpu)
        wall, cpu = statistics.median(walls), statistics.median(cpus)
        rows.append(
            f"| `model solve`, whole process, {label} | {wall:.3f} | {cpu:.3f} | {wall / scipy_wall:.2f} | {cpu / scipy_cpu:.2f} |"
        )
    ours = np.loadtxt(out, delimiter=",", skiprows=1)
    gap = np.max(np.abs(ours[-1, 1 : 1 + 2 * LINKS] - solved["scipy"].y[:, -1]))
    return [
        "| 20-link chain, 5 s, DOP853 | wall (s) | CPU (s) | wall / SciPy | CPU / SciPy |",
        "|---|---:|---:|---:|---:|",
        f"| SciPy `solve_ivp` alone ({nfev} RHS, {scipy_cpu / nfev * 1e6:.0f} µs of CPU each) | {scipy_wall:.3f} | {scipy_cpu:.3f} | 1.00 | 1.00 |",
        *rows,
        "",
        f"Largest difference of the final states: {gap:.1e}.",
    ]


def in_process(bench: Path) -> float:
    """The median CPU seconds the ``dense_samples`` bench binary prints for its solves."""
    out = subprocess.run([str(bench)], check=True, capture_output=True, text=True).stdout
    return float(out.split("samples: ")[1].split(" s")[0])


def dense(cli: Path, repeat: int, scratch: Path, bench: Path | None) -> list[str]:
    y0 = np.array([0.0, 0.3, 0.0, 2.0, 0.0, 150.0])
    times = np.linspace(0.0, 1.0, 1_000_001)

    def scipy() -> None:
        solve_ivp(
            heavy_top_rhs, (0.0, 1.0), y0, method="DOP853", rtol=RTOL, atol=ATOL, t_eval=times
        )

    scipy_wall, scipy_cpu = median_of(scipy, repeat, time.process_time)
    cache = scratch / "warm"
    run = model_solve(cli, cache, scratch / "top.csv", [str(HEAVY_TOP), "--t-end", "1", "--dt", "1e-6"])
    run()  # fills the cache
    wall, cpu = median_of(run, repeat)
    rows = [
        "| heavy top, 1 s, 10^6 + 1 samples | wall (s) | CPU (s) | wall / SciPy | CPU / SciPy |",
        "|---|---:|---:|---:|---:|",
        f"| SciPy `solve_ivp(t_eval=...)` alone | {scipy_wall:.3f} | {scipy_cpu:.3f} | 1.00 | 1.00 |",
    ]
    if bench is not None:
        # The bench binary's own median, then SciPy's again: the two sides at the same moment.
        solve = in_process(bench)
        _, after = median_of(scipy, repeat, time.process_time)
        rows.append(
            f"| `solve` in process (`--bench dense_samples`, median of 7) | | {solve:.3f} | | {solve / scipy_cpu:.2f} |"
        )
        rows.append(f"| SciPy again, after it | | {after:.3f} | | {after / scipy_cpu:.2f} |")
    rows.append(
        f"| `model solve --dt 1e-6`, whole process, CSV written, warm cache | {wall:.3f} | {cpu:.3f} | {wall / scipy_wall:.2f} | {cpu / scipy_cpu:.2f} |"
    )
    return rows


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--cli", type=Path, default=ROOT / "target" / "release" / "eulerdisk")
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument(
        "--bench",
        type=Path,
        help="the dense_samples bench binary (cargo bench -p model-interpreted --bench dense_samples --no-run prints it), timed between two SciPy runs",
    )
    parser.add_argument("--only-dense", action="store_true", help="skip the chain")
    args = parser.parse_args()
    print(f"machine: {os.cpu_count()} cores, load average {os.getloadavg()[0]:.2f}\n")
    with tempfile.TemporaryDirectory() as scratch:
        if not args.only_dense:
            print("\n".join(chain(args.cli, args.repeat, Path(scratch))), end="\n\n")
        print("\n".join(dense(args.cli, args.repeat, Path(scratch), args.bench)), end="\n\n")


if __name__ == "__main__":
    main()
