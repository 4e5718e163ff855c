"""The default (window) estimate made in the engine against the general path, inside one binary.

Run:  .venv/bin/python bench/window_in_engine.py      (~20 s)

One run's estimate (``accuracy.SingleRun``: ``_core.window_estimate``, one engine call) and an
ensemble's (``accuracy.EnsembleRun``: ``_core.window_estimates``, the companions as one ensemble)
against the general path on the same answers (a plain runner: the companion through
``_core.solve`` / ``solve_ensemble``, the comparison and the growth called from Python, per
member), interleaved, best of 9 (7) rounds; the answer's own engine run beside them. Both paths
give the same estimates (tests/test_measurement_primitives.py).

Last, what a user pays: ``gyrostat.solve`` of each case with its default estimate against the same
with ``error_estimate=False`` (the goal: at most 1.5x), alternated for 15 rounds of ~50 ms each;
the ratio of the bests and the median of the rounds' ratios.
"""
import time, numpy as np, gyrostat as g, warnings
from gyrostat import _core, accuracy as acc
warnings.simplefilter("ignore")
cases = {
 "averaged (a, r), t = 60": (g.AveragedModel(g.Body([8.0, 8.0, 4.0]), [g.ViscousCavity(1260, 1000, 0.48), g.ConstantTorque([0.0, 0.0, -0.01])]), np.array([1.0, 1.0]), 60.0, 1e-8),
 "triaxial damped, t = 1e4": (g.Model(g.Body([1, 1.4, 2.1]), [g.LinearDamping(diagonal=[1e-4, 2.5e-4, 0.7e-4])]), np.array([0.15, 0.3, 1.0]), 1e4, 1e-8),
 "Lagrange top, t = 2000": None,
}
from gyrostat.lagrange import LagrangeTop, paper_torque, initial_state
import math
cases["Lagrange top, t = 2000"] = (LagrangeTop(1.5, 1.0, 0.5, [paper_torque(0.002)]), np.asarray(initial_state([0.0, 0.0, math.sqrt(3.0)], math.radians(60.0))), 2000.0, 1e-8)
def timed(f, n):
    t = time.perf_counter()
    for _ in range(n): f()
    return (time.perf_counter() - t) / n
for name, (model, y0, t1, rtol) in cases.items():
    core = model._core
    o = g.Options(); o.rtol = rtol; o.atol = rtol * 1e-3; o.n_out = 201
    ans = _core.solve(core, y0, 0.0, t1, o)
    plain = lambda: _core.solve(core, y0, 0.0, t1, o)
    eng = lambda: acc.estimate_runs(acc.SingleRun(core, y0, 0.0), [core], o, 0.0, t1, [ans])
    gen = lambda: acc.estimate_runs(lambda oo, t, ms: [_core.solve(core, y0, 0.0, t, oo)], [core], o, 0.0, t1, [ans])
    n = max(3, int(0.05 / timed(plain, 3)))
    best = {"plain": 1e9, "engine": 1e9, "general": 1e9}
    for _ in range(9):
        best["plain"] = min(best["plain"], timed(plain, n))
        best["engine"] = min(best["engine"], timed(eng, n))
        best["general"] = min(best["general"], timed(gen, n))
    print(f"{name:28s} answer's engine run {best['plain']*1e6:9.1f} us; its window estimate: engine path {best['engine']*1e6:8.1f} us, general path {best['general']*1e6:8.1f} us ({best['general']/best['engine']:.2f}x)")
# ensemble of the averaged model
model, y0, t1, rtol = cases["averaged (a, r), t = 60"]
core = model._core; count = 500
y0s = np.column_stack([np.linspace(0.9, 1.1, count), np.ones(count)])
o = g.Options(); o.rtol = rtol; o.atol = rtol * 1e-3; o.n_out = 201
answers = list(_core.solve_ensemble([core], y0s, 0.0, t1, o, 1, None, batch=True))
plain = lambda: _core.solve_ensemble([core], y0s, 0.0, t1, o, 1, None, batch=True)
eng = lambda: acc.estimate_runs(acc.EnsembleRun([core], y0s, 0.0, count, 1), [core] * count, o, 0.0, t1, answers)
gen = lambda: acc.estimate_runs(lambda oo, t, ms: _core.solve_ensemble([core], y0s[ms], 0.0, t, oo, 1, None, batch=True), [core] * count, o, 0.0, t1, answers)
best = {"plain": 1e9, "engine": 1e9, "general": 1e9}
for _ in range(7):
    best["plain"] = min(best["plain"], timed(plain, 3))
    best["engine"] = min(best["engine"], timed(eng, 3))
    best["general"] = min(best["general"], timed(gen, 3))
print(f"averaged ensemble, {count} members, one thread: answers {best['plain']/count*1e6:.1f} us/member; estimates: engine path {best['engine']/count*1e6:.1f} us/member, general path {best['general']/count*1e6:.1f} us/member ({best['general']/best['engine']:.2f}x)")
# a whole solve with its default estimate against without (what a user pays; the goal: <= 1.5x)
import statistics
for name, (model, y0, t1, rtol) in cases.items():
    settings = dict(rtol=rtol, atol=rtol * 1e-3, n_out=201, check_validity=False)
    off = lambda: g.solve(model, y0, (0.0, t1), error_estimate=False, **settings)
    on = lambda: g.solve(model, y0, (0.0, t1), **settings)
    n = max(3, int(0.05 / timed(on, 3)))
    times = {"off": [], "on": []}
    for _ in range(15):
        times["off"].append(timed(off, n))
        times["on"].append(timed(on, n))
    ratios = [b / a for a, b in zip(times["off"], times["on"])]
    print(f"{name:28s} solve {min(times['off'])*1e6:9.1f} us, with its estimate {min(times['on'])*1e6:9.1f} us: "
          f"{min(times['on'])/min(times['off']):.2f}x (rounds: median {statistics.median(ratios):.2f}x, "
          f"{min(ratios):.2f}-{max(ratios):.2f}x)")
