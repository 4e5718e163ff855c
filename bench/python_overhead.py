"""Python overhead of one gyrostat.solve call, and the averaged model's advantage seen from Python.

Run:  .venv/bin/python bench/python_overhead.py   (after `bash run.sh test` or `pip install .`)

Rows (best of 7 repeats of N calls each; this machine is shared and noisy, so only the best
repeat is kept):
* `gyrostat.solve`: the whole Python call on a trivial problem (a zero-length span, two
  outputs): argument checks, options, the binding, the engine, the Solution.
* `gyrostat.solve, t_eval=[t0, t1]`: the same call with the output times given as a list.
* `_core.solve`: the binding and the engine alone, with options built once.
* `engine (C++)`: the engine's own time for the same problem, measured inside C++ by
  `_core.solve_ensemble` over 10 000 members on one thread (per member, binding excluded).
The Python overhead is the first row (and the second) minus the engine's own time.

Then the averaged model against the full one at ε = 1e-4 from Python, on the problem of
`gyrostat_bench`'s averaged rows (oblate body (1, 1, 1.8), a cavity of strength κ = 0.4 ε and a
damping ε·diag(1, 1, 0.5), t1 = 3/ε, DOP853 at rtol 1e-10, outputs at t0 and t1): the cost
ratio of the two `gyrostat.solve` calls, and the same ratio inside C++ for comparison.
"""

from __future__ import annotations

import time

import numpy as np

import gyrostat as g
from gyrostat import _core


def best_per_call(call, n: int, repeats: int = 7) -> float:
    best = float("inf")
    for _ in range(repeats):
        started = time.perf_counter()
        for _ in range(n):
            call()
        best = min(best, (time.perf_counter() - started) / n)
    return best


def main() -> None:
    model = g.Model(g.Body([1.0, 2.0, 3.0]))
    y0 = np.array([1.0, 0.5, -0.3])
    options = g.Options()
    options.n_out = 2
    n = 100_000
    python = best_per_call(lambda: g.solve(model, y0, (0.0, 0.0), n_out=2), n)
    python_t_eval = best_per_call(lambda: g.solve(model, y0, (0.0, 0.0), t_eval=[0.0, 0.0]), n)
    binding = best_per_call(lambda: _core.solve(model._core, y0, 0.0, 0.0, options), n)
    members = 10_000
    starts = np.tile(y0, (members, 1))
    engine = best_per_call(lambda: _core.solve_ensemble([model._core], starts, 0.0, 0.0, options, 1), 3) / members
    print("Python overhead of one solve call (trivial problem: zero-length span, 2 outputs)")
    print(f"  gyrostat.solve, n_out=2             {python * 1e6:7.2f} us per call")
    print(f"  gyrostat.solve, t_eval=[t0, t1]     {python_t_eval * 1e6:7.2f} us per call (output times as a list)")
    print(f"  _core.solve                         {binding * 1e6:7.2f} us per call (binding + engine)")
    print(f"  engine (C++)                        {engine * 1e6:7.2f} us per solve (inside one ensemble call)")
    print(f"  Python overhead, n_out=2            {(python - engine) * 1e6:7.2f} us per call (target: at most 3 us)")
    print(f"  Python overhead, t_eval list        {(python_t_eval - engine) * 1e6:7.2f} us per call (target: at most 3 us)")

    epsilon = 1e-4
    body = g.Body([1.0, 1.0, 1.8])
    torques = [g.ViscousCavity(1.0, 1.0 / epsilon, 0.4), g.LinearDamping(epsilon * np.diag([1.0, 1.0, 0.5]))]
    horizon = 3.0 / epsilon
    full_model, averaged_model = g.Model(body, torques), g.AveragedModel(body, torques)
    settings = dict(n_out=0, rtol=1e-10, atol=1e-12, max_steps=100_000_000)
    full = best_per_call(lambda: g.solve(full_model, [1.0, 0.0, 1.0], (0.0, horizon), **settings, error_estimate=False), 1,
                         repeats=3)
    averaged = best_per_call(lambda: g.solve(averaged_model, [1.0, 1.0], (0.0, horizon), **settings,
                                             check_validity=False, error_estimate=False), 2000)
    core_options = g.Options()
    core_options.n_out, core_options.rtol, core_options.atol = 0, 1e-10, 1e-12
    averaged_engine = best_per_call(lambda: _core.solve_ensemble([averaged_model._core], np.tile([1.0, 1.0], (1000, 1)),
                                                                 0.0, horizon, core_options, 1), 3) / 1000
    print(f"\nAveraged vs full model, eps = {epsilon:g}, t1 = 3/eps = {horizon:g}, outputs at t0 and t1, rtol 1e-10")
    print(f"  full (Euler's equations), gyrostat.solve   {full * 1e3:9.3f} ms")
    print(f"  averaged (a, r), gyrostat.solve            {averaged * 1e6:9.2f} us")
    print(f"  averaged (a, r), engine alone              {averaged_engine * 1e6:9.2f} us")
    print(f"  ratio from Python                          {full / averaged:9.0f} x (target: at least 1000)")
    print(f"  ratio inside the engine                    {full / averaged_engine:9.0f} x")


if __name__ == "__main__":
    main()
