"""Paper 004: a free gyrostat under a servo torque orthogonal to its momentum G and its angular
velocity ω (Makeev). Derivation, checks and measured errors: docs/papers/004_orthogonal_torque.md.

The torque is M = L(t) e_L, e_L = Q/|Q|, Q = ω × G, G = Jω + k. It keeps |G| and h = ω·Jω
exactly, and the motion is the torque-free Zhukovsky–Volterra (ZV) gyrostat run on the clock

    τ(t) = ∫ g dt,   g = dτ/dt = 1 − L(t)/|Q(ω)|,      ω(t) = ω_ZV(τ(t)).

At Q = 0 the direction is undefined: below the threshold |Q| < δ = η|ω||G| (η = 1e-3 by
default) the core tapers the torque to L Q/n, n = (|Q|² + δ²)/(2δ) (C¹ at |Q| = δ, zero torque
at Q = 0); at and above it the paper's L Q/|Q| is applied exactly. Both invariants and the clock
stay exact; where |Q| < δ the prescribed L is not applied, and the solution flags those times.

Contents: magnitude laws (:func:`constant`, :func:`polynomial`, :func:`harmonic`,
:func:`tabulated`), :class:`OrthogonalModel`, :func:`solve` (→ :class:`OrthogonalSolution`
with τ(t), g(t), |Q|, the invariants, the angles of G in body axes, and a report of where g ≤ 0),
:func:`torque_free_at_tau` (ω_ZV(τ)), the nearly spherical approximations of §4
(:class:`NearlySpherical`) and :func:`run_scene` for scene files with ``kind = "orthogonal_torque"``.
"""

from __future__ import annotations

import json
import math
import time
import tomllib
import warnings
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from gyrostat import _core
from gyrostat.model import Model, _check_torques
from gyrostat.solution import Solution
from gyrostat.solve import _check_method, _output_times, _solution, solve as _solve

ETA = 1e-3
"""Default regularisation: δ = η |ω| |G|."""

STATE_NAMES_RATES = ("p", "q", "r", "tau")
STATE_NAMES_ATTITUDE = ("p", "q", "r", "q_w", "q_x", "q_y", "q_z", "tau")


# ------------------------------------------------------------------------------ magnitude laws
def _finite(value, what: str) -> float:
    try:
        x = float(value)
    except (TypeError, ValueError):
        raise ValueError(f"{what} = {value!r} is not a number") from None
    if not math.isfinite(x):
        raise ValueError(f"{what} = {x} is not finite")
    return x


def constant(value: float) -> _core.MagnitudeLaw:
    """L(t) = value."""
    return _core.MagnitudeLaw.constant(_finite(value, "constant L"))


def polynomial(coefficients: Sequence[float]) -> _core.MagnitudeLaw:
    """L(t) = Σ c_i tⁱ, coefficients (c0, c1, …)."""
    return _core.MagnitudeLaw.polynomial([_finite(c, f"polynomial coefficient {i}") for i, c in enumerate(coefficients)])


def harmonic(mean: float, amplitudes: Sequence[float] = (), frequencies: Sequence[float] = (),
             phases: Sequence[float] | None = None) -> _core.MagnitudeLaw:
    """L(t) = L0 + Σ A_i sin(w_i t + φ_i) (phases default to 0)."""
    amplitudes = [float(a) for a in np.atleast_1d(amplitudes)]
    frequencies = [float(w) for w in np.atleast_1d(frequencies)]
    phases = [0.0] * len(amplitudes) if phases is None else [float(p) for p in np.atleast_1d(phases)]
    return _core.MagnitudeLaw.harmonic(_finite(mean, "harmonic mean L0"), amplitudes, frequencies, phases)


def tabulated(times: Sequence[float], values: Sequence[float], interpolation: str = "linear") -> _core.MagnitudeLaw:
    """L(t) interpolated in a table (``"linear"`` or ``"cubic"`` Hermite); held constant outside it.
    Times must increase strictly: a zero or negative spacing raises ValueError naming it."""
    if interpolation not in ("linear", "cubic"):
        raise ValueError(f"interpolation = {interpolation!r}: choose 'linear' or 'cubic'")
    return _core.MagnitudeLaw.tabulated([float(t) for t in np.ravel(times)], [float(v) for v in np.ravel(values)],
                                        interpolation == "cubic")


def law_from_spec(spec: dict | float) -> _core.MagnitudeLaw:
    """A law from a scene table: a number, or {kind = "constant"|"polynomial"|"harmonic"|"tabulated", …}."""
    if isinstance(spec, (int, float)):
        return constant(spec)
    kind = spec.get("kind", "constant")
    if kind == "constant":
        return constant(spec["value"])
    if kind == "polynomial":
        return polynomial(spec["coefficients"])
    if kind == "harmonic":
        return harmonic(spec["mean"], spec.get("amplitudes", ()), spec.get("frequencies", ()), spec.get("phases"))
    if kind == "tabulated":
        return tabulated(spec["times"], spec["values"], spec.get("interpolation", "linear"))
    raise ValueError(f"law kind = {kind!r}: choose constant, polynomial, harmonic or tabulated")


