"""The triaxial averaged model against the full one: its order in ε, its cost, the flat spin.

Run:  PYTHONPATH=python .venv/bin/python bench/triaxial_averaging.py

Rows (one machine, one run; best of 3 repeats for times; this machine is shared and noisy):
1. Order: M = −ε diag(1, 2, 3) ω on A = (3, 2, 1) from k² = 0.3 about the major axis, over t = 1/ε:
   the largest relative error of |G| and T of the averaged run against the full one (DOP853 at rtol
   1e-12), at ε = 1e-2 … 1e-4 (two decades), and the slope of log error against log ε.
2. Cost from Python at ε = 1e-4 over t = 1/ε, both at rtol 1e-10: `gyrostat.solve` of the full model
   against the averaged one, with the damping above (closed form in K and E) and with the
   moving-mass damper (no closed form: the trapezoidal rule in the phase). Goal: ≥ 1000×. The errors at
   t1: |G| and T (relative, the larger), and ω at the carried phase (|Δω|/|ω|: the phase's error).
3. The flat spin (python/gyrostat/scenes/explorer1_flat_spin.toml, ε = 1e-4): the time the nutation
   angle reaches 90° on the full model and on the ladder's run (averaged, switching to the full model
   across the separatrix), and their cost. Goals: within 1 %, ≥ 100× cheaper.
"""

from __future__ import annotations

import copy
import math
import tomllib
import sys
import time
from pathlib import Path

import numpy as np

import gyrostat as g
from gyrostat import ladder
from gyrostat.families import rigid_body
from gyrostat.scene import Scene

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "tests"))
import triaxial_reference as R  # noqa: E402

A = (3.0, 2.0, 1.0)


def best(call, repeats: int = 3):
    times, result = [], None
    for _ in range(repeats):
        started = time.perf_counter()
        result = call()
        times.append(time.perf_counter() - started)
    return min(times), result


def start():
    G, T = R.invariants_at(A, 0.3, side="largest")
    return np.asarray(R.free_motion(A, G, T, 0.0, 1), float)


def order() -> None:
    body, w0 = g.Body(list(A)), start()
    print("1. order in eps (max relative error of |G| and T over [0, 1/eps], full at rtol 1e-12)")
    print(f"{'eps':>8} {'error':>10} {'error/eps':>10}")
    epsilons, errors = (1e-2, 3e-3, 1e-3, 3e-4, 1e-4), []
    for eps in epsilons:
        torques = [g.LinearDamping(eps * np.diag([1.0, 2.0, 3.0]))]
        times = np.linspace(0.0, 1.0 / eps, 201)
        full = g.solve(g.Model(body, torques), w0, (0.0, 1.0 / eps), method="dop853", rtol=1e-12, atol=1e-14,
                       t_eval=times)
        slow = g.solve(g.TriaxialAveragedModel(body, torques), w0, (0.0, 1.0 / eps), rtol=1e-12, atol=1e-14,
                       t_eval=times)
        error = max(float(np.max(np.abs(slow[n] - full[n]) / full[n])) for n in ("angular_momentum_norm", "kinetic_energy"))
        errors.append(error)
        print(f"{eps:8.0e} {error:10.3e} {error / eps:10.3f}")
    slope = np.polyfit(np.log(epsilons), np.log(errors), 1)[0]
    print(f"slope {slope:.3f} over {epsilons[0]:g} .. {epsilons[-1]:g}\n")


def cost() -> None:
    for eps in (1e-4, 1e-5):
        cost_at(eps)


def cost_at(eps: float) -> None:
    body, w0 = g.Body(list(A)), start()
    print(f"2. cost from Python at eps = {eps:g} over t = 1/eps (rtol 1e-10, atol 1e-12; best of 3)")
    print(f"{'torque':<34} {'full s':>9} {'averaged s':>11} {'ratio':>8} {'steps full/avg':>16} {'rel. error':>11} {'omega error':>11}")
    cases = {"linear damping (closed form)": [g.LinearDamping(eps * np.diag([1.0, 2.0, 3.0]))],
             "moving-mass damper (quadrature)": [g.MovingMassDamper(1.0, 1.0, 30.0, 30.0 * 30.0 * eps)]}
    for name, torques in cases.items():
        options = dict(method="dop853", rtol=1e-10, atol=1e-12, t_eval=[0.0, 1.0 / eps])
        full_s, full = best(lambda: g.solve(g.Model(body, torques), w0, (0.0, 1.0 / eps), error_estimate=False, **options))
        slow_model = g.TriaxialAveragedModel(body, torques)
        slow_s, slow = best(lambda: g.solve(slow_model, w0, (0.0, 1.0 / eps), check_validity=False,
                                            error_estimate=False, **options), 20)
        error = max(abs(slow[n][-1] - full[n][-1]) / full[n][-1] for n in ("angular_momentum_norm", "kinetic_energy"))
        carried = np.array([slow["p"][-1], slow["q"][-1], slow["r"][-1]])  # omega at the carried phase
        omega_error = np.linalg.norm(carried - full.omega[-1]) / np.linalg.norm(full.omega[-1])
        print(f"{name:<34} {full_s:9.4f} {slow_s:11.6f} {full_s / slow_s:8.0f} "
              f"{int(full.stats['steps']):>8}/{int(slow.stats['steps']):<7} {error:11.2e} {omega_error:11.2e}")
    print()


def flat_spin() -> None:
    doc = tomllib.loads((ROOT / "python/gyrostat/scenes/explorer1_flat_spin.toml").read_text())
    print("3. the flat spin (explorer1_flat_spin.toml): the time the nutation angle reaches 90 degrees")
    rows = {}
    for model in ("full", "auto"):
        d = copy.deepcopy(doc)
        d["integration"]["model"] = model
        d["outputs"]["plots"] = []
        scene = Scene.from_dict(d, name="explorer1")
        ladder.choosing._CHOICES.clear()  # the ladder's first solve: its probes are paid

        def run():
            from gyrostat.runner import solve_scene
            ladder.choosing._CHOICES.clear()
            return solve_scene(scene, progress=False)

        seconds, (solutions, report, _) = best(run, 1 if model == "full" else 3)
        sol = solutions.get("full", solutions.get("averaged"))
        rows[model] = (seconds, rigid_body.first_reaching(sol, "nutation_angle", 0.5 * math.pi), report)
    (t_full_s, t90_full, _), (t_auto_s, t90_auto, report) = rows["full"], rows["auto"]
    print(f"full model: 90 degrees at t = {t90_full:.6g} s, {t_full_s:.3f} s of CPU")
    print(f"ladder ({report['model']}, {len(report['ladder'].get('switches', []))} switches): 90 degrees at t = {t90_auto:.6g} s, "
          f"{t_auto_s:.4f} s (probes included)")
    print(f"relative difference {abs(t90_auto - t90_full) / t90_full:.2e}, cost ratio {t_full_s / t_auto_s:.0f}")


if __name__ == "__main__":
    order()
    cost()
    flat_spin()
