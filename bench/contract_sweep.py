"""The accuracy contract on scenes nobody tuned it on: random bodies, spans and perturbations across
the families, each at accuracies 1e-3, 1e-5, 1e-7 and 1e-9, checked against the same model run at
rtol 1e-13 (its own error bounded by its distance to the run at 1e-12; a case whose true error is
within 10x that bound is marked ``~`` and not judged).

Run:  .venv/bin/python bench/contract_sweep.py [--seed N] [--explicit]   (~1 min a seed)

With ``--explicit`` every case runs at rtol = 1e-4, 1e-6, 1e-8 and 1e-10 instead (the accuracies / 10) with the
default estimate (the window's, or the whole span's where the engine finds a separatrix crossing),
and only the band is judged.

It prints one line per case and flags what breaks the contract: ``DELIVERED>A`` (the true error
above the accuracy without an AccuracyWarning) and ``BAND`` (the estimate outside [0.5, 30] x a true
error above 1e-10). This is a search for faults, not a proof: its reference is the engine's own DOP853
(tests/test_accuracy_contract.py holds the SciPy references for the cases it found).
"""

from __future__ import annotations

import argparse
import math
import time
import warnings

import numpy as np

import gyrostat as g
from gyrostat import accuracy as acc
from gyrostat import lagrange as lg
from gyrostat.orthogonal import OrthogonalModel

N_OUT = 101
ACCURACIES = (1e-3, 1e-5, 1e-7, 1e-9)


def true_error(model, reference, solution) -> float:
    if len(solution.t) != len(reference.t):
        return math.nan
    apart = acc.differences(reference._result, solution._result, model._core)
    return max(float(v.max()) for v in apart.values())


EXPLICIT = False
"""--explicit: each case at rtol = 1e-4, 1e-6, 1e-8, 1e-10 (atol = rtol · 1e-3 · max|y0|) with the default
estimate, judged on the band alone (an explicit rtol promises no accuracy)."""