# ------------------------------------------------------------------------------ the model
class OrthogonalModel:
    """Gyrostat under the servo torque L(t) Q/|Q| (regularised), plus optional other torques.

    State: (p, q, r, τ) or, with ``attitude=True``, (p, q, r, q_w, q_x, q_y, q_z, τ). Invariants
    recorded: ``angular_momentum_norm`` |G| and ``h`` = ω·Jω (exact without other torques).

    ``regularisation``: ``"threshold"`` (default: the paper's torque wherever |Q| ≥ δ = η|ω||G|,
    tapered to L Q/n, n = (|Q|² + δ²)/(2δ), below) or ``"smooth"`` (L Q/√(|Q|² + δ²) everywhere:
    smooth, but the applied L is off by a relative δ²/2|Q|² at every |Q|).
    """

    kind = "orthogonal_torque"

    def __init__(self, body: _core.Body, law: _core.MagnitudeLaw | float, torques: Sequence = (),
                 attitude: bool = False, eta: float = ETA, regularisation: str = "threshold"):
        if not isinstance(body, _core.Body):
            raise TypeError(f"body must be a gyrostat.Body, not {type(body).__name__}")
        if not isinstance(law, _core.MagnitudeLaw):
            law = constant(law)
        self.body, self.law = body, law
        self.torques = _check_torques(torques)
        self.attitude = bool(attitude)
        self.eta = _finite(eta, "eta")
        if regularisation not in ("threshold", "smooth"):
            raise ValueError(f"regularisation = {regularisation!r}: choose 'threshold' or 'smooth'")
        self.regularisation = regularisation
        self._core = _core.orthogonal_model(body, law, list(self.torques), self.attitude, self.eta,
                                            regularisation == "smooth")

    @property
    def dim(self) -> int:
        return self._core.dim

    @property
    def state_names(self) -> tuple[str, ...]:
        return STATE_NAMES_ATTITUDE if self.attitude else STATE_NAMES_RATES

    @property
    def moments(self) -> np.ndarray:
        return np.asarray(self.body.moments, float)

    @property
    def rotor(self) -> np.ndarray:
        return np.asarray(self.body.rotor, float)

    def rhs(self, t: float, y):
        return self._core.rhs(float(t), np.asarray(y, float))

    def tau_rate(self, t, omega) -> np.ndarray:
        """g = dτ/dt at times t for angular velocities omega (n, 3)."""
        t = np.atleast_1d(np.asarray(t, float))
        return np.asarray(self._core.tau_rate(t, np.atleast_2d(np.asarray(omega, float))))

    def torque_free(self, attitude: bool | None = None) -> Model:
        """The Zhukovsky–Volterra gyrostat of the same body (the full model without torque)."""
        return Model(self.body, attitude=self.attitude if attitude is None else attitude)

    def __repr__(self) -> str:
        return (f"OrthogonalModel({self.body!r}, law={self.law.kind}, attitude={self.attitude}, eta={self.eta}, "
                f"regularisation={self.regularisation!r})")


@dataclass
class OrthogonalSolution(Solution):
    """A :class:`Solution` of :class:`OrthogonalModel` plus the derived outputs:

    tau, g: the clock τ(t) and its rate g = 1 − L/|Q| (regularised below δ); law: L(t); q_norm: |Q(ω(t))|;
    delta: δ(t); regularised: |Q| < δ (the prescribed L was not applied there);
    g_report: where g ≤ 0 (τ stops or runs backwards), with times and values (:func:`tau_report`).
    """

    tau: np.ndarray = None
    g: np.ndarray = None
    law: np.ndarray = None
    q_norm: np.ndarray = None
    delta: np.ndarray = None
    regularised: np.ndarray = None
    g_report: dict = None
    moments: np.ndarray = None
    rotor: np.ndarray = None

    def momentum(self) -> np.ndarray:
        """(n, 3) G = Jω + k in body axes."""
        return self.omega * self.moments + self.rotor

    def momentum_angles(self) -> np.ndarray:
        """(n, 2) θ, φ of G in body axes (paper (15)): G/|G| = (sinθ sinφ, sinθ cosφ, cosθ).
        These equal the Euler angles θ, φ of (16) at τ(t); they need no attitude."""
        G = self.momentum()
        s = G / np.linalg.norm(G, axis=1)[:, None]
        return np.column_stack([np.arccos(np.clip(s[:, 2], -1, 1)), np.arctan2(s[:, 0], s[:, 1])])


def _quaternion_state(model, omega0, quaternion0) -> np.ndarray:
    omega0 = np.asarray(omega0, float).ravel()
    if omega0.size != 3:
        raise ValueError(f"omega0 must have 3 components, got {omega0.size}")
    if model.attitude:
        q0 = np.array([1.0, 0, 0, 0]) if quaternion0 is None else np.asarray(quaternion0, float).ravel()
        if q0.size != 4:
            raise ValueError(f"quaternion0 must have 4 components (w, x, y, z), got {q0.size}")
        return np.concatenate([omega0, q0, [0.0]])
    if quaternion0 is not None:
        raise ValueError("quaternion0 given but the model has no attitude: use OrthogonalModel(..., attitude=True)")
    return np.concatenate([omega0, [0.0]])


def solve(model: OrthogonalModel, omega0, t_span, *, quaternion0=None, method: str = "dop853", rtol: float = 1e-10,
          atol: float = 1e-12, t_eval=None, n_out: int | None = None, every_step: bool = False,
          max_steps: int = 1_000_000, first_step: float = 0.0, max_step: float = math.inf,
          freeze_tol: float = 1e-6) -> OrthogonalSolution:
    """Integrates the model in real time t from ω0 (τ(t0) = 0). ``method``: any of gyrostat.METHODS
    except ``taylor`` (the servo torque is not polynomial: ValueError). Bad input (NaN, negative
    tolerances, …) raises ValueError naming the value."""
    if not isinstance(model, OrthogonalModel):
        raise TypeError(f"model must be an OrthogonalModel, not {type(model).__name__}")
    _check_method(method)
    t0, t1, times = _output_times(t_span, t_eval, n_out)
    y0 = _quaternion_state(model, omega0, quaternion0)
    result = _core.solve_orthogonal(model._core, y0, t0, t1, method, float(rtol), float(atol), times,
                                    bool(every_step), int(max_steps), float(first_step), float(max_step))
    return _finish(model, _solution(result), freeze_tol)


def solve_ensemble(model: OrthogonalModel, omega0s, t_span, *, quaternion0s=None, method: str = "dop853",
                   rtol: float = 1e-10, atol: float = 1e-12, t_eval=None, n_out: int | None = None,
                   max_steps: int = 1_000_000, threads: int = 0) -> list[OrthogonalSolution]:
    """N initial angular velocities (N, 3) (and quaternions (N, 4) with attitude) of one model in
    one call on C++ threads (GIL released); results in index order, equal to single runs."""
    if not isinstance(model, OrthogonalModel):
        raise TypeError(f"model must be an OrthogonalModel, not {type(model).__name__}")
    _check_method(method)
    omega0s = np.atleast_2d(np.asarray(omega0s, float))
    if omega0s.shape[1] != 3:
        raise ValueError(f"omega0s must be (N, 3), got shape {omega0s.shape}")
    qs = [None] * len(omega0s) if quaternion0s is None else np.atleast_2d(np.asarray(quaternion0s, float))
    if model.attitude and quaternion0s is None:
        qs = [np.array([1.0, 0, 0, 0])] * len(omega0s)
    y0s = np.array([_quaternion_state(model, w, q) for w, q in zip(omega0s, qs)])
    t0, t1, times = _output_times(t_span, t_eval, n_out)
    results = _core.solve_orthogonal_ensemble(model._core, y0s, t0, t1, method, float(rtol), float(atol), times,
                                              int(max_steps), int(threads))
    return [_finish(model, _solution(r)) for r in results]


