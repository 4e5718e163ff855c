"""solve, solve_ensemble and the closed form of the torque-free body."""

from __future__ import annotations

import math
import warnings
from collections.abc import Sequence

import numpy as np

from gyrostat import _core
from gyrostat.model import Model
from gyrostat.solution import Solution

METHODS: tuple[str, ...] = tuple(_core.methods())
"""Integrators: ``dop853`` (fixed-size, allocation-free; the default for non-stiff problems),
``taylor`` (adaptive-order Taylor series for the polynomial right-hand sides of the gyrostat
with constant and linear torques: the fastest at tight tolerances), ``cvode_bdf`` (stiff),
``cvode_adams``, ``arkode_fehlberg8``, ``arkode_verner6`` (see docs/integrators.md)."""


def _output_times(t_span, t_eval, n_out) -> tuple[float, float, list[float]]:
    if len(t_span) != 2:
        raise ValueError(f"t_span must be (t0, t1), got {t_span!r}")
    t0, t1 = float(t_span[0]), float(t_span[1])
    if t_eval is not None and n_out is not None:
        raise ValueError("give t_eval or n_out, not both")
    if t_eval is None:
        n = 1001 if n_out is None else int(n_out)
        if n < 2:
            raise ValueError(f"n_out = {n_out} must be at least 2")
        if not (math.isfinite(t0) and math.isfinite(t1)):
            raise ValueError(f"t_span = ({t0}, {t1}) must be finite")
        t_eval = np.linspace(t0, t1, n)
    t_eval = np.asarray(t_eval, dtype=float)
    if t_eval.ndim != 1:
        raise ValueError(f"t_eval must be one-dimensional, got shape {t_eval.shape}")
    return t0, t1, t_eval.tolist()


def _state(model, y0) -> np.ndarray:
    y0 = np.asarray(y0, dtype=float).ravel()
    if model.attitude and y0.size == 3:
        y0 = np.concatenate([y0, [1.0, 0.0, 0.0, 0.0]])
    if y0.size != model.dim:
        raise ValueError(f"initial state has {y0.size} components; this model needs {model.dim} ({', '.join(model.state_names)})")
    return y0


def _solution(result: _core.Result) -> Solution:
    stats = result.stats
    return Solution(
        t=np.asarray(result.t),
        y=np.asarray(result.y),
        invariants={name: np.asarray(result.invariants[:, i]) for i, name in enumerate(result.invariant_names)},
        stats={
            "steps": stats.steps,
            "rhs_evals": stats.rhs_evals,
            "rejected_steps": stats.rejected_steps,
            "jacobian_evals": stats.jacobian_evals,
            "nonlinear_conv_failures": stats.nonlinear_conv_failures,
            "last_step": stats.last_step,
        },
        status=result.status,
        message=result.message,
        method=result.method,
    )


def _check_method(method: str) -> None:
    if method not in METHODS:
        raise ValueError(f"unknown method {method!r}; choose one of {', '.join(METHODS)}")
    if method == "arkode_verner6":
        warnings.warn(
            "arkode_verner6: the ARKODE_VERNER_8_5_6 table of SUNDIALS 6.4 converges at order 3, not 6 "
            "(measured; see docs/integrators.md): expect global errors far above rtol; prefer dop853",
            UserWarning, stacklevel=3)


def solve(
    model,
    y0,
    t_span,
    *,
    method: str = "dop853",
    rtol: float = 1e-8,
    atol: float = 1e-10,
    t_eval=None,
    n_out: int | None = None,
    every_step: bool = False,
    max_steps: int = 1_000_000,
    first_step: float = 0.0,
    max_step: float = math.inf,
    check_validity: bool = True,
) -> Solution:
    """Integrates a model (:class:`Model`, :class:`AveragedModel`, :class:`MovingMassModel`)
    from y0 over t_span = (t0, t1).

    For an averaged model the assumptions of the averaging (fast frequency against the slow
    rates along the solution, near symmetry, the torques' own conditions) are checked after the
    run: broken ones are warned about (:class:`gyrostat.ValidityWarning`) and listed in
    ``solution.notes``; ``check_validity=False`` skips this.

    Outputs are at ``t_eval`` or, by default, at ``n_out`` = 1001 evenly spaced times (dense
    output between steps, so memory grows with the outputs, not with the steps). With
    ``every_step=True`` every accepted step is recorded too.

    A run that fails (too many steps, step-size underflow, a non-finite state) returns the
    partial trajectory with ``status`` and ``message`` saying why; bad input (negative rtol,
    NaN state, t_eval outside the span) raises ValueError naming the value.
    """
    _check_method(method)
    t0, t1, times = _output_times(t_span, t_eval, n_out)
    y = _state(model, y0)
    result = _core.solve(model._core, y, t0, t1, method, float(rtol), float(atol), times, bool(every_step),
                         int(max_steps), float(first_step), float(max_step))
    solution = _solution(result)
    if check_validity and getattr(model, "kind", "") == "averaged" and solution.t.size:
        from gyrostat import validity

        broken = [a for a in validity.check(model, solution.y, solution.t, warn=True) if not a.holds]
        solution.notes += [f"assumption broken: {a}" for a in broken]
    return solution


