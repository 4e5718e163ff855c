"""A user's torque against the built-in one: the cost of gyrostat.CustomTorque on a 512-member ensemble.

Run:  PYTHONPATH=python .venv/bin/python bench/custom_torque.py   (needs a C compiler: it builds
tests/user_torques/drag.c, the compiled torque, on first use)

Rows (best of 5 rounds, each round running every compiled row once; one machine, one run, this
machine is shared and noisy):
* `LinearDamping (built-in)`: M = -c omega as the library's own torque, 512 torque-free-like members
  (moments (1, 2, 2.5), omega0 drawn once), t = 0..200, DOP853 at rtol 1e-10, 11 outputs each,
  every core, SIMD batches as the default (`batch=True`) and one member at a time (`batch=False`).
* `CustomTorque, compiled`: the same M = -c omega written in C (`linear_drag` in drag.c, c through
  the LowLevelCallable's user_data), called from C++ without the GIL on every thread; its members
  run one at a time (the scalar signature has no batch).
* `CustomTorque, compiled vectorised, SIMD batches`: the same in C with the vectorised signature
  (`linear_drag_lanes`: n members at once, structure of arrays), which the batches call once per
  DOP853 stage for their lanes.
* `CustomTorque, Python`: the same in NumPy, each call holding the GIL (the slow path), on 32
  members, scaled to 512; and its cost per call.
The goal: the compiled torque at most 2x the built-in's time (both in SIMD batches: the
vectorised row against the first). Every row ends at the same states to rounding (checked here).
"""

from __future__ import annotations

import sys
import time
from pathlib import Path

import numpy as np

import gyrostat as g

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests"))
import user_torques as user  # noqa: E402

C = 0.02
MEMBERS = 512
OPTIONS = dict(method="dop853", rtol=1e-10, atol=1e-12, n_out=11)


def best(call, repeats: int = 3) -> float:
    times = []
    for _ in range(repeats):
        started = time.perf_counter()
        call()
        times.append(time.perf_counter() - started)
    return min(times)


def best_interleaved(calls: dict, rounds: int = 5) -> dict:
    """The best time of each call over `rounds` rounds, each round running every call once: on a
    shared machine a burst of load then touches every row alike, not one row's repeats."""
    times = {name: [] for name in calls}
    for _ in range(rounds):
        for name, call in calls.items():
            started = time.perf_counter()
            call()
            times[name].append(time.perf_counter() - started)
    return {name: min(values) for name, values in times.items()}


def main() -> None:
    body = g.Body([1.0, 2.0, 2.5])
    y0s = np.random.default_rng(1).normal(size=(MEMBERS, 3))
    builtin = g.Model(body, [g.LinearDamping(C * np.eye(3))])
    compiled = g.Model(body, [g.CustomTorque(user.compiled_linear(C))])
    vectorised = g.Model(body, [g.CustomTorque(user.compiled_linear(C, vectorised=True))])
    numpy_linear = lambda t, w: -C * w  # noqa: E731
    tuple_linear = lambda t, w: (-C * w[0], -C * w[1], -C * w[2])  # noqa: E731
    python = g.Model(body, [g.CustomTorque(numpy_linear, name="numpy_linear")])
    python_tuple = g.Model(body, [g.CustomTorque(tuple_linear, name="tuple_linear")])

    def run(model, batch=True, members=MEMBERS):
        return g.solve_ensemble(model, y0s[:members], (0.0, 200.0), batch=batch, error_estimate=False, **OPTIONS)

    reference = run(builtin, batch=False)
    for other in (run(compiled), run(builtin), run(vectorised)):
        worst = max(np.abs(a.y - b.y).max() for a, b in zip(reference, other))
        assert worst < 1e-8, worst  # batched lanes equal single runs to the tolerance, not bit for bit
    rows = best_interleaved({
        "LinearDamping (built-in), SIMD batches": lambda: run(builtin),
        "LinearDamping (built-in), one member at a time": lambda: run(builtin, batch=False),
        "CustomTorque, compiled": lambda: run(compiled),
        "CustomTorque, compiled vectorised, SIMD batches": lambda: run(vectorised),
    })
    rows["CustomTorque, Python (32 members, x16)"] = 16 * best(lambda: run(python, members=32), repeats=1)
    calls = sum(r.stats["rhs_evals"] for r in run(python, members=32))
    print(f"{MEMBERS} members, t = 0..200, DOP853 rtol 1e-10, {g.simd_lanes} SIMD lanes ({g.simd_instruction_set})")
    base = rows["LinearDamping (built-in), SIMD batches"]
    for name, seconds in rows.items():
        print(f"  {name:50s} {seconds * 1e3:9.1f} ms   {seconds / base:6.2f}x")
    per_call = rows["CustomTorque, Python (32 members, x16)"] / 16 / calls
    print(f"  Python torque: {per_call * 1e6:.2f} us per call ({calls} calls on 32 members)")
    # the library's own share of a call: the call's cost less the function's own time (called from Python),
    # for a function returning a NumPy array and one returning a tuple
    w, n = np.array([1.0, 0.5, -0.3]), 20000
    for label, model, function in (("NumPy array", python, numpy_linear), ("tuple", python_tuple, tuple_linear)):
        whole = best(lambda model=model: run(model, members=32), repeats=7) / calls
        own = best(lambda function=function: [function(1.0, w) for _ in range(n)], repeats=7) / n
        print(f"  returning a {label:11s}: {whole * 1e6:.2f} us per call, the function's own {own * 1e6:.2f} us, "
              f"the library's {(whole - own) * 1e6:.2f} us")
    ratio = rows["CustomTorque, compiled"] / rows["LinearDamping (built-in), one member at a time"]
    print(f"  compiled / built-in one at a time: {ratio:.2f}x;  compiled / built-in batched: "
          f"{rows['CustomTorque, compiled'] / base:.2f}x")
    print(f"  compiled vectorised / built-in, both in SIMD batches: "
          f"{rows['CustomTorque, compiled vectorised, SIMD batches'] / base:.2f}x  (goal <= 2x)")


if __name__ == "__main__":
    main()