def _finish(model: OrthogonalModel, base: Solution, freeze_tol: float = 1e-6) -> OrthogonalSolution:
    sol = OrthogonalSolution(**{k: getattr(base, k) for k in ("t", "y", "invariants", "stats", "status", "message",
                                                             "method", "notes")})
    sol.moments, sol.rotor = model.moments, model.rotor
    n = sol.t.size
    sol.tau = sol.y[:, -1].copy() if n else np.zeros(0)
    if n:
        omega = sol.omega
        G = sol.momentum()
        Q = np.cross(omega, G)
        sol.q_norm = np.linalg.norm(Q, axis=1)
        sol.delta = model.eta * np.linalg.norm(omega, axis=1) * np.linalg.norm(G, axis=1)
        sol.law = np.asarray(model.law.values(sol.t))
        sol.g = model.tau_rate(sol.t, omega)
        sol.regularised = sol.q_norm < sol.delta
    else:
        sol.q_norm = sol.delta = sol.law = sol.g = np.zeros(0)
        sol.regularised = np.zeros(0, bool)
    sol.g_report = tau_report(model, sol, freeze_tol)
    sol.notes.extend(sol.g_report["messages"])
    return sol


def tau_report(model: OrthogonalModel, sol: OrthogonalSolution, freeze_tol: float = 1e-6) -> dict:
    """Where g = dτ/dt ≤ 0: zero crossings (time, τ, |Q|, L), intervals with g < 0, the minimum of
    g, a frozen end state (|g| and |ω̇| below freeze_tol), and times where |Q| < δ.

    What the motion does: ω moves along the torque-free orbit with speed g. Where g = 0 the servo
    torque cancels ω × G and ω stands still (a uniform rotation about a fixed inertial axis);
    where g < 0 the body retraces the ZV orbit backwards (τ decreases)."""
    t, g, tau = sol.t, sol.g, sol.tau
    report = {"min_g": None, "t_min_g": None, "crossings": [], "negative_intervals": [], "frozen": None,
              "regularised_times": [], "messages": []}
    if t.size == 0:
        return report
    i = int(np.argmin(g))
    report["min_g"], report["t_min_g"] = float(g[i]), float(t[i])
    sign = np.sign(g)
    for j in np.nonzero(sign[:-1] != sign[1:])[0]:
        if g[j] == 0 and j > 0:
            continue
        w = g[j] / (g[j] - g[j + 1]) if g[j] != g[j + 1] else 0.0
        tc = float(t[j] + w * (t[j + 1] - t[j]))
        entry = {"t": tc, "tau": float(tau[j] + w * (tau[j + 1] - tau[j])),
                 "q_norm": float(sol.q_norm[j] + w * (sol.q_norm[j + 1] - sol.q_norm[j])),
                 "L": float(model.law(tc)), "direction": "down" if g[j] > g[j + 1] else "up"}
        report["crossings"].append(entry)
    negative = g < 0
    if np.any(negative):
        edges = np.diff(np.concatenate([[0], negative.astype(int), [0]]))
        starts, ends = np.nonzero(edges == 1)[0], np.nonzero(edges == -1)[0] - 1
        for a, b in zip(starts, ends):
            report["negative_intervals"].append({"t_start": float(t[a]), "t_end": float(t[b]),
                                                 "min_g": float(g[a:b + 1].min())})
    dy = model.rhs(t[-1], sol.y[-1])
    rate = float(np.linalg.norm(dy[:3]))
    if abs(g[-1]) < freeze_tol or rate < freeze_tol:
        report["frozen"] = {"t": float(t[-1]), "g": float(g[-1]), "omega_rate": rate, "tau": float(tau[-1]),
                            "q_norm": float(sol.q_norm[-1]), "L": float(sol.law[-1])}
    if np.any(sol.regularised):
        report["regularised_times"] = [float(t[sol.regularised].min()), float(t[sol.regularised].max())]
    msgs = report["messages"]
    msgs.append(f"g = dtau/dt >= {report['min_g']:.4g} (minimum at t = {report['t_min_g']:.6g}); "
                f"tau(t_end) = {tau[-1]:.8g}")
    for c in report["crossings"]:
        what = ("g falls through 0: tau stops and then runs backwards (the body retraces the torque-free orbit; "
                "not L-reducible forward in time)" if c["direction"] == "down" else
                "g rises through 0: tau turns forward again")
        msgs.append(f"t = {c['t']:.6g} (tau = {c['tau']:.6g}, |Q| = {c['q_norm']:.6g}, L = {c['L']:.6g}): {what}")
    if report["frozen"]:
        f = report["frozen"]
        msgs.append(f"frozen at the end: |g| = {abs(f['g']):.2e}, |domega/dt| = {f['omega_rate']:.2e}, |Q| = "
                    f"{f['q_norm']:.8g} ~ L = {f['L']:.6g}: the torque cancels omega x G, tau -> {f['tau']:.8g}")
    if report["regularised_times"]:
        a, b = report["regularised_times"]
        msgs.append(f"|Q| < delta = eta|omega||G| in t in [{a:.6g}, {b:.6g}]: the prescribed L was not applied there "
                    f"(regularised torque L Q/n, n = (|Q|^2 + delta^2)/(2 delta))")
    return report


def orbit_q_range(model: OrthogonalModel, omega0, span: float | None = None, n: int = 20001) -> tuple[float, float]:
    """min and max of |Q| along the torque-free orbit through ω0 (sampled over τ ∈ [0, span]).
    For a constant L this decides the regime: L < min: τ → +∞; L > max: τ → −∞; in between:
    τ converges to a τ* with |Q(τ*)| = L (the motion freezes)."""
    omega0 = np.asarray(omega0, float)
    J, k = model.moments, model.rotor
    if span is None:
        span = 400.0 / (np.linalg.norm(omega0) + np.linalg.norm(k) / J.min() + 1e-300)
    zv = _solve(model.torque_free(attitude=False), omega0, (0.0, span), n_out=n, rtol=1e-10, atol=1e-12)
    Q = np.cross(zv.omega, zv.omega * J + k)
    q = np.linalg.norm(Q, axis=1)
    return float(q.min()), float(q.max())