def solve_ensemble(
    models: Model | Sequence[Model],
    y0s,
    t_span,
    *,
    method: str = "dop853",
    rtol: float = 1e-8,
    atol: float = 1e-10,
    t_eval=None,
    n_out: int | None = None,
    every_step: bool = False,
    max_steps: int = 1_000_000,
    first_step: float = 0.0,
    max_step: float = math.inf,
    threads: int = 0,
) -> list[Solution]:
    """Integrates N trajectories in one call on a pool of C++ threads (GIL released).

    ``y0s`` is (N, dim); ``models`` is one model for all members or a sequence of N. Results
    come in index order and equal single :func:`solve` runs exactly. A member with bad input
    gets ``status == "invalid_input"`` and its message; the others are unaffected.
    ``threads`` ≤ 0 uses every hardware thread.
    """
    _check_method(method)
    if not isinstance(models, (list, tuple)):
        models = [models]
    models = list(models)
    if not models:
        raise ValueError("solve_ensemble needs at least one model")
    y0s = np.asarray(y0s, dtype=float)
    if y0s.ndim != 2:
        raise ValueError(f"y0s must be (N, dim), got shape {y0s.shape}")
    if models[0].attitude and y0s.shape[1] == 3:
        y0s = np.hstack([y0s, np.tile([1.0, 0.0, 0.0, 0.0], (y0s.shape[0], 1))])
    if len(models) not in (1, y0s.shape[0]):
        raise ValueError(f"{len(models)} models for {y0s.shape[0]} initial states: give 1 or {y0s.shape[0]}")
    if y0s.shape[1] != models[0].dim:
        raise ValueError(f"y0s has {y0s.shape[1]} columns; the model needs {models[0].dim}")
    t0, t1, times = _output_times(t_span, t_eval, n_out)
    results = _core.solve_ensemble([m._core for m in models], y0s, t0, t1, method, float(rtol), float(atol), times,
                                   bool(every_step), int(max_steps), float(first_step), float(max_step), int(threads))
    return [_solution(r) for r in results]


def torque_free(body: _core.Body, omega0, t_eval) -> Solution:
    """ω(t) of a torque-free rigid body in closed form (Jacobi elliptic functions): no integration.

    Valid for a body without rotor (k = 0) and no torque; the attitude is not part of the closed
    form. Returns a :class:`Solution` with ``method == "closed_form"`` and the invariants.
    """
    omega0 = np.asarray(omega0, dtype=float).ravel()
    if omega0.size != 3:
        raise ValueError(f"omega0 must have 3 components, got {omega0.size}")
    t = np.asarray(t_eval, dtype=float).ravel()
    if not np.all(np.isfinite(t)):
        raise ValueError("t_eval has non-finite values")
    exact = _core.TorqueFreeSolution(body, omega0, float(t[0]) if t.size else 0.0)
    omega = np.asarray(exact.omega(t.tolist()))
    moments = np.asarray(body.moments)
    solution = Solution(
        t=t,
        y=omega,
        invariants={
            "angular_momentum_norm": np.linalg.norm(omega * moments, axis=1),
            "kinetic_energy": 0.5 * np.sum(moments * omega**2, axis=1),
        },
        stats={"steps": 0, "rhs_evals": 0, "rejected_steps": 0, "jacobian_evals": 0,
               "nonlinear_conv_failures": 0, "last_step": 0.0},
        status="success",
        message="",
        method="closed_form",
    )
    solution.notes.append(
        f"closed form: m = k^2 = {exact.modulus_squared:.6g}, period of omega = {exact.period:.6g}")
    return solution
