"""Writes heyoka_sensitivities.json: an independent peer reference for forward sensitivities of
Euler's rigid-body equations (free, and under a linear damping torque), computed with heyoka's
first-order variational equations (heyoka.var_ode_sys), not with gyrostat.

What is stored, for each case: the state y(t) = ω(t) = (p, q, r) at t = 0, 5, 10, 15, 20 and, for
each parameter, the sensitivity ∂ω(t)/∂parameter as [∂p/∂·, ∂q/∂·, ∂r/∂·] per output time. The
stored numbers come from heyoka's Taylor integrator in double precision at its default tolerance
(machine epsilon, 2.2e-16; order 20), high_accuracy mode, written as Python reprs (full double
precision).

Generated with heyoka (heyoka.py) 7.13.2, numpy, Python 3.11. heyoka is not a gyrostat dependency;
to run:
    pip install --target /tmp/hy heyoka
    PYTHONPATH=/tmp/hy .venv/bin/python tests/data/make_heyoka_sensitivities.py
(a few seconds on one core, mostly LLVM JIT compilation; `--no-check` skips the verification
below.)

Physics. Principal moments A = (A1, A2, A3) (kg m^2), body angular velocity ω = (p, q, r) (rad/s),
linear damping torque M = -D ω with D a 3x3 matrix (N m s), i.e.
    M_i = -(D[i,0] p + D[i,1] q + D[i,2] r),
and Euler's equations
    A1 p' = (A2 - A3) q r + M_1
    A2 q' = (A3 - A1) r p + M_2
    A3 r' = (A1 - A2) p q + M_3.
All nine entries of D are separate ODE parameters, so the sensitivity to "LinearDamping.matrix[0,1]"
is the derivative w.r.t. the single entry D[0,1] (only in the p equation) with D[1,0] held fixed.
The sensitivities S_k(t) = ∂ω(t)/∂θ_k solve the variational equations
    S_k' = (∂f/∂ω) S_k + ∂f/∂θ_k,   S_k(0) = e_k for θ_k an initial component of ω, else 0,
which heyoka derives symbolically (var_ode_sys) and integrates along with ω.

Cases (t = 0 .. 20):
  "free":   A = (1.0, 1.4, 2.1), D = 0, ω0 = (0.15, 0.3, 1.0); parameters p, q, r (initial
            components), moments[0..2].
  "damped": A = (1.0, 1.4, 2.1), D = [[0.05, 0.01, 0], [0.01, 0.08, 0], [0, 0, 0.03]],
            ω0 = (0.15, 0.3, 1.0); parameters p, q, r, moments[0..2], LinearDamping.matrix[0,0],
            [1,1], [0,1], [2,2].

Verification (run by default; numbers from the run that wrote the file, heyoka 7.13.2, x86_64).
Error measure: for each case, parameter and time, max_i |x_i - x_ref_i| / max_i |x_ref_i| over
the 3 components (normwise relative); the worst over all cases/parameters/times is quoted.
  1. Same variational integration in 80-bit long double (tol = 1.08e-19), from the same
     double-valued inputs: the stored (double) values differ from it by at most 6.3e-16 for y and
     2.3e-15 for the sensitivities, normwise (componentwise, over components above 1e-3 of their
     vector's max: 1.5e-14).
  2. Same double integration at tol = 1e-13: agrees with the stored values to 3.9e-15 (y 4.1e-16).
  3. 9-point (8th-order) central differences of plain (non-variational) long-double heyoka runs,
     absolute step h = 2e-4 (perturbations made in long double): differ from the stored
     sensitivities by at most 3.4e-15, and from the long-double variational ones by at most
     2.3e-15 (4th-order 5-point stencils were limited to ~1e-13 by truncation/rounding).
  4. Free case, physics: kinetic energy T = ½ Σ A_i ω_i² and |L|² = Σ A_i² ω_i² stay constant,
     and so do their derivatives w.r.t. ω0 (Σ A_i ω_i S_i, Σ A_i² ω_i S_i) and w.r.t. A_j
     (½ ω_j² + Σ A_i ω_i S_i), all to 3.6e-15.
So 14 significant digits (normwise per vector) of every stored number are trustworthy: the data
are a reference to a relative tolerance of 1e-13 with margin (>= 40x). Small components of a
vector (e.g. ∂r/∂moments[0] = -5.0e-4 at t = 20 beside ∂p/∂moments[0] = 1.39) carry the same
absolute error, so compare them normwise, not componentwise.
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

import heyoka as hy
import numpy as np

HERE = Path(__file__).resolve().parent
TIMES = [0.0, 5.0, 10.0, 15.0, 20.0]
MOMENTS = [1.0, 1.4, 2.1]
OMEGA0 = [0.15, 0.3, 1.0]
D_ZERO = [[0.0, 0.0, 0.0], [0.0, 0.0, 0.0], [0.0, 0.0, 0.0]]
D_DAMPED = [[0.05, 0.01, 0.0], [0.01, 0.08, 0.0], [0.0, 0.0, 0.03]]
MOMENT_NAMES = ["moments[0]", "moments[1]", "moments[2]"]
DAMPING_NAMES = {"LinearDamping.matrix[0,0]": (0, 0), "LinearDamping.matrix[1,1]": (1, 1),
                 "LinearDamping.matrix[0,1]": (0, 1), "LinearDamping.matrix[2,2]": (2, 2)}
CASES = {
    "free": (MOMENTS, D_ZERO, OMEGA0, ["p", "q", "r"] + MOMENT_NAMES),
    "damped": (MOMENTS, D_DAMPED, OMEGA0, ["p", "q", "r"] + MOMENT_NAMES + list(DAMPING_NAMES)),
}

# ODE parameters: par[0..2] = A1, A2, A3; par[3 + 3 i + j] = D[i, j].
STATE = hy.make_vars("p", "q", "r")


def _par_index(name: str) -> int:
    if name in MOMENT_NAMES:
        return MOMENT_NAMES.index(name)
    i, j = DAMPING_NAMES[name]
    return 3 + 3 * i + j


def _arg(name: str) -> hy.expression:
    """heyoka's variational argument for a parameter name: a state variable or an ODE parameter."""
    return STATE["pqr".index(name)] if name in ("p", "q", "r") else hy.par[_par_index(name)]