def constant_law_regime(model: OrthogonalModel, omega0) -> str | None:
    """For a constant L: which of the three regimes (docs §Singular cases) applies; None otherwise."""
    if model.law.kind != "constant":
        return None
    L = model.law(0.0)
    qmin, qmax = orbit_q_range(model, omega0)
    if L < qmin:
        return f"L = {L:.6g} < min|Q| = {qmin:.6g} on the torque-free orbit: tau increases without bound"
    if L > qmax:
        return f"L = {L:.6g} > max|Q| = {qmax:.6g} on the torque-free orbit: tau decreases without bound"
    return (f"min|Q| = {qmin:.6g} < L = {L:.6g} < max|Q| = {qmax:.6g}: tau converges to tau* with |Q(tau*)| = L "
            f"and the motion freezes (uniform rotation)")


# ------------------------------------------------------------------------------ torque-free at τ
def _evaluate_at(model: Model, y0, tau, **options) -> np.ndarray:
    """States of a torque-free model at arbitrary (not monotone) times τ from y0 at τ = 0."""
    tau = np.asarray(tau, float).ravel()
    values, inverse = np.unique(tau, return_inverse=True)
    out = np.empty((values.size, model.dim))
    options = {"rtol": 1e-12, "atol": 1e-13, **options}
    forward, backward = values >= 0, values < 0
    if np.any(forward):
        times = values[forward]
        grid = times if times[0] == 0 else np.concatenate([[0.0], times])
        s = _solve(model, y0, (0.0, max(grid[-1], 1e-300)), t_eval=grid, **options).raise_for_status()
        out[forward] = s.y[grid.size - times.size:]
    if np.any(backward):
        times = values[backward][::-1]
        grid = np.concatenate([[0.0], times])
        s = _solve(model, y0, (0.0, grid[-1]), t_eval=grid, **options).raise_for_status()
        out[backward] = s.y[1:][::-1]
    return out[inverse]


def torque_free_at_tau(model: OrthogonalModel, omega0, tau, quaternion0=None, **options) -> np.ndarray:
    """The Zhukovsky–Volterra solution through ω0 (and q0 when given) at the times τ: (n, 3) or
    (n, 7). Compare ω(t) with ``torque_free_at_tau(model, ω0, solution.tau)``. The attitude does
    not map through τ (the servo torque turns the inertial G): only ω and the angles of G do."""
    free = model.torque_free(attitude=quaternion0 is not None)
    y0 = np.asarray(omega0, float) if quaternion0 is None else np.concatenate([omega0, quaternion0])
    return _evaluate_at(free, y0, tau, **options)


# ------------------------------------------------------------------------------ Euler angles
def rz(a: float) -> np.ndarray:
    c, s = math.cos(a), math.sin(a)
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


def rx(a: float) -> np.ndarray:
    c, s = math.cos(a), math.sin(a)
    return np.array([[1.0, 0.0, 0.0], [0.0, c, -s], [0.0, s, c]])


def r313(psi: float, theta: float, phi: float) -> np.ndarray:
    """Body → inertial rotation Rz(ψ) Rx(θ) Rz(φ) (paper (15): R^T e3 = (sinθ sinφ, sinθ cosφ, cosθ))."""
    return rz(psi) @ rx(theta) @ rz(phi)


def quaternion_from_matrix(R: np.ndarray) -> np.ndarray:
    """Unit quaternion (w, x, y, z) of a rotation matrix (Shepperd's method)."""
    t = np.trace(R)
    i = int(np.argmax([t, R[0, 0], R[1, 1], R[2, 2]]))
    if i == 0:
        w = math.sqrt(1 + t) / 2
        q = [w, (R[2, 1] - R[1, 2]) / (4 * w), (R[0, 2] - R[2, 0]) / (4 * w), (R[1, 0] - R[0, 1]) / (4 * w)]
    elif i == 1:
        x = math.sqrt(1 + 2 * R[0, 0] - t) / 2
        q = [(R[2, 1] - R[1, 2]) / (4 * x), x, (R[0, 1] + R[1, 0]) / (4 * x), (R[0, 2] + R[2, 0]) / (4 * x)]
    elif i == 2:
        y = math.sqrt(1 + 2 * R[1, 1] - t) / 2
        q = [(R[0, 2] - R[2, 0]) / (4 * y), (R[0, 1] + R[1, 0]) / (4 * y), y, (R[1, 2] + R[2, 1]) / (4 * y)]
    else:
        z = math.sqrt(1 + 2 * R[2, 2] - t) / 2
        q = [(R[1, 0] - R[0, 1]) / (4 * z), (R[0, 2] + R[2, 0]) / (4 * z), (R[1, 2] + R[2, 1]) / (4 * z), z]
    q = np.asarray(q)
    return q / np.linalg.norm(q)


def attitude_along_momentum(G0, psi0: float = 0.0) -> np.ndarray:
    """The quaternion of R313(ψ0, θ0, φ0) with θ0, φ0 the angles of G0 in body axes, so that the
    inertial z3 axis lies along G (the frame of the paper's Euler angles (15))."""
    s = np.asarray(G0, float) / np.linalg.norm(G0)
    return quaternion_from_matrix(r313(psi0, math.acos(max(-1.0, min(1.0, s[2]))), math.atan2(s[0], s[1])))


def _angles_from_matrices(R: np.ndarray) -> np.ndarray:
    """(n, 3) (ψ, θ, φ) z-x-z of body → inertial matrices (n, 3, 3)."""
    theta = np.arccos(np.clip(R[:, 2, 2], -1, 1))
    return np.column_stack([np.arctan2(R[:, 0, 2], -R[:, 1, 2]), theta, np.arctan2(R[:, 2, 0], R[:, 2, 1])])


def wrap(angle):
    """Angle (differences) to (−π, π]."""
    return (np.asarray(angle) + np.pi) % (2 * np.pi) - np.pi


