"""SIMD batch ensembles against heyoka's batch mode, at equal error, in one run.

    PYTHONPATH=python python bench/batch_ensemble.py [--members 1024] [--out bench/results] [--quick]
    GYROSTAT_SIMD=avx2 python bench/batch_ensemble.py --quick --heyoka-width 4   # an AVX2 machine's forms

Problem (issue 12): the torque-free body I = (2, 3, 4), N members with ω0 uniform in [−1, 1]³
(seed 1), t = 200, outputs at t0 and t1 only. Error: the largest over the members of
|ω(t1) − ω_exact(t1)| / |ω0|, ω_exact from the closed form (gyrostat.torque_free, accurate to
1e-15 at these times: issue 13). Times: best of 3, all in this one run.

Rows:
* gyrostat `solve_ensemble` with taylor and dop853, batch on and off, 1 and 2 threads, timed
  through the engine's own entry point `gyrostat._core.solve_ensemble` (what heyoka is timed on:
  its C++ core; the Python Solution objects of `gyrostat.solve_ensemble` are not part of the
  integration and cost about 2 µs per member);
* heyoka `taylor_adaptive_batch` (SIMD width `hy.recommended_simd_size()`), one thread: the
  members W at a time through one batch integrator (JIT compilation excluded);
* heyoka on every core: one batch integrator per thread (Python threads; heyoka releases the GIL
  while it propagates), against gyrostat with as many threads.

Prints the ratios at equal error (log-log interpolation of time against error on each method's
work-precision envelope) and draws bench/results/batch_ensemble.png (work-precision; throughput
against the number of members at the tolerance where the two reach heyoka's error at tol 1e-12).
"""

from __future__ import annotations

import argparse
import os
import sys
import time
from pathlib import Path

import numpy as np

import gyrostat as g
from gyrostat import _core

HERE = Path(__file__).resolve().parent
J = np.array([2.0, 3.0, 4.0])
T1 = 200.0


def best_time(run, repeats=3):
    best = np.inf
    for _ in range(repeats):
        start = time.perf_counter()
        run()
        best = min(best, time.perf_counter() - start)
    return best


def starts(n, seed=1):
    return np.random.default_rng(seed).uniform(-1.0, 1.0, size=(n, 3))


def exact(y0s):
    body = g.Body(J)
    return np.array([g.torque_free(body, w, [0.0, T1]).y[-1] for w in y0s])


def error(final, y0s, reference):
    return float(np.max(np.linalg.norm(final - reference, axis=1) / np.linalg.norm(y0s, axis=1)))


def gyrostat_run(y0s, method, rtol, batch, threads):
    model = g.Model(g.Body(J))
    core = model._core
    opts = _core.Options()
    opts.method, opts.rtol, opts.atol, opts.n_out = method, rtol, rtol * 1e-3, 0
    opts.max_steps = 10**8

    def run():
        return _core.solve_ensemble([core], y0s, 0.0, T1, opts, threads, None, batch=batch)

    results = run()
    if not all(r.status == "success" for r in results):
        raise RuntimeError(f"gyrostat {method} rtol {rtol}: {results[0].message}")
    final = np.array([np.asarray(r.y)[-1] for r in results])
    return best_time(run), final


HEYOKA_WIDTH = 0
"""heyoka's batch width (0: ``hy.recommended_simd_size()``; ``--heyoka-width 4`` stands for an AVX2 machine's)."""