def euler_system() -> list[tuple[hy.expression, hy.expression]]:
    """A_i ω_i' = (A_j - A_k) ω_j ω_k - Σ_l D[i,l] ω_l, (i, j, k) cyclic."""
    A = [hy.par[i] for i in range(3)]
    D = [[hy.par[3 + 3 * i + j] for j in range(3)] for i in range(3)]
    p, q, r = STATE
    w = [p, q, r]
    M = [-(D[i][0] * w[0] + D[i][1] * w[1] + D[i][2] * w[2]) for i in range(3)]
    return [(p, ((A[1] - A[2]) * q * r + M[0]) / A[0]),
            (q, ((A[2] - A[0]) * r * p + M[1]) / A[1]),
            (r, ((A[0] - A[1]) * p * q + M[2]) / A[2])]


def _pars(moments, D, fp_type=float) -> np.ndarray:
    return np.array(list(moments) + [x for row in D for x in row], dtype=fp_type)


def variational(moments, D, omega0, names, fp_type=float, tol=None):
    """(y, {name: sensitivity}) at TIMES, by heyoka's variational equations."""
    vsys = hy.var_ode_sys(euler_system(), [_arg(n) for n in names], order=1)
    kw = {} if tol is None else {"tol": fp_type(tol)}
    ta = hy.taylor_adaptive(vsys, np.array(omega0, dtype=fp_type), pars=_pars(moments, D, fp_type),
                            fp_type=fp_type, compact_mode=True, high_accuracy=True, **kw)
    out = ta.propagate_grid(np.array(TIMES, dtype=fp_type))[-1]  # (len(TIMES), 3 + 3 * len(names))
    y = out[:, :3]
    sens = {n: np.empty((len(TIMES), 3), dtype=fp_type) for n in names}
    for idx in range(ta.get_vslice(order=1).start, ta.dim):
        comp, *orders = ta.get_mindex(idx)  # component of ω, then one 0/1 per variational argument
        sens[names[orders.index(1)]][:, comp] = out[:, idx]
    return y, sens


def plain_run(moments, D, omega0, fp_type) -> np.ndarray:
    """ω at TIMES, plain integration (no variational equations)."""
    ta = hy.taylor_adaptive(euler_system(), np.array(omega0, dtype=fp_type),
                            pars=_pars(moments, D, fp_type), fp_type=fp_type, compact_mode=True,
                            high_accuracy=True)
    return ta.propagate_grid(np.array(TIMES, dtype=fp_type))[-1]


# 8th-order central-difference weights for f'(x): sum_s W[s] f(x + s h) / h.
FD_WEIGHTS = {1: 4 / 5, 2: -1 / 5, 3: 4 / 105, 4: -1 / 280}