# ------------------------------------------------------------------------------ nearly spherical
@dataclass
class NearlySpherical:
    """A nearly spherical gyrostat A_j = J + μ J_j (paper §4) with rotor k, |G| = G, and an
    initial attitude given by the Euler angles (ψ0, θ0, φ0) with the inertial z3 axis along G.

    Angles are functions of the torque-free time τ; in the full model evaluate them at τ(t).
    Implemented (they hold; errors measured in tests/test_orthogonal.py and the docs):

    * :meth:`zeroth` — μ = 0, the spherical gyrostat, closed form for any k:
      R(τ) = Rz(Gτ/J) R0 Rot(k̂, |k|τ/J)ᵀ, i.e. s = G/|G| rotates about k at rate |k|/J and
      Jψ' = G − N1/sinθ. Error O(μ) at fixed τ, O(1) on τ ~ 1/μ.
    * :meth:`first` — (21) + μ(22) with the corrected ψ row (−PG, not −JPG). (16) is linear in
      a_j = 1/A_j, so this field is exactly (16) with a_j = (1 − μ b_j)/J: the ZV gyrostat with
      moments J/(1 − μ b_j), solved here by the library. Error O(μ²) at fixed τ, O(μ) on τ ~ 1/μ.
    * k = 0 results: :meth:`rigid_orbit` (sin²θ (P(φ) − b3) = const), :meth:`orbit_29` (the
      paper's (29), error O(μ) + O(n²)), :meth:`mean_precession_rate` ((34) corrected:
      (1 − μP*)G/J), :meth:`mean_spin_rate` (from the φ period quadrature) and
      :meth:`mean_spin_rate_simple` (μ D2 cosθ0/J, ⟨cosθ⟩ ≈ cosθ0).
    """

    J: float
    Jj: Sequence[float]
    mu: float
    k: Sequence[float] = (0.0, 0.0, 0.0)
    G: float = 1.0
    theta0: float = 1.0
    phi0: float = 0.0
    psi0: float = 0.0

    def __post_init__(self):
        self.J = _finite(self.J, "J")
        self.mu = _finite(self.mu, "mu")
        self.G = _finite(self.G, "G")
        self.Jj = np.asarray(self.Jj, float)
        self.k = np.asarray(self.k, float)
        if self.J <= 0:
            raise ValueError(f"J = {self.J} must be positive")
        if not (np.all(np.isfinite(self.Jj)) and np.all(np.isfinite(self.k))):
            raise ValueError(f"Jj = {self.Jj.tolist()} and k = {self.k.tolist()} must be finite")
        if not 0 < math.sin(self.theta0):
            raise ValueError(f"theta0 = {self.theta0}: the Euler angles (16) are singular at sin(theta) = 0")

    @property
    def b(self) -> np.ndarray:
        return self.Jj / self.J

    @property
    def moments(self) -> np.ndarray:
        return self.J + self.mu * self.Jj

    def body(self) -> _core.Body:
        return _core.Body(self.moments, self.k)

    @property
    def R0(self) -> np.ndarray:
        return r313(self.psi0, self.theta0, self.phi0)

    def initial_state(self) -> tuple[np.ndarray, np.ndarray]:
        """ω0 = A⁻¹(G s0 − k) and q0 (inertial z3 along G)."""
        s0 = self.R0[2, :]
        return (self.G * s0 - self.k) / self.moments, quaternion_from_matrix(self.R0)

    def exact(self, tau, **options) -> np.ndarray:
        """(n, 3) (ψ, θ, φ) of the ZV gyrostat with the true moments (the reference in τ)."""
        return self._zv_angles(self.moments, tau, **options)

    def zeroth(self, tau) -> np.ndarray:
        """(n, 3) (ψ, θ, φ) of the zeroth approximation (21), closed form."""
        tau = np.atleast_1d(np.asarray(tau, float))
        knorm = float(np.linalg.norm(self.k))
        R = np.empty((tau.size, 3, 3))
        for i, s in enumerate(tau):
            B = _rotation(self.k / knorm, knorm * s / self.J) if knorm > 0 else np.eye(3)
            R[i] = rz(self.G * s / self.J) @ self.R0 @ B.T
        return _angles_from_matrices(R)

    def first(self, tau, **options) -> np.ndarray:
        """(n, 3) (ψ, θ, φ) of the first approximation (21) + μ(22), ψ row corrected."""
        a = (1 - self.mu * self.b) / self.J
        if np.any(a <= 0):
            raise ValueError(f"1 - mu b_j = {(1 - self.mu * self.b).tolist()} must be positive: mu = {self.mu} too large")
        return self._zv_angles(1 / a, tau, **options)

    def _zv_angles(self, moments, tau, **options) -> np.ndarray:
        model = Model(_core.Body(np.asarray(moments, float), self.k), attitude=True)
        s0 = self.R0[2, :]
        y0 = np.concatenate([(self.G * s0 - self.k) / moments, quaternion_from_matrix(self.R0)])
        y = _evaluate_at(model, y0, tau, **options)
        return Solution(np.zeros(len(y)), y, {}, {}, "success", "", "").euler_angles()

    # ---- k = 0 (rigid nearly spherical body)
    def _P(self, phi):
        b1, b2, _ = self.b
        return b1 * np.sin(phi) ** 2 + b2 * np.cos(phi) ** 2

    @property
    def P_star(self) -> float:
        return 0.5 * (self.b[0] + self.b[1])

    @property
    def D1(self) -> float:
        return (self.b[1] - self.b[0]) * self.G

    @property
    def D2(self) -> float:
        return (self.P_star - self.b[2]) * self.G

    def _rigid(self):
        if np.any(self.k):
            raise ValueError(f"k = {self.k.tolist()}: the reduced results (28)-(34) hold for k = 0 only "
                             "(docs/papers/004_orthogonal_torque.md)")

    def rigid_orbit(self, phi) -> np.ndarray:
        """sinθ(φ) on the exact first-order orbit sin²θ (P(φ) − b3) = sin²θ0 (P(φ0) − b3) (k = 0)."""
        self._rigid()
        c = math.sin(self.theta0) ** 2 * (self._P(self.phi0) - self.b[2])
        return np.sqrt(c / (self._P(np.asarray(phi, float)) - self.b[2]))

    def orbit_29(self, phi) -> np.ndarray:
        """The paper's (29): sinθ ≈ sinθ0 exp[n (sin²φ − sin²φ0)], n = D1/(2 D2) (k = 0)."""
        self._rigid()
        n = self.D1 / (2 * self.D2)
        return math.sin(self.theta0) * np.exp(n * (np.sin(np.asarray(phi, float)) ** 2 - math.sin(self.phi0) ** 2))

    def mean_precession_rate(self) -> float:
        """(34) corrected: Ω = (1 − μP*) G / J (printed: P* G/J)."""
        self._rigid()
        return (1 - self.mu * self.P_star) * self.G / self.J

    def mean_spin_rate_simple(self) -> float:
        """(34) corrected, crude: μ D2 cosθ0 / J (printed: D2/J)."""
        self._rigid()
        return self.mu * self.D2 * math.cos(self.theta0) / self.J

    def mean_spin_rate(self, n: int = 4096) -> float:
        """±2π/T_φ with T_φ = (J/μ) ∫0^{2π} dφ / (|P(φ) − b3| G |cosθ(φ)|) on the exact first-order
        orbit (k = 0); the sign is that of (P − b3) cosθ0. Trapezoid rule on a periodic integrand."""
        self._rigid()
        phi = np.linspace(0, 2 * np.pi, n, endpoint=False)
        u = self.rigid_orbit(phi)
        if np.any(u >= 1):
            raise ValueError("the first-order orbit reaches sin(theta) = 1: phi does not rotate (no mean spin)")
        P = self._P(phi) - self.b[2]
        integrand = 1.0 / (np.abs(P) * self.G * np.sqrt(1 - u * u))
        period = self.J / abs(self.mu) * integrand.mean() * 2 * np.pi
        return float(np.sign(P[0] * math.cos(self.theta0) * self.mu) * 2 * np.pi / period)