def check(name: str, model, y0, t1: float, kw: dict | None = None) -> int:
    """Prints the case's lines; returns how many broke the contract."""
    plain = dict(n_out=N_OUT, error_estimate=False, progress=False, check_validity=False, method="dop853")
    reference = g.solve(model, y0, (0, t1), rtol=1e-13, atol=1e-16, **plain)
    bound = true_error(model, reference, g.solve(model, y0, (0, t1), rtol=1e-12, atol=1e-15, **plain))
    broken = 0
    size = float(np.max(np.abs(y0))) or 1.0
    for accuracy in ACCURACIES:
        started = time.perf_counter()
        if EXPLICIT:
            rtol = accuracy / 10.0
            solution = g.solve(model, y0, (0, t1), n_out=N_OUT, rtol=rtol, atol=rtol * 1e-3 * size, progress=False,
                               check_validity=False, **(kw or {}))
            label, accuracy = f"rtol={rtol:<6g}", math.inf  # (an explicit rtol promises no accuracy: the band alone)
        else:
            label = f"A={accuracy:<6g}"
            solution = g.solve(model, y0, (0, t1), n_out=N_OUT, accuracy=accuracy, progress=False,
                               check_validity=False, **(kw or {}))
        seconds = time.perf_counter() - started
        true = true_error(model, reference, solution)
        estimate, warned, judged = solution.error_estimate, bool(solution.accuracy_warnings), true > 10 * bound
        ratio = estimate / true if true > 0 else math.inf
        flags = []
        if judged and true > accuracy and not warned:
            flags.append("DELIVERED>A")
        if judged and true > 1e-10 and not 0.5 <= ratio <= 30:
            flags.append("BAND")
        broken += bool(flags)
        print(f"{name:58s} {label} true={true:.2e} est={estimate:.2e} r={ratio:<7.2g}"
              f"{'~' if not judged else ' '} {'W' if warned else ' '} {seconds * 1e3:6.1f} ms {' '.join(flags)}",
              flush=True)
    return broken


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--rounds", type=int, default=3, help="random draws of every family")
    parser.add_argument("--explicit", action="store_true", help="explicit rtols with the default estimate instead")
    args = parser.parse_args()
    global EXPLICIT
    EXPLICIT = args.explicit
    warnings.simplefilter("ignore")
    rng = np.random.default_rng(args.seed)
    broken = 0
    for _ in range(args.rounds):
        moments = rng.uniform(1, 3, 3)
        while 2 * moments.max() >= moments.sum():  # (the triangle inequality of inertia: Body refuses the rest)
            moments = rng.uniform(1, 3, 3)
        body = g.Body(list(moments))
        w0 = rng.normal(size=3)
        eps = 10 ** rng.uniform(-4, -2)
        damping = g.LinearDamping(diagonal=list(eps * rng.uniform(0.5, 2, 3)))
        span = float(rng.uniform(0.2, 1) / eps)
        broken += check(f"damped, eps {eps:.2e}, t {span:.0f}, J {np.array2string(np.asarray(body.moments), precision=4)}, "
                        f"w0 {np.array2string(w0, precision=4)}", g.Model(body, [damping]), w0, span)
        broken += check(f"damped with attitude, eps {eps:.2e}, t {span:.0f}", g.Model(body, [damping], attitude=True),
                        np.r_[w0, 1.0, 0.0, 0.0, 0.0], span)
        viscosity, span = 10 ** rng.uniform(0, 3), float(rng.uniform(100, 3000))
        broken += check(f"cavity, nu {viscosity:.4g}, t {span:.0f}", g.Model(body, [g.ViscousCavity(1.0, viscosity, 1.0)]),
                        w0, span)
        broken += check("constant torque", g.Model(body, [g.ConstantTorque(list(rng.normal(size=3) * 0.01))]), w0,
                        float(rng.uniform(50, 500)))
        broken += check("torque free (closed form)", g.TorqueFreeModel(body), w0, float(rng.uniform(50, 500)))
        span = float(rng.uniform(20, 200))
        broken += check(f"orthogonal torque, w0 {np.array2string(w0, precision=4)}, t {span:.4g}",
                        OrthogonalModel(g.Body([1.0, 1.4, 2.1]), 0.01), w0, span)
        cavity = g.ViscousCavity(1260, 1000 * rng.uniform(0.5, 2), 0.48)
        broken += check("averaged (a, r)", g.AveragedModel(g.Body([8.0, 8.0, 4.0]),
                                                            [cavity, g.ConstantTorque([0.0, 0.0, -0.01])]),
                        np.array([1.0, 1.0]), float(rng.uniform(20, 100)))
        broken += check("averaged triaxial", g.TriaxialAveragedModel(g.Body([1.0, 1.4, 2.1]),
                                                                     [g.LinearDamping(diagonal=[1e-3, 2.5e-3, 7e-4])]),
                        np.array([0.15, 0.3, 1.0]), float(rng.uniform(200, 1000)))
        theta0 = math.radians(rng.uniform(20, 80))
        broken += check(f"Lagrange top, theta0 {math.degrees(theta0):.0f} deg",
                        lg.LagrangeTop(1.5, 1.0, 0.5, [lg.paper_torque(0.002)]),
                        lg.initial_state([0.0, 0.0, math.sqrt(3.0)], theta0), float(rng.uniform(200, 2000)))
        lam, span = float(rng.uniform(5, 100)), float(rng.uniform(10, 60))
        mass = g.MovingMassModel(g.Body([4.0, 4.0, 2.0]), mass=1.0, arm=1.0, frequency=10.0, damping=lam)
        broken += check(f"moving mass, lambda {lam:.4g}, t {span:.4g}, auto", mass,
                        mass.quasi_static_state([1.0, 0.0, 1.0]), span, {"method": "auto"})
    print(f"{broken} case(s) broke the contract")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
