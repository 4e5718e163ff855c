"""The cost of forward sensitivities against the plain run, for every family (goal: n_p
sensitivities at most 1.5 × (1 + n_p) × the plain run's time, both at the same rtol).

Each row: the plain run (``gyrostat.solve``, ``error_estimate=False``) and the run with n_p
sensitivities (initial components and parameters), their times (best of ``--rounds`` rounds, each
round running every row once, so that a burst of load touches every row alike), the time ratio
over (1 + n_p), and the right-hand-side evaluations of each (deterministic).

    .venv/bin/python bench/sensitivity_cost.py [--rounds 7] [--rtol 1e-10]
"""

from __future__ import annotations

import argparse
import time
import warnings

import numpy as np

import gyrostat
from gyrostat.lagrange import LagrangeAveraged, LagrangeTop
from gyrostat.orthogonal import OrthogonalModel

BODY = gyrostat.Body([1.0, 1.4, 2.1])


def cases():
    """(label, model, y0, t1, names)."""
    damping = gyrostat.LinearDamping(matrix=[[0.05, 0.01, 0.0], [0.01, 0.08, 0.0], [0.0, 0.0, 0.03]])
    cavity = gyrostat.ViscousCavity(density=1.0, viscosity=0.1, p0=0.5)
    top_state = [0.1, 0.0, 5.0, 1.0, 0.0, 0.0, 0.0]
    mass_state = [0.1, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0]
    return [
        ("gyrostat, damping", gyrostat.Model(BODY, [damping]), [0.15, 0.3, 1.0], 20.0,
         ["p", "q", "r", "moments[0]", "LinearDamping.matrix[0,0]", "LinearDamping.matrix[0,1]"]),
        ("gyrostat, damping, 1 parameter", gyrostat.Model(BODY, [damping]), [0.15, 0.3, 1.0], 20.0,
         ["LinearDamping.matrix[0,0]"]),
        ("gyrostat + attitude, cavity", gyrostat.Model(BODY, [cavity], attitude=True), [0.15, 0.3, 1.0], 20.0,
         ["p", "ViscousCavity.viscosity"]),
        ("averaged (a, r)", gyrostat.AveragedModel(gyrostat.Body([2.0, 2.0, 1.0]),
                                                   [gyrostat.LinearDamping(diagonal=[0.01, 0.01, 0.02])]),
         [0.3, 0.0, 1.0], 100.0, ["a", "LinearDamping.matrix[2,2]"]),
        ("averaged triaxial", gyrostat.TriaxialAveragedModel(BODY, [gyrostat.LinearDamping(diagonal=[1e-3, 2.5e-3, 7e-4])]),
         [0.15, 0.3, 1.0], 100.0, ["G2", "LinearDamping.matrix[0,0]"]),
        ("moving mass", gyrostat.MovingMassModel(gyrostat.Body([2.0, 2.0, 1.0]), 0.1, 0.2, 10.0, 0.5),
         mass_state, 5.0, ["q", "damping"]),
        ("Lagrange top", LagrangeTop(2.0, 1.0, 0.5), top_state, 5.0, ["p", "mu"]),
        ("Lagrange averaged", LagrangeAveraged(2.0, 1.0, 0.5, [gyrostat.LinearDamping(diagonal=[0.01, 0.01, 0.01])]),
         [0.1, 0.0, 5.0, 1.0, 0.0, 0.0, 0.0], 5.0, ["r", "mu"]),
        ("orthogonal torque", OrthogonalModel(BODY, 0.01), [0.15, 0.3, 1.0], 5.0, ["p", "moments[0]"]),
    ]


def timed(run, repeat: int) -> float:
    start = time.perf_counter()
    for _ in range(repeat):
        run()
    return (time.perf_counter() - start) / repeat


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--rounds", type=int, default=7)
    parser.add_argument("--rtol", type=float, default=1e-10)
    args = parser.parse_args()
    warnings.simplefilter("ignore", gyrostat.ValidityWarning)
    rows = []
    for label, model, y0, t1, names in cases():
        def plain(model=model, y0=y0, t1=t1):
            return gyrostat.solve(model, y0, (0.0, t1), rtol=args.rtol, n_out=11, error_estimate=False)

        def sensitive(model=model, y0=y0, t1=t1, names=names):
            return gyrostat.solve(model, y0, (0.0, t1), rtol=args.rtol, n_out=11, error_estimate=False,
                                  sensitivities=names)
        rows.append((label, names, plain, sensitive, plain().stats["rhs_evals"], sensitive().stats["rhs_evals"]))
    best = {label: [np.inf, np.inf] for label, *_ in rows}
    for _ in range(args.rounds):
        for label, names, plain, sensitive, *_ in rows:
            repeat = max(3, int(0.02 / max(timed(plain, 1), 1e-6)))
            best[label][0] = min(best[label][0], timed(plain, repeat))
            best[label][1] = min(best[label][1], timed(sensitive, max(1, repeat // (1 + len(names)))))
    print(f"rtol {args.rtol:g}, 11 outputs, best of {args.rounds} rounds; goal: ratio / (1 + n_p) <= 1.5")
    print(f"{'case':34s} {'n_p':>3s} {'plain':>10s} {'with':>10s} {'ratio/(1+n_p)':>13s} {'rhs plain':>9s} {'rhs with':>9s}")
    for label, names, _, _, rhs_plain, rhs_with in rows:
        plain_time, with_time = best[label]
        print(f"{label:34s} {len(names):3d} {plain_time * 1e6:8.1f}us {with_time * 1e6:8.1f}us "
              f"{with_time / plain_time / (1 + len(names)):13.2f} {rhs_plain:9d} {rhs_with:9d}")


if __name__ == "__main__":
    main()
