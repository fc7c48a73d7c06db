"""Measures the Python package against the command line and against SciPy.

1. ``eulerdisk.run`` on the paper's 100 s scene against ``eulerdisk run`` (the same work:
   no figures, no progress, the trajectory written to a folder), and in memory only.
2. Two runs in two Python threads against one: the GIL is released while they simulate.
3. ``Model.solve`` on the heavy top (``model-macros/examples/heavy_top.dsl``, 10 s) against
   SciPy's ``solve_ivp`` on the same equations written in NumPy, DOP853 at the same tolerances.

Each time is the median of ``--repeat`` runs, wall-clock and CPU time of this process (its
children for the command line). Prints Markdown tables for BENCHMARKS.md.

    python python/bench/compare.py --cli target/release/eulerdisk
"""

from __future__ import annotations

import argparse
import math
import os
import resource
import statistics
import subprocess
import tempfile
import threading
import time
from collections.abc import Callable
from pathlib import Path

import numpy as np

import eulerdisk

ROOT = Path(__file__).resolve().parents[2]
HEAVY_TOP = ROOT / "model-macros" / "examples" / "heavy_top.dsl"


def children_cpu() -> float:
    usage = resource.getrusage(resource.RUSAGE_CHILDREN)
    return usage.ru_utime + usage.ru_stime


def measure(
    work: Callable[[], object], repeat: int, cpu: Callable[[], float]
) -> tuple[float, float]:
    """Median wall and CPU seconds of ``work`` over ``repeat`` calls."""
    walls, cpus = [], []
    for _ in range(repeat):
        c0, w0 = cpu(), time.perf_counter()
        work()
        walls.append(time.perf_counter() - w0)
        cpus.append(cpu() - c0)
    return statistics.median(walls), statistics.median(cpus)


def python_vs_cli(cli: Path, repeat: int) -> list[str]:
    with tempfile.TemporaryDirectory() as scratch:
        out = Path(scratch)
        command = [
            str(cli),
            "run",
            "tangent-toy",
            "--no-figures",
            "--quiet",
            "--out",
            str(out / "cli"),
        ]
        cli_wall, cli_cpu = measure(
            lambda: subprocess.run(command, check=True, capture_output=True), repeat, children_cpu
        )
        files_wall, files_cpu = measure(
            lambda: eulerdisk.run("tangent-toy", progress=False, out=out / "py"),
            repeat,
            time.process_time,
        )
        memory_wall, memory_cpu = measure(
            lambda: eulerdisk.run("tangent-toy", progress=False), repeat, time.process_time
        )
    rows = [
        "| 100 s paper scene, no figures | wall (s) | CPU (s) | wall vs CLI |",
        "|---|---:|---:|---:|",
        f"| `eulerdisk run` (CLI, trajectory.csv written) | {cli_wall:.2f} | {cli_cpu:.2f} | 1.00 |",
        f"| `eulerdisk.run(out=...)` (trajectory.csv written) | {files_wall:.2f} | {files_cpu:.2f} | {files_wall / cli_wall:.3f} |",
        f"| `eulerdisk.run()` (arrays in memory only) | {memory_wall:.2f} | {memory_cpu:.2f} | {memory_wall / cli_wall:.3f} |",
    ]
    return rows


def threads(repeat: int) -> list[str]:
    def one() -> None:
        eulerdisk.run("tangent-toy", t_end=20.0, progress=False)

    def two() -> None:
        pair = [threading.Thread(target=one) for _ in range(2)]
        for th in pair:
            th.start()
        for th in pair:
            th.join()

    one_wall, one_cpu = measure(one, repeat, time.process_time)
    two_wall, two_cpu = measure(two, repeat, time.process_time)
    return [
        "| 20 s paper scene | wall (s) | CPU (s) | CPU / wall | runs per wall second |",
        "|---|---:|---:|---:|---:|",
        f"| one run, one thread | {one_wall:.2f} | {one_cpu:.2f} | {one_cpu / one_wall:.2f} | {1 / one_wall:.3f} |",
        f"| two runs, two threads | {two_wall:.2f} | {two_cpu:.2f} | {two_cpu / two_wall:.2f} | {2 / two_wall:.3f} |",
        f"| scaling (runs per second, two threads / one) | | | | {2 * one_wall / two_wall:.2f}x |",
    ]


# The heavy top of heavy_top.dsl, written by hand in NumPy: the momenta p_phi and p_psi are
# conserved, so the angular accelerations follow from differentiating them.
M, G, L, I1, I3 = 0.5, 9.81, 0.04, 0.0012, 0.0009


