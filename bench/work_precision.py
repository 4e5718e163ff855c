"""Work-precision chart: gyrostat's integrators (the C++ benchmark executable) against SciPy's
solve_ivp (DOP853, RK45, LSODA, Radau, BDF) and heyoka's Taylor integrator, on the same
problems, in one run. Error is the max-norm error of the final state against the reference the
executable prints (the closed form for the torque-free body); time is the best of repeated runs
of one whole trajectory.

    python bench/work_precision.py --bench-exe build/release/gyrostat_bench [--quick]

Writes bench/out/work_precision_<problem>.png, bench/out/rows.csv and prints the ratios at equal
error (log-log interpolation of each method's time against its error).
"""

from __future__ import annotations

import argparse
import csv
import io
import subprocess
import sys
import time
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent


def best_time(run, budget=0.3, min_repeats=3, max_repeats=50):
    best, spent, k = np.inf, 0.0, 0
    while k < max_repeats and (k < min_repeats or spent < budget):
        start = time.perf_counter()
        run()
        elapsed = time.perf_counter() - start
        best, spent, k = min(best, elapsed), spent + elapsed, k + 1
        if elapsed > 5.0:  # slow peers: one run is measurement enough
            break
    return best


def run_executable(exe: str, quick: bool):
    out = subprocess.run([exe] + (["--quick"] if quick else []), check=True, capture_output=True, text=True).stdout
    rows, references, comments = [], {}, []
    for line in out.splitlines():
        if line.startswith("# reference_state"):
            _, _, name, *values = line.split()
            references[name] = np.array([float(v) for v in values])
        elif line.startswith("#"):
            comments.append(line)
        elif line and not line.startswith("problem,"):
            problem, method, rtol, error, steps, nfev, seconds = next(csv.reader(io.StringIO(line)))
            rows.append(dict(problem=problem, method=method, rtol=float(rtol), error=float(error), steps=int(steps),
                             rhs_evals=int(nfev), seconds=float(seconds), source="gyrostat (C++)"))
    return rows, references, comments


def torque_free_problem():
    A = np.array([1.0, 2.0, 3.0])
    y0 = np.array([1.0, 0.5, -0.3])

    def f(t, w):
        p, q, r = w
        return [(A[1] - A[2]) / A[0] * q * r, (A[2] - A[0]) / A[1] * r * p, (A[0] - A[1]) / A[2] * p * q]

    return A, y0, f


def scipy_rows(t1, reference, tolerances, quick):
    from scipy.integrate import solve_ivp

    _, y0, f = torque_free_problem()
    rows = []
    methods = ["DOP853", "RK45", "LSODA", "Radau", "BDF"]
    for method in methods:
        tols = tolerances if method in ("DOP853", "LSODA") else tolerances[: 4 if not quick else 1]
        for rtol in tols:
            result = {}

            def run():
                result["sol"] = solve_ivp(f, (0.0, t1), y0, method=method, rtol=rtol, atol=rtol * 1e-3)

            seconds = best_time(run, budget=0.5, min_repeats=1, max_repeats=3)
            sol = result["sol"]
            if not sol.success:
                continue
            rows.append(dict(problem="torque_free", method=f"scipy_{method}", rtol=rtol,
                             error=float(np.max(np.abs(sol.y[:, -1] - reference))), steps=sol.t.size - 1,
                             rhs_evals=sol.nfev, seconds=seconds, source="SciPy solve_ivp"))
            print(f"  scipy {method} rtol={rtol:g}: {seconds:.3g} s", file=sys.stderr)
    return rows


def heyoka_rows(t1, reference, tolerances):
    try:
        import heyoka as hy
    except ImportError:
        print("heyoka is not installed: skipping it (pip install heyoka)", file=sys.stderr)
        return []
    A, y0, _ = torque_free_problem()
    p, q, r = hy.make_vars("p", "q", "r")
    system = [(p, (A[1] - A[2]) / A[0] * q * r), (q, (A[2] - A[0]) / A[1] * r * p), (r, (A[0] - A[1]) / A[2] * p * q)]
    rows = []
    for tol in tolerances:
        start = time.perf_counter()
        ta = hy.taylor_adaptive(system, list(y0), tol=tol)
        compile_seconds = time.perf_counter() - start

        def run():
            ta.time = 0.0
            ta.state[:] = y0
            ta.propagate_until(t1)

        seconds = best_time(run)
        run()
        steps = ta.propagate_until(t1)  # no-op, kept for symmetry
        del steps
        rows.append(dict(problem="torque_free", method="heyoka_taylor", rtol=tol,
                         error=float(np.max(np.abs(ta.state - reference))), steps=-1, rhs_evals=-1,
                         seconds=seconds, source=f"heyoka (JIT {compile_seconds:.2f} s excluded)"))
    return rows


