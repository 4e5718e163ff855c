"""method="auto" against dop853 and cvode_bdf on non-stiff, stiff, changing and mildly stiff cases:
steps, right-hand-side and Jacobian evaluations, seconds (best of 3), error of the final state.

Run:  .venv/bin/python bench/auto_method.py

Cases (rtol 1e-8, atol 1e-10 for the three methods compared, unless the case says otherwise):
* explorer: an Explorer-1-like prolate body with the explicit moving-mass damper (issue 15):
  moments (10, 10, 2), m = 0.1, ρ = 1, Ω = 5, λ = 1, ω0 = (0.05, 0, 2) on the quasi-static
  motion, t = 0..2e4. Not stiff (eigenvalues ≈ −0.5 ± 5i): DOP853's steps are accuracy-limited.
  Reference: dop853 at rtol 1e-13.
* stiff: paper 001's moving mass with Ω = 100, λ = 2e4 (bench/stiff_radau.py), ω0 = (1, 0, 1),
  t = 0..20: an eigenvalue ≈ −2e4 throughout. Reference: cvode_bdf at rtol 1e-12.
* changing: the gyrostat A = (1, 2, 3) under a constant torque (0.5, −0.3, 1) in a resistive
  medium D(t) = 4000 t (10 − t) I (zero at the ends, 1e5 at t = 5), t = 0..10: stiff in the middle
  only. Reference: dop853 at rtol 1e-13 (held by stability in the middle, but accurate).
* mild: paper 001's moving mass with a mild damper (Ω = 10, λ = 98, ω0 = (1, 0, 1), t = 0..40;
  bench/accuracy_cost.py's scene) at rtol 3.8e-6 (atol 3.8e-9 max|y0|): DOP853 is held at its
  stability boundary, but BDF's steps at this tolerance are only ~2x DOP853's, each costing ~5 of
  them: BDF does not pay. Reference: dop853 at rtol 1e-13.
"""

from __future__ import annotations

import numpy as np

import gyrostat as g
from stiff_radau import timed  # best of 3; found beside this script (python puts bench/ on sys.path)

METHODS = ("auto", "dop853", "cvode_bdf")


def cases():
    explorer = g.MovingMassModel(g.Body([10.0, 10.0, 2.0]), mass=0.1, arm=1.0, frequency=5.0, damping=1.0)
    stiff = g.MovingMassModel(g.Body([4.0, 4.0, 2.0]), mass=1.0, arm=1.0, frequency=100.0, damping=2e4)
    eye = np.eye(3)
    changing = g.Model(g.Body([1.0, 2.0, 3.0]), [g.ConstantTorque([0.5, -0.3, 1.0]),
                                                  g.ResistiveMedium([0 * eye, 4e4 * eye, -4e3 * eye])])
    mild = g.MovingMassModel(g.Body([4.0, 4.0, 2.0]), mass=1.0, arm=1.0, frequency=10.0, damping=98.0)
    mild_y0 = mild.quasi_static_state([1.0, 0.0, 1.0])
    return [
        ("explorer", explorer, explorer.quasi_static_state([0.05, 0.0, 2.0]), 2e4, dict(method="dop853", rtol=1e-13, atol=1e-15)),
        ("stiff", stiff, stiff.quasi_static_state([1.0, 0.0, 1.0]), 20.0, dict(method="cvode_bdf", rtol=1e-12, atol=1e-14)),
        ("changing", changing, [1.0, 0.5, -0.3], 10.0, dict(method="dop853", rtol=1e-13, atol=1e-15)),
        ("mild", mild, mild_y0, 40.0, dict(method="dop853", rtol=1e-13, atol=1e-16),
         dict(rtol=3.8e-6, atol=3.8e-9 * float(np.max(np.abs(mild_y0))))),
    ]


def main() -> None:
    print(f"{'case':9s} {'method':10s} {'steps':>8s} {'f evals':>9s} {'J evals':>8s} {'seconds':>9s} "
          f"{'error':>9s}  switches")
    for name, model, y0, t1, tight, *given in cases():
        tolerances = given[0] if given else dict(rtol=1e-8, atol=1e-10)
        reference = g.solve(model, y0, (0.0, t1), n_out=0, progress=False, **tight).raise_for_status().y[-1]
        for method in METHODS:
            seconds, sol = timed(lambda: g.solve(model, y0, (0.0, t1), method=method, n_out=0, progress=False,
                                                   error_estimate=False, **tolerances))
            s = sol.stats
            error = float(np.max(np.abs(sol.y[-1] - reference)))
            switches = ", ".join(f"{to} at t = {t:.4g}" for t, to, _ in sol.method_switches) or "-"
            print(f"{name:9s} {method:10s} {s['steps']:8d} {s['rhs_evals']:9d} {s['jacobian_evals']:8d} "
                  f"{seconds:9.4f} {error:9.2e}  {switches}")
    for name, model, y0, t1, _, *given in cases()[2:]:
        print(f"\nwhy each switch ({name} case):")
        tolerances = given[0] if given else dict(rtol=1e-8, atol=1e-10)
        for t, to, why in g.solve(model, y0, (0.0, t1), method="auto", n_out=0, progress=False, error_estimate=False,
                                  **tolerances).method_switches:
            print(f"  t = {t:.6g} -> {to}: {why}")


if __name__ == "__main__":
    main()