def central_differences(moments, D, omega0, names, h=2e-4, fp_type=np.longdouble) -> dict:
    """9-point (8th-order) central differences of plain heyoka runs, absolute step h.

    One compiled integrator is reused: time, initial state and parameters are reset per run, and
    the perturbations are made in fp_type, so each step is exactly a multiple of the same h.
    """
    ta = hy.taylor_adaptive(euler_system(), np.array(omega0, dtype=fp_type),
                            pars=_pars(moments, D, fp_type), fp_type=fp_type, compact_mode=True,
                            high_accuracy=True)
    grid = np.array(TIMES, dtype=fp_type)

    def run(y0, pars):
        ta.time = fp_type(0)
        ta.state[:] = y0
        ta.pars[:] = pars
        return ta.propagate_grid(grid)[-1]

    y0 = np.array(omega0, dtype=fp_type)
    pars = _pars(moments, D, fp_type)
    h = fp_type(h)
    out = {}
    for n in names:
        vec, k = (y0, "pqr".index(n)) if n in ("p", "q", "r") else (pars, _par_index(n))
        acc = np.zeros((len(TIMES), 3), dtype=fp_type)
        for s, w in FD_WEIGHTS.items():
            for sign in (1, -1):
                v = vec.copy()
                v[k] += sign * s * h
                acc += sign * fp_type(w) * (run(v, pars) if vec is y0 else run(y0, v))
        out[n] = acc / h
    return out


def _normwise(a, ref) -> float:
    """Worst over rows of max|a - ref| / max|ref| (rows with ref == 0: absolute difference)."""
    a, ref = np.asarray(a, dtype=np.longdouble), np.asarray(ref, dtype=np.longdouble)
    scale = np.max(np.abs(ref), axis=1)
    scale[scale == 0] = 1
    return float(np.max(np.max(np.abs(a - ref), axis=1) / scale))


def _componentwise(a, ref, floor=1e-3) -> float:
    """Worst |a - ref| / |ref| over components with |ref| > floor * max|ref of that row|."""
    a, ref = np.asarray(a, dtype=np.longdouble), np.asarray(ref, dtype=np.longdouble)
    big = np.abs(ref) > floor * np.max(np.abs(ref), axis=1, keepdims=True)
    return float(np.max(np.abs(a - ref)[big] / np.abs(ref)[big]))


def check(case: str, y, sens) -> None:
    moments, D, omega0, names = CASES[case]
    y_ld, sens_ld = variational(moments, D, omega0, names, fp_type=np.longdouble)
    y_lo, sens_lo = variational(moments, D, omega0, names, tol=1e-13)
    fd = central_differences(moments, D, omega0, names)
    print(f"{case}: vs long double: y {_normwise(y, y_ld):.2g}, sensitivities "
          f"{max(_normwise(sens[n], sens_ld[n]) for n in names):.2g} normwise, "
          f"{max(_componentwise(sens[n], sens_ld[n]) for n in names):.2g} componentwise")
    print(f"{case}: vs double tol=1e-13: y {_normwise(y_lo, y):.2g}, sensitivities "
          f"{max(_normwise(sens_lo[n], sens[n]) for n in names):.2g}")
    print(f"{case}: vs long-double 9-point central differences: "
          f"{max(_normwise(fd[n], sens[n]) for n in names):.2g} normwise "
          f"(worst: {max(names, key=lambda n: _normwise(fd[n], sens[n]))}); "
          f"long-double variational vs them: {max(_normwise(fd[n], sens_ld[n]) for n in names):.2g}")
    if not np.any(D):
        _check_invariants(case, moments, y, sens)


def _check_invariants(case, moments, y, sens) -> None:
    """Free body: T = ½ Σ A ω², |L|² = Σ A² ω² and their parameter derivatives are constant."""
    A = np.array(moments)
    drift = [np.ptp((A * y * y).sum(1)), np.ptp((A * A * y * y).sum(1))]
    for n in ("p", "q", "r"):  # d/dω0: Σ A ω S, Σ A² ω S
        drift += [np.ptp((A * y * sens[n]).sum(1)), np.ptp((A * A * y * sens[n]).sum(1))]
    for j in range(3):  # d(2T)/dA_j = ω_j² + 2 Σ A ω S
        drift.append(np.ptp(y[:, j] ** 2 + 2 * (A * y * sens[f"moments[{j}]"]).sum(1)))
    print(f"{case}: invariants (T, |L|^2 and their derivatives) drift at most {max(drift):.2g}")


def main(argv: list[str]) -> int:
    table = {"heyoka_version": hy.__version__, "cases": {}}
    for case, (moments, D, omega0, names) in CASES.items():
        y, sens = variational(moments, D, omega0, names)
        if "--no-check" not in argv:
            check(case, y, sens)
        table["cases"][case] = {
            "moments": list(moments), "D": [list(row) for row in D], "omega0": list(omega0),
            "t": list(TIMES), "parameters": list(names),
            "y": [[float(x) for x in row] for row in y],
            "sensitivity": {n: [[float(x) for x in row] for row in sens[n]] for n in names},
        }
    # json writes floats with repr(), i.e. the shortest string that round-trips the double.
    (HERE / "heyoka_sensitivities.json").write_text(json.dumps(table, indent=1) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