def time_at_error(rows, error):
    """Time a method needs to reach `error`: log-log interpolation on its work-precision
    envelope (for each measured error, the cheapest run at least that accurate, since a
    method's error need not be monotone in its tolerance); None outside the measured range."""
    pts = sorted((r["error"], r["seconds"]) for r in rows if r["error"] > 0)
    if len(pts) < 2 or not (pts[0][0] <= error <= pts[-1][0]):
        return None
    errors = np.log([p[0] for p in pts])
    envelope = np.log(np.minimum.accumulate([p[1] for p in pts]))
    return float(np.exp(np.interp(np.log(error), errors, envelope)))


def chart(rows, problem, path, title):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(8.5, 5.5))
    methods = sorted({r["method"] for r in rows if r["problem"] == problem})
    colors = plt.cm.tab20(np.linspace(0, 1, 20))
    for index, method in enumerate(methods):
        pts = sorted((r["error"], r["seconds"]) for r in rows if r["problem"] == problem and r["method"] == method
                     and r["error"] > 0)
        if not pts:
            continue
        style = "-o" if not method.startswith(("scipy", "heyoka")) else "--s"
        ax.loglog([p[0] for p in pts], [p[1] for p in pts], style, ms=4, label=method,
                  color=colors[(2 * index) % 20 + (index // 10)])
    ax.set_xlabel("error of the final state (max norm)")
    ax.set_ylabel("time per trajectory [s] (best of repeats)")
    ax.set_title(title)
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=8, ncol=2)
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)


def draw_charts(rows, out: Path) -> None:
    chart(rows, "torque_free", out / "work_precision_torque_free.png",
          "Torque-free triaxial body, 100 periods: work against precision")
    chart(rows, "forced", out / "work_precision_forced.png", "Forced damped gyrostat with attitude, t = 200")
    chart(rows, "stiff", out / "work_precision_stiff.png", "Stiff damping (D = 1e3 I), t = 10")
    chart(rows, "moving_mass", out / "work_precision_moving_mass.png",
          "Explicit moving-mass model (paper 001), Ω² = 2000, λ = 400, t = 20")


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--bench-exe", default=str(HERE.parent / "build" / "bench" / "gyrostat_bench"))
    parser.add_argument("--quick", action="store_true", help="two tolerances only (a smoke run)")
    parser.add_argument("--out", default=str(HERE / "out"))
    parser.add_argument("--replot", metavar="ROWS_CSV", help="only redraw the charts from a rows.csv of an earlier run")
    args = parser.parse_args()
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    if args.replot:
        with open(args.replot) as handle:
            rows = [dict(r, error=float(r["error"]), seconds=float(r["seconds"])) for r in csv.DictReader(handle)]
        draw_charts(rows, out)
        return

    rows, references, comments = run_executable(args.bench_exe, args.quick)
    for c in comments:
        print(c)
    t1 = float(next(c for c in comments if c.startswith("# torque_free")).split("t1 = ")[1].split()[0])
    tolerances = [1e-6, 1e-10] if args.quick else [1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10, 1e-11, 1e-12, 1e-13]
    rows += scipy_rows(t1, references["torque_free"], tolerances, args.quick)
    rows += heyoka_rows(t1, references["torque_free"], tolerances)

    with (out / "rows.csv").open("w", newline="") as handle:
        writer = csv.DictWriter(handle, fieldnames=list(rows[0]))
        writer.writeheader()
        writer.writerows(rows)
    draw_charts(rows, out)

    # Ratios at equal error, anchored at the fastest of gyrostat's integrators at rtol 1e-10 on
    # the torque-free body (the error it reaches there is the "equal error").
    ours = [r for r in rows if r["problem"] == "torque_free" and r["source"].startswith("gyrostat")
            and abs(r["rtol"] - 1e-10) < 1e-16]
    anchor = min(ours, key=lambda r: r["seconds"])
    print(f"\nAt equal error {anchor['error']:.3e} (gyrostat {anchor['method']} at rtol 1e-10, "
          f"{anchor['seconds']:.3e} s per trajectory):")
    print("| method | time at that error [s] | ratio to gyrostat " + anchor["method"] + " |")
    print("| --- | --- | --- |")
    for method in sorted({r["method"] for r in rows if r["problem"] == "torque_free"}):
        t = time_at_error([r for r in rows if r["problem"] == "torque_free" and r["method"] == method], anchor["error"])
        print(f"| {method} | {t:.3e} | {t / anchor['seconds']:.2f} |" if t else f"| {method} | error not reached in the sweep | — |")


if __name__ == "__main__":
    main()