def _rotation(axis: np.ndarray, angle: float) -> np.ndarray:
    """Rodrigues: rotation by angle about the unit axis."""
    K = np.array([[0, -axis[2], axis[1]], [axis[2], 0, -axis[0]], [-axis[1], axis[0], 0]])
    return np.eye(3) + math.sin(angle) * K + (1 - math.cos(angle)) * K @ K


# ------------------------------------------------------------------------------ scenes
UNITS = {"t": "s", "p": "rad/s", "q": "rad/s", "r": "rad/s", "q_w": "1", "q_x": "1", "q_y": "1", "q_z": "1",
         "tau": "s", "g": "1", "L": "N m", "Q_norm": "kg m^2/s^2", "angular_momentum_norm": "kg m^2/s",
         "h": "kg m^2/s^2", "theta_G": "rad", "phi_G": "rad", "psi": "rad", "theta": "rad", "phi": "rad"}


@dataclass
class OrthogonalScene:
    """A scene file with ``kind = "orthogonal_torque"``::

        kind = "orthogonal_torque"
        title = "..."
        [body]                      # a triaxial gyrostat, or instead [nearly_spherical]
        moments = [2.0, 3.0, 4.0]
        rotor = [0.3, -0.2, 0.5]
        [nearly_spherical]          # A_j = J + mu J_j; the initial state from G, theta0, phi0, psi0
        J = 2.0; Jj = [1.0, -0.6, 1.6]; mu = 0.05; rotor = [0.6, 0.8, 0.0]; G = 2.0
        theta0 = 1.0; phi0 = 1.1435; psi0 = 0.0
        [initial]                   # with [body]: omega and (optional) attitude quaternion
        omega = [1.0, 0.5, -0.8]
        attitude = [1.0, 0.0, 0.0, 0.0]   # optional; default: inertial z3 along G(0), psi0 = 0
        [[runs]]                    # one run per magnitude law
        name = "constant"
        law = { kind = "constant", value = 0.15 }     # or harmonic / polynomial / tabulated
        [integration]
        method = "dop853"; rtol = 1e-10; atol = 1e-12; t_span = [0.0, 60.0]; n_out = 1201; eta = 1e-3
    """

    name: str
    title: str
    body: _core.Body
    omega0: np.ndarray
    quaternion0: np.ndarray
    runs: list
    method: str
    rtol: float
    atol: float
    t_span: tuple
    n_out: int
    eta: float
    spherical: NearlySpherical | None = None

    @classmethod
    def from_toml(cls, path) -> "OrthogonalScene":
        path = Path(path)
        with path.open("rb") as handle:
            data = tomllib.load(handle)
        where = path.name
        spherical = None
        if "nearly_spherical" in data:
            s = data["nearly_spherical"]
            spherical = NearlySpherical(s["J"], s["Jj"], s["mu"], s.get("rotor", (0, 0, 0)), s.get("G", 1.0),
                                        s.get("theta0", 1.0), s.get("phi0", 0.0), s.get("psi0", 0.0))
            body = spherical.body()
            omega0, q0 = spherical.initial_state()
        elif "body" in data:
            body = _core.Body(np.asarray(data["body"]["moments"], float),
                              np.asarray(data["body"].get("rotor", (0, 0, 0)), float))
            init = data.get("initial", {})
            if "omega" not in init:
                raise ValueError(f"{where}: [initial] needs 'omega'")
            omega0 = np.asarray(init["omega"], float)
            if "attitude" in init:
                q0 = np.asarray(init["attitude"], float)
            else:  # inertial z3 along G(0), ψ0 = 0: the Euler angles of (15)-(16)
                q0 = attitude_along_momentum(np.asarray(body.moments) * omega0 + np.asarray(body.rotor))
        else:
            raise ValueError(f"{where}: needs [body] or [nearly_spherical]")
        runs = data.get("runs", [])
        if not runs:
            raise ValueError(f"{where}: needs at least one [[runs]] with a law")
        laws = [(str(r.get("name", f"run{i}")), law_from_spec(r["law"]), r["law"]) for i, r in enumerate(runs)]
        integ = data.get("integration", {})
        t_span = tuple(float(x) for x in integ.get("t_span", (0.0, 60.0)))
        return cls(name=path.stem, title=str(data.get("title", path.stem)), body=body, omega0=omega0, quaternion0=q0,
                   runs=laws, method=str(integ.get("method", "dop853")), rtol=float(integ.get("rtol", 1e-10)),
                   atol=float(integ.get("atol", 1e-12)), t_span=t_span, n_out=int(integ.get("n_out", 1201)),
                   eta=float(integ.get("eta", ETA)), spherical=spherical)