def heyoka_batch(y0s, tol, ensemble=False):
    import heyoka as hy

    p, q, r = hy.make_vars("p", "q", "r")
    system = [(p, (J[1] - J[2]) / J[0] * q * r), (q, (J[2] - J[0]) / J[1] * r * p), (r, (J[0] - J[1]) / J[2] * p * q)]
    W = HEYOKA_WIDTH or hy.recommended_simd_size()
    n = len(y0s)
    if n % W:
        raise ValueError(f"{n} members: give a multiple of heyoka's SIMD width {W}")
    ta = hy.taylor_adaptive_batch(system, np.zeros((3, W)), tol=tol)
    final = np.empty_like(y0s)

    def one_thread():
        for b in range(n // W):
            ta.set_time(0.0)
            ta.state[:] = y0s[b * W:(b + 1) * W].T
            ta.propagate_until(T1)
            final[b * W:(b + 1) * W] = ta.state.T

    # every core: one batch integrator per thread (copied once, outside the timing), each thread
    # taking every cores-th batch; heyoka releases the GIL while it propagates. (heyoka's own
    # ensemble_propagate_until_batch deep-copies the integrator for every batch: measured 5-10x
    # slower than this at these sizes, so it would flatter us.)
    from concurrent.futures import ThreadPoolExecutor

    cores = os.cpu_count() or 1
    copies = [ta] + [ta.__deepcopy__({}) for _ in range(cores - 1)]

    def share(k):
        integrator = copies[k]
        for b in range(k, n // W, cores):
            integrator.set_time(0.0)
            integrator.state[:] = y0s[b * W:(b + 1) * W].T
            integrator.propagate_until(T1)
            final[b * W:(b + 1) * W] = integrator.state.T

    pool = ThreadPoolExecutor(cores)

    def every_core():
        list(pool.map(share, range(cores)))

    run = every_core if ensemble else one_thread
    run()
    return best_time(run), final.copy(), W


def envelope(rows):
    """(error, time) pairs, for each error the cheapest run at least that accurate."""
    rows = sorted(rows, key=lambda r: r[0])
    out, best = [], np.inf
    for e, s in rows:
        best = min(best, s)
        out.append((e, best))
    return out


def time_at(rows, target):
    env = envelope(rows)
    errs = np.log([e for e, _ in env])
    times = np.log([s for _, s in env])
    order = np.argsort(errs)
    errs, times = errs[order], times[order]
    x = np.log(target)
    if x < errs[0] or x > errs[-1]:
        return None
    return float(np.exp(np.interp(x, errs, times)))


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--members", type=int, default=1024)
    parser.add_argument("--out", type=Path, default=HERE / "out")
    parser.add_argument("--quick", action="store_true", help="fewer tolerances and no throughput sweep")
    parser.add_argument("--heyoka-width", type=int, default=0,
                        help="heyoka's batch width (default: its recommended SIMD size; 4 with GYROSTAT_SIMD=avx2 "
                             "stands for an AVX2 machine)")
    args = parser.parse_args(argv)
    global HEYOKA_WIDTH
    HEYOKA_WIDTH = args.heyoka_width
    try:
        import heyoka as hy  # noqa: F401
    except ImportError:
        sys.exit("heyoka is not installed: pip install heyoka (or the 'bench' extra)")
    cores = os.cpu_count() or 1
    y0s = starts(args.members)
    reference = exact(y0s)
    print(f"gyrostat SIMD lanes: {g.simd_lanes} ({g.simd_instruction_set}); members {args.members}, t = {T1:g}, "
          f"{cores} cores")
    tols = [1e-8, 1e-10, 1e-12, 1e-14] if args.quick else [1e-8, 1e-9, 1e-10, 1e-11, 1e-12, 1e-13, 1e-14]
    curves = {}

    def add(label, seconds, final, tol):
        e = error(final, y0s, reference)
        curves.setdefault(label, []).append((e, seconds, tol))
        print(f"  {label:34s} tol {tol:7.0e}  error {e:9.2e}  {seconds * 1e3:9.2f} ms  "
              f"({seconds / args.members * 1e6:7.2f} µs per member)")

    for tol in tols:
        s, f, W = heyoka_batch(y0s, tol)
        add(f"heyoka batch (W={W}), 1 thread", s, f, tol)
        s, f = gyrostat_run(y0s, "taylor", tol, True, 1)
        add("gyrostat taylor batch, 1 thread", s, f, tol)
        s, f = gyrostat_run(y0s, "taylor", tol, False, 1)
        add("gyrostat taylor scalar, 1 thread", s, f, tol)
        if tol >= 1e-13:
            s, f = gyrostat_run(y0s, "dop853", tol, True, 1)
            add("gyrostat dop853 batch, 1 thread", s, f, tol)
            s, f = gyrostat_run(y0s, "dop853", tol, False, 1)
            add("gyrostat dop853 scalar, 1 thread", s, f, tol)
        if cores > 1:
            s, f, _ = heyoka_batch(y0s, tol, ensemble=True)
            add(f"heyoka batch, {cores} threads", s, f, tol)
            s, f = gyrostat_run(y0s, "taylor", tol, True, cores)
            add(f"gyrostat taylor batch, {cores} threads", s, f, tol)

    print("\nAt equal error (time / heyoka batch's time at the error heyoka reaches at each tol):")
    pairs = [("gyrostat taylor batch, 1 thread", f"heyoka batch (W={W}), 1 thread"),
             ("gyrostat taylor scalar, 1 thread", f"heyoka batch (W={W}), 1 thread"),
             ("gyrostat dop853 batch, 1 thread", f"heyoka batch (W={W}), 1 thread")]
    if cores > 1:
        pairs.append((f"gyrostat taylor batch, {cores} threads", f"heyoka batch, {cores} threads"))
    for ours, theirs in pairs:
        cells = []
        for e, s, tol in curves[theirs]:
            t = time_at([(x, y) for x, y, _ in curves[ours]], e)
            cells.append(f"{tol:.0e}: " + ("  —  " if t is None else f"{t / s:5.2f}"))
        print(f"  {ours:34s} " + "  ".join(cells))

    if not args.quick:
        throughput(args, curves, W, cores)
    chart(args.out, curves, None if args.quick else THROUGHPUT)


THROUGHPUT: dict = {}


def throughput(args, curves, W, cores):
    """Members per second against N, at heyoka's tol 1e-12 and gyrostat's rtol of equal error."""
    heyoka_error = next(e for e, _, tol in curves[f"heyoka batch (W={W}), 1 thread"] if tol == 1e-12)
    ours = sorted(curves["gyrostat taylor batch, 1 thread"], key=lambda r: r[0])
    rtol = next((tol for e, _, tol in sorted(ours, key=lambda r: -r[2]) if e <= heyoka_error), 1e-14)
    print(f"\nThroughput: heyoka tol 1e-12 (error {heyoka_error:.2e}) and gyrostat taylor at rtol {rtol:.0e} "
          f"(the loosest reaching it)")
    for n in [8, 32, 128, 512, 2048, 8192]:
        y0s = starts(n, seed=2)
        row = {}
        row["heyoka batch, 1 thread"] = n / heyoka_batch(y0s, 1e-12)[0]
        row["gyrostat batch, 1 thread"] = n / gyrostat_run(y0s, "taylor", rtol, True, 1)[0]
        row["gyrostat scalar, 1 thread"] = n / gyrostat_run(y0s, "taylor", rtol, False, 1)[0]
        if cores > 1:
            row[f"heyoka batch, {cores} threads"] = n / heyoka_batch(y0s, 1e-12, ensemble=True)[0]
            row[f"gyrostat batch, {cores} threads"] = n / gyrostat_run(y0s, "taylor", rtol, True, cores)[0]
        THROUGHPUT[n] = row
        print(f"  N = {n:5d}: " + ", ".join(f"{k} {v:,.0f}/s" for k, v in row.items()))


def chart(out: Path, curves, throughput_rows):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    out.mkdir(parents=True, exist_ok=True)
    fig, axes = plt.subplots(1, 2 if throughput_rows else 1, figsize=(12 if throughput_rows else 6.5, 4.8), squeeze=False)
    ax = axes[0][0]
    for label, rows in curves.items():
        rows = sorted(rows, key=lambda r: r[2], reverse=True)
        ax.loglog([r[0] for r in rows], [r[1] for r in rows], "--s" if label.startswith("heyoka") else "-o", label=label,
                  markersize=4)
    ax.set_xlabel("error at t = 200 (max over members of |Δω| / |ω0|)")
    ax.set_ylabel("time for the ensemble [s]")
    ax.set_title(f"torque-free ensemble, I = (2, 3, 4), SIMD lanes {g.simd_lanes} ({g.simd_instruction_set})")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    if throughput_rows:
        ax = axes[0][1]
        ns = sorted(throughput_rows)
        for key in throughput_rows[ns[0]]:
            ax.loglog(ns, [throughput_rows[n][key] for n in ns], "--s" if key.startswith("heyoka") else "-o", label=key,
                      markersize=4)
        ax.set_xlabel("members N")
        ax.set_ylabel("members per second [1/s]")
        ax.set_title("throughput at equal error (heyoka tol 1e-12)")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(out / "batch_ensemble.png", dpi=120)
    print(f"wrote {out / 'batch_ensemble.png'}")


if __name__ == "__main__":
    main()