def heavy_top_rhs(_t: float, y: np.ndarray) -> np.ndarray:
    _phi, th, _psi, wphi, wth, wpsi = y
    s, c = math.sin(th), math.cos(th)
    w3 = wpsi + wphi * c
    # d/dt (I3 w3) = 0 and d/dt (I1 wphi s^2 + I3 w3 c) = 0:
    dwphi = (I3 * w3 * s * wth - 2 * I1 * wphi * s * c * wth) / (I1 * s * s)
    dwth = (I1 * wphi**2 * s * c - I3 * w3 * wphi * s + M * G * L * s) / I1
    dwpsi = -(dwphi * c - wphi * s * wth)
    return np.array([wphi, wth, wpsi, dwphi, dwth, dwpsi])


def dsl_vs_scipy(repeat: int) -> list[str]:
    from scipy.integrate import solve_ivp

    rtol, atol, t_end = 1e-8, 1e-10, 10.0
    start = {"theta": 0.3, "w_psi": 150.0, "w_phi": 2.0}
    top = eulerdisk.Model.from_file(HEAVY_TOP)
    y0 = np.array([start.get(name, 0.0) for name in top.states])
    solved: dict[str, object] = {}

    def ours() -> None:
        solved["ours"] = top.solve(t_end, state=start, method="dop853", rtol=rtol, atol=atol)

    def theirs() -> None:
        solved["scipy"] = solve_ivp(
            heavy_top_rhs, (0.0, t_end), y0, method="DOP853", rtol=rtol, atol=atol
        )

    compile_wall, _ = measure(
        lambda: eulerdisk.Model.from_file(HEAVY_TOP), repeat, time.process_time
    )
    our_wall, our_cpu = measure(ours, repeat, time.process_time)
    their_wall, their_cpu = measure(theirs, repeat, time.process_time)
    a = solved["ours"]
    b = solved["scipy"]
    ours_end = np.array([a[name][-1] for name in top.states])
    gap = np.max(np.abs(ours_end - b.y[:, -1]))
    return [
        f"| heavy top, 10 s, DOP853, rtol {rtol:g}, atol {atol:g} | wall (ms) | CPU (ms) | steps | RHS evaluations |",
        "|---|---:|---:|---:|---:|",
        f"| `Model.from_file` (compile the DSL file) | {compile_wall * 1e3:.1f} | | | |",
        f"| `Model.solve` (interpreted DSL) | {our_wall * 1e3:.1f} | {our_cpu * 1e3:.1f} | {a.stats['steps']} | {a.stats['rhs_evals']} |",
        f"| `scipy.integrate.solve_ivp` (NumPy) | {their_wall * 1e3:.1f} | {their_cpu * 1e3:.1f} | {len(b.t) - 1} | {b.nfev} |",
        f"| speed-up | {their_wall / our_wall:.1f}x | {their_cpu / our_cpu:.1f}x | | |",
        "",
        f"Largest difference of the final states: {gap:.2e}.",
    ]


def solve_many_vs_loop(repeat: int) -> list[str]:
    """``Model.solve_many`` on every core against a loop of single solves, heavy top."""
    top = eulerdisk.Model.from_file(HEAVY_TOP)
    y0 = np.zeros((16, len(top.states)))
    y0[:, top.states.index("theta")] = 0.3
    y0[:, top.states.index("w_phi")] = 2.0
    y0[:, top.states.index("w_psi")] = np.linspace(100.0, 200.0, 16)

    def loop() -> None:
        for row in y0:
            top.solve(10.0, y0=row, t_eval=0.01)

    def many() -> None:
        top.solve_many(10.0, y0=y0, t_eval=0.01)

    loop_wall, loop_cpu = measure(loop, repeat, time.process_time)
    many_wall, many_cpu = measure(many, repeat, time.process_time)
    cores = os.cpu_count()
    return [
        "| heavy top, 10 s, 16 spins, DOP853 | wall (s) | CPU (s) | CPU / wall |",
        "|---|---:|---:|---:|",
        f"| a loop of `Model.solve` | {loop_wall:.2f} | {loop_cpu:.2f} | {loop_cpu / loop_wall:.2f} |",
        f"| `Model.solve_many` ({cores} workers) | {many_wall:.2f} | {many_cpu:.2f} | {many_cpu / many_wall:.2f} |",
        f"| speed-up | {loop_wall / many_wall:.2f}x | | |",
    ]


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--cli", type=Path, default=ROOT / "target" / "release" / "eulerdisk")
    parser.add_argument("--repeat", type=int, default=3)
    args = parser.parse_args()
    print(f"machine: {os.cpu_count()} cores, load average {os.getloadavg()[0]:.2f}\n")
    for table in (
        python_vs_cli(args.cli, args.repeat),
        threads(args.repeat),
        dsl_vs_scipy(5 * args.repeat),
        solve_many_vs_loop(args.repeat),
    ):
        print("\n".join(table), end="\n\n")


if __name__ == "__main__":
    main()