def _save(columns: dict, folder: Path, stem: str) -> list[Path]:
    from gyrostat.runner import write_columns

    return write_columns(columns, folder, stem, UNITS)


def _law_text(spec) -> str:
    if isinstance(spec, (int, float)):
        return f"L = {spec:g}"
    kind = spec.get("kind", "constant")
    if kind == "constant":
        return f"L = {spec['value']:g}"
    if kind == "harmonic":
        terms = " ".join(f"{'+' if a >= 0 else '−'} {abs(a):g} sin({w:g}t)"
                         for a, w in zip(spec.get("amplitudes", []), spec.get("frequencies", [])))
        return f"L = {spec['mean']:g} {terms}"
    return f"L: {kind}"


def run_scene(path, out_dir, progress: bool = True) -> dict:
    """Solves every run of an orthogonal-torque scene, compares with the torque-free solution at
    τ(t) (and, for a nearly spherical body, with the approximations of §4), writes
    result_<run>.csv/.npz, PNG plots and report.json into out_dir/<scene name>/."""
    from gyrostat import plots as _plots  # noqa: F401  (sets the Agg backend)
    from gyrostat.validity import ValidityWarning

    scene = OrthogonalScene.from_toml(path)
    folder = Path(out_dir) / scene.name
    folder.mkdir(parents=True, exist_ok=True)
    started = time.perf_counter()
    t_eval = np.linspace(scene.t_span[0], scene.t_span[1], scene.n_out)
    results, runs, files, broken = {}, {}, [], []
    for name, law, spec in scene.runs:
        model = OrthogonalModel(scene.body, law, attitude=True, eta=scene.eta)
        sol = solve(model, scene.omega0, scene.t_span, quaternion0=scene.quaternion0, method=scene.method,
                    rtol=scene.rtol, atol=scene.atol, t_eval=t_eval)
        zv = torque_free_at_tau(model, scene.omega0, sol.tau)
        extra = {"max_error_vs_torque_free_at_tau": float(np.max(np.abs(sol.omega - zv))),
                 "tau_end": float(sol.tau[-1]), "min_g": sol.g_report["min_g"]}
        regime = constant_law_regime(model, scene.omega0)
        if regime:
            sol.notes.append(regime)
        if sol.g_report["crossings"] or sol.g_report["min_g"] <= 0:
            broken.append(f"{name}: g = 1 - L/|Q| reaches {sol.g_report['min_g']:.3g} <= 0: tau(t) is not a "
                          "homeomorphism (the paper's (10) assumes g > 0)")
        if sol.g_report["regularised_times"]:
            broken.append(f"{name}: |Q| < delta at some times: the prescribed L was not applied there")
        zv_att = torque_free_at_tau(model, scene.omega0, sol.tau, scene.quaternion0)
        exact_angles = Solution(sol.t, zv_att, {}, {}, "success", "", "").euler_angles()
        approx = {"exact": exact_angles}
        extra["max_psi_full_minus_zv"] = float(np.max(np.abs(wrap(sol.euler_angles()[:, 0] - exact_angles[:, 0]))))
        if scene.spherical is not None:
            ns = scene.spherical
            zeroth, first = ns.zeroth(sol.tau), ns.first(sol.tau)
            ang = sol.momentum_angles()
            approx = {"exact": exact_angles, "zeroth": zeroth, "first": first}
            for label, a in (("zeroth", zeroth), ("first", first)):
                extra[f"max_error_{label}_theta"] = float(np.max(np.abs(ang[:, 0] - a[:, 1])))
                extra[f"max_error_{label}_phi"] = float(np.max(np.abs(wrap(ang[:, 1] - a[:, 2]))))
                extra[f"max_error_{label}_psi_vs_zv"] = float(np.max(np.abs(wrap(exact_angles[:, 0] - a[:, 0]))))
            if not np.any(ns.k):
                extra["mean_precession_rate_corrected_34"] = ns.mean_precession_rate()
                extra["mean_spin_rate_quadrature"] = ns.mean_spin_rate()
        results[name] = (sol, zv, approx, spec)
        runs[name] = {"method": sol.method, "status": sol.status, "message": sol.message, "stats": sol.stats,
                      "invariant_relative_change": {k: float(v[-1] / v[0] - 1) for k, v in sol.invariants.items()},
                      "notes": sol.notes, **extra}
        columns = {"t": sol.t, **{n: sol.y[:, i] for i, n in enumerate(model.state_names)}, **sol.invariants,
                   "g": sol.g, "L": sol.law, "Q_norm": sol.q_norm, "theta_G": sol.momentum_angles()[:, 0],
                   "phi_G": sol.momentum_angles()[:, 1]}
        for n, v in zip(("psi", "theta", "phi"), sol.euler_angles().T):
            columns[n] = v
        files += _save(columns, folder, f"result_{name}")
        if progress:
            print(f"[{scene.name}] {name}: tau(T) = {sol.tau[-1]:.6g}", flush=True, file=__import__("sys").stderr)
    files += _draw(scene, results, folder)
    for text in broken:
        warnings.warn(f"{scene.name}: {text}", ValidityWarning, stacklevel=2)
    report = {"scene": scene.name, "title": scene.title, "model": "orthogonal_torque",
              "model_reason": "full model in t with tau and the attitude quaternion (paper 004); the torque-free "
                              "(Zhukovsky-Volterra) solution at tau(t) and, for a nearly spherical body, the "
                              "approximations of section 4 for comparison",
              "status": "success" if all(r[0].success for r in results.values()) else "failed",
              "seconds": time.perf_counter() - started, "runs": runs, "broken_assumptions": broken}
    json_path = folder / "report.json"
    report["files"] = [str(f) for f in files + [json_path]]
    json_path.write_text(json.dumps(report, indent=2, default=float) + "\n")
    return report


