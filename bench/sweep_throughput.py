"""Throughput and memory of sweeps (gyrostat.sweep) against the same members through solve_ensemble.

Run:  .venv/bin/python bench/sweep_throughput.py [--members 100000]   (or: bash run.sh bench)

The scene: `forced_damped` (a body under a constant torque and a linear damping) over t = 0..10
with 11 outputs, DOP853 at the scene's tolerances, its initial ω and the damping dispersed
(Normal and LogUniform, seed 1). Rows, all measured in this one run:

* `sweep, default`: `gyrostat.sweep(..., trajectories=False)` as a user calls it: at 10⁵ members
  (at least `sweeps.WORKERS_FROM`) one forked worker process per core, each drawing its chunks'
  members, checking each member's scene entries, building its model and solving the chunk on one
  C++ thread; summaries kept; after a warm-up sweep of 100 members (the process's first Dataset
  imports xarray's duck-array modules, ~1 s);
* `sweep, workers=1`: this process alone: the next chunk's members made on a helper thread while
  the current one is solved on the C++ pool (Python's lock keeps the making to one core);
* `solve_ensemble`: the same members (the same models and initial states, built beforehand and
  not timed) in one `gyrostat.solve_ensemble` call: the engine alone;
* `sweep, Dask LocalCluster`: the sweep with `client=` on a LocalCluster of 2 worker processes
  (one thread each), cluster start-up excluded; its overhead per member against the local pool;
* peak resident memory of a summaries-only sweep streamed to a file (`path=`), in a fresh
  process, at N/10 and N members: it must not grow with N.
"""

from __future__ import annotations

import argparse
import os
import subprocess
import sys
import time
import tomllib
from pathlib import Path

import numpy as np

import gyrostat as g
from gyrostat import sweeps
from gyrostat.sweeps import runners

SCENE = Path(g.__file__).parent / "scenes" / "forced_damped.toml"
VARY = {"initial.omega[0]": g.Normal(1.0, 0.1), "initial.omega[2]": g.Normal(-0.3, 0.1),
        "torques[1].matrix[0][0]": g.LogUniform(1e-3, 1e-1)}


def document() -> dict:
    with open(SCENE, "rb") as handle:
        doc = tomllib.load(handle)
    doc["integration"].update(t_span=[0.0, 10.0], n_out=11)
    return doc


def peak_memory(members: int) -> float:
    """Peak RSS (MiB, VmHWM: ru_maxrss would carry this process's peak across exec) of a fresh
    process running a streamed summaries-only sweep of `members`."""
    script = f"""
import tempfile, os, tomllib
import gyrostat as g
import numpy as np
doc = tomllib.load(open({str(SCENE)!r}, "rb")); doc["integration"].update(t_span=[0.0, 10.0], n_out=11)
vary = {{"initial.omega[0]": g.Normal(1.0, 0.1), "initial.omega[2]": g.Normal(-0.3, 0.1),
        "torques[1].matrix[0][0]": g.LogUniform(1e-3, 1e-1)}}
with tempfile.TemporaryDirectory() as folder:
    ds = g.sweep(doc, vary, samples={members}, seed=1, trajectories=False, progress=False, error_estimate=False,
                 path=os.path.join(folder, "s.nc"), chunk_size=2000)
    ds.close()
print(next(int(line.split()[1]) for line in open("/proc/self/status") if line.startswith("VmHWM")) / 1024)
"""
    out = subprocess.run([sys.executable, "-c", script], check=True, capture_output=True, text=True)
    return float(out.stdout.strip().splitlines()[-1])


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--members", type=int, default=100_000, help="members of the sweep (default: %(default)s)")
    args = parser.parse_args()
    n = args.members
    doc = document()

    g.sweep(doc, VARY, samples=100, seed=2, trajectories=False, progress=False, error_estimate=False)  # warm-up: xarray's first
    # Dataset imports its duck-array modules (dask.array: ~1 s), once per process, not per member
    started = time.perf_counter()
    swept = g.sweep(doc, VARY, samples=n, seed=1, trajectories=False, progress=False, error_estimate=False)
    t_sweep = time.perf_counter() - started
    started = time.perf_counter()
    alone = g.sweep(doc, VARY, samples=n, seed=1, trajectories=False, progress=False, error_estimate=False, workers=1)
    t_alone = time.perf_counter() - started
    identical = alone.drop_attrs().identical(swept.drop_attrs())

    plan = sweeps.Plan(doc, VARY, samples=n, seed=1)
    members = []
    for i in range(n):
        try:
            members.append(plan.member(plan.values(i)))
        except ValueError:
            pass
    run = members[0]
    started = time.perf_counter()
    solutions = g.solve_ensemble([m.model for m in members], [m.y0 for m in members], run.t_span,
                                 check_validity=False, progress=False, error_estimate=False, **run.options)
    t_ensemble = time.perf_counter() - started
    same = np.array_equal(np.array([s.y[-1, 0] for s in solutions]),
                          swept["final_p"].values[swept["status"].values == "success"])

    from distributed import Client, LocalCluster

    dask_members = min(n, 20_000)
    local_small = time.perf_counter()
    g.sweep(doc, VARY, samples=dask_members, seed=1, trajectories=False, progress=False, error_estimate=False, workers=-1)
    local_small = time.perf_counter() - local_small
    with LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None) as cluster, \
            Client(cluster) as client:
        started = time.perf_counter()
        g.sweep(doc, VARY, samples=dask_members, seed=1, trajectories=False, progress=False, error_estimate=False, client=client)
        t_dask = time.perf_counter() - started

    print(f"Sweep of {n} members (forced_damped, t = 0..10, 11 outputs, dop853), summaries only, "
          f"{os.cpu_count()} cores")
    print(f"  sweep, default             {t_sweep:8.3f} s   {n / t_sweep:10.0f} members/s   "
          f"({runners._processes(None, 0, n)} worker processes)")
    print(f"  sweep, workers=1           {t_alone:8.3f} s   {n / t_alone:10.0f} members/s   "
          f"(identical Dataset: {identical})")
    print(f"  solve_ensemble (engine)    {t_ensemble:8.3f} s   {len(members) / t_ensemble:10.0f} members/s   "
          f"(same final p: {same})")
    print(f"  sweep / solve_ensemble     {t_sweep / t_ensemble:8.2f}x  "
          f"(target: at most 2x; workers=1: {t_alone / t_ensemble:.2f}x)")
    print(f"  sweep, Dask LocalCluster   {t_dask:8.3f} s   {dask_members / t_dask:10.0f} members/s   "
          f"({dask_members} members; local workers {local_small:.3f} s; Dask overhead "
          f"{(t_dask - local_small) / dask_members * 1e6:+.1f} us per member)")
    small, large = peak_memory(n // 10), peak_memory(n)
    print(f"  peak memory, streamed      {small:8.1f} MiB at {n // 10} members, {large:.1f} MiB at {n} members")


if __name__ == "__main__":
    main()