def _draw(scene: OrthogonalScene, results: dict, folder: Path) -> list[Path]:
    import matplotlib.pyplot as plt

    from gyrostat.plots import _finish

    files = []
    n = len(results)
    # angular velocity with the torque-free solution at τ(t)
    fig, axes = plt.subplots(n, 1, figsize=(8, 3.2 * n), sharex=True, squeeze=False)
    for ax, (name, (sol, zv, _, spec)) in zip(axes[:, 0], results.items()):
        for i, c in enumerate(("p", "q", "r")):
            ax.plot(sol.t, sol.omega[:, i], label=f"{c} (full model)")
            ax.plot(sol.t, zv[:, i], "k:", lw=1, label="ω_ZV(τ(t)) (torque-free)" if i == 0 else None)
        ax.set_ylabel("ω [rad/s]")
        ax.set_title(f"{scene.title}: {_law_text(spec)}")
        ax.legend(loc="upper right", fontsize=7, ncol=2)
        ax.grid(alpha=0.3)
    axes[-1, 0].set_xlabel("t [s]")
    files.append(_finish(fig, folder / "omega.png"))
    # invariants: relative change
    fig, axes = plt.subplots(2, 1, figsize=(8, 5.5), sharex=True)
    for name, (sol, *_rest) in results.items():
        for ax, key, label in zip(axes, ("angular_momentum_norm", "h"), ("|G|", "h = ω·Jω")):
            v = sol.invariants[key]
            ax.plot(sol.t, v / v[0] - 1, label=f"{label}, {name}")
            ax.set_ylabel(f"{label}: relative change [1]")
    for ax in axes:
        ax.grid(alpha=0.3)
        ax.legend(loc="upper left", fontsize=8)
    axes[0].set_title(f"{scene.title}: invariants (exact for the servo torque)")
    axes[1].set_xlabel("t [s]")
    files.append(_finish(fig, folder / "invariants.png"))
    # τ(t) and g(t)
    fig, axes = plt.subplots(2, 1, figsize=(8, 5.5), sharex=True)
    for name, (sol, *_rest) in results.items():
        axes[0].plot(sol.t, sol.tau, label=f"τ(t), {name}")
        line, = axes[1].plot(sol.t, sol.g, label=f"g = 1 − L/|Q|, {name}")
        for c in sol.g_report["crossings"]:
            axes[0].plot(c["t"], c["tau"], "o", ms=3, color=line.get_color())
            axes[1].plot(c["t"], 0.0, "o", ms=3, color=line.get_color())
    axes[0].plot(sol.t, sol.t - sol.t[0], "k:", lw=1, label="τ = t (no torque)")
    axes[1].axhline(0.0, color="r", lw=0.8, ls="--", label="g = 0: τ stops")
    axes[0].set_ylabel("τ [s]")
    axes[1].set_ylabel("g = dτ/dt [1]")
    axes[1].set_xlabel("t [s]")
    axes[0].set_title(f"{scene.title}: time change τ(t) (paper (10))")
    for ax, loc in zip(axes, ("upper left", "lower left")):
        ax.grid(alpha=0.3)
        ax.legend(loc=loc, fontsize=7, framealpha=0.8, ncol=2)
    axes[0].text(0.99, 0.02, "dots: g = 0 (τ stops, then reverses)", transform=axes[0].transAxes, ha="right",
                 fontsize=7)
    files.append(_finish(fig, folder / "tau.png"))
    # Euler angles (θ, φ of G in body axes; ψ) with the approximations at τ(t)
    fig, axes = plt.subplots(3, n, figsize=(6 * n, 8), sharex=True, squeeze=False)
    for j, (name, (sol, zv, approx, spec)) in enumerate(results.items()):
        ang = sol.momentum_angles()
        euler = sol.euler_angles()
        ax_psi, ax_th, ax_ph = axes[:, j]
        ax_th.plot(sol.t, ang[:, 0], label="full model")
        ax_ph.plot(sol.t, np.unwrap(ang[:, 1]), label="full model")
        ax_psi.plot(sol.t, np.unwrap(euler[:, 0]), label="full model (quaternion; inertial G moves)")
        styles = {"exact": ("k:", "torque-free ZV at τ(t)"), "zeroth": ("--", "zeroth approx. (21) at τ(t)"),
                  "first": ("-.", "first approx. (21)+μ(22) at τ(t)")}
        for key, a in approx.items():
            st, label = styles[key]
            if key != "exact":
                ax_th.plot(sol.t, a[:, 1], st, label=label)
                ax_ph.plot(sol.t, np.unwrap(a[:, 2]), st, label=label)
            ax_psi.plot(sol.t, np.unwrap(a[:, 0]), st, label=label)
        ax_psi.set_title(f"{_law_text(spec)}")
        ax_psi.set_ylabel("ψ precession [rad]")
        ax_th.set_ylabel("θ nutation (of G in body) [rad]")
        ax_ph.set_ylabel("φ proper rotation [rad]")
        ax_ph.set_xlabel("t [s]")
        for ax in axes[:, j]:
            ax.grid(alpha=0.3)
            ax.legend(loc="best", fontsize=6, framealpha=0.7)
    fig.suptitle(f"{scene.title}: Euler angles z-x-z", fontsize=10)
    files.append(_finish(fig, folder / "euler_angles.png"))
    # errors of the approximations (nearly spherical only)
    if scene.spherical is not None:
        fig, axes = plt.subplots(1, n, figsize=(6 * n, 4), squeeze=False)
        for ax, (name, (sol, zv, approx, spec)) in zip(axes[0], results.items()):
            ang = sol.momentum_angles()
            for key, st in (("zeroth", "--"), ("first", "-")):
                a = approx[key]
                ax.semilogy(sol.t, np.maximum(np.abs(ang[:, 0] - a[:, 1]), 1e-16), st, label=f"|Δθ| {key}")
                ax.semilogy(sol.t, np.maximum(np.abs(wrap(approx["exact"][:, 0] - a[:, 0])), 1e-16), st,
                            label=f"|Δψ| {key} (vs ZV ψ at τ(t))")
            ax.set_xlabel("t [s]")
            ax.set_ylabel("error [rad]")
            ax.set_ylim(1e-6, 5.0)
            ax.set_title(f"approximations at τ(t) vs full model, μ = {scene.spherical.mu:g}, {_law_text(spec)}",
                         fontsize=9)
            ax.grid(alpha=0.3, which="both")
            ax.legend(fontsize=7)
        files.append(_finish(fig, folder / "approximation_errors.png"))
    return files
