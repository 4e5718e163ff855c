"""The orthogonal torque family (paper 004): a free gyrostat under a servo torque orthogonal to its
momentum G and its angular velocity ω (Makeev). Derivation, checks and measured errors:
docs/papers/004_orthogonal_torque.md.

A family module provides its models (``ModelBase`` subclasses with their own assumptions), its
paper helpers and analysis, its plots (drawn with :mod:`gyrostat.figures`), its scene kind(s)
(:class:`gyrostat.kind.Kind`: schema and defaults, runs, ladder rungs, checks, analysis, plots)
and one ``register(...)`` line; see :mod:`gyrostat.families.rigid_body` for the full recipe.
Here the kind ``orthogonal_torque``; it has one rung, the full model: its exact solution, the
torque-free gyrostat at τ(t), needs τ(t) from the full run, and the nearly spherical
approximations of §4 are compared in the plots, not a rung. :mod:`gyrostat.orthogonal`
re-exports the models and helpers.

The torque is M = L(t) e_L, e_L = Q/|Q|, Q = ω × G, G = Jω + k. It keeps |G| and h = ω·Jω
exactly, and the motion is the torque-free Zhukovsky–Volterra (ZV) gyrostat run on the clock

    τ(t) = ∫ g dt,   g = dτ/dt = 1 − L(t)/|Q(ω)|,      ω(t) = ω_ZV(τ(t)).

At Q = 0 the direction is undefined: below the threshold |Q| < δ = η|ω||G| (η = 1e-3 by
default) the core tapers the torque to L Q/n, n = (|Q|² + δ²)/(2δ) (C¹ at |Q| = δ, zero torque
at Q = 0); at and above it the paper's L Q/|Q| is applied exactly. Both invariants and the clock
stay exact; where |Q| < δ the prescribed L is not applied, and the solution flags those times.

Contents: magnitude laws (:func:`constant`, :func:`polynomial`, :func:`harmonic`,
:func:`tabulated`), :class:`OrthogonalModel` (solved by :func:`gyrostat.solve`, which records
τ(t) as a state and g, L, |Q|, δ, the angles of G in body axes as outputs), :func:`tau_report`
(where g ≤ 0), :func:`torque_free_at_tau` (ω_ZV(τ)) and the nearly spherical approximations of
§4 (:class:`NearlySpherical`).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from gyrostat import _core, attitude, figures
from gyrostat.events import Event
from gyrostat.families.rigid_body import Model
from gyrostat.figures import LEGEND_SIZE, keep, legend_outside, mark_singular, plt, unit_label, wrap_angle
from gyrostat.kind import (BODY, METHOD, SPLITTING_FIELDS, Kind, Run, build, engine_option, integration, make_body,
                           outputs_field, register, title_fields)
from gyrostat.modelbase import ModelBase, check_torques, flag
from gyrostat.schema import (ArrayOf, Choice, Field, ListOf, OneOf, SceneError, Table, Variants, Vector, all_finite,
                             increasing, nonzero_quaternion, positive, span_order)
from gyrostat.schema import finite as finite_value
from gyrostat.solve import solve

ETA = 1e-3
"""Default regularisation: δ = η |ω| |G|."""


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
    """L(t) = value: a constant magnitude law of the servo torque.

    Parameters
    ----------
    value : float
        L, in N m.

    Examples
    --------
    >>> from gyrostat import orthogonal
    >>> law = orthogonal.constant(0.1)
    >>> law.kind, law(3.0)
    ('constant', 0.1)
    """
    return _core.MagnitudeLaw.constant(_finite(value, "constant L"))


def polynomial(coefficients: Sequence[float]) -> _core.MagnitudeLaw:
    """L(t) = Σ c_i tⁱ, coefficients (c0, c1, …).

    Parameters
    ----------
    coefficients : sequence of float
        c_i, in N m / s^i.

    Examples
    --------
    >>> from gyrostat import orthogonal
    >>> round(orthogonal.polynomial([0.1, 0.02])(2.0), 12)
    0.14
    """
    return _core.MagnitudeLaw.polynomial([_finite(c, f"polynomial coefficient {i}") for i, c in enumerate(coefficients)])


def harmonic(mean: float, amplitudes: Sequence[float] = (), frequencies: Sequence[float] = (),
             phases: Sequence[float] | None = None) -> _core.MagnitudeLaw:
    """L(t) = L0 + Σ A_i sin(w_i t + φ_i) (phases default to 0).

    Parameters
    ----------
    mean : float
        L0, in N m.
    amplitudes : sequence of float, optional
        A_i, in N m.
    frequencies : sequence of float, optional
        w_i, in rad/s.
    phases : sequence of float, optional
        φ_i, in rad (default 0).

    Examples
    --------
    >>> import numpy as np
    >>> from gyrostat import orthogonal
    >>> round(orthogonal.harmonic(0.1, [0.05], [2.0])(np.pi / 4), 12)
    0.15
    """
    amplitudes = [float(a) for a in np.atleast_1d(amplitudes)]
    frequencies = [float(w) for w in np.atleast_1d(frequencies)]
    phases = [0.0] * len(amplitudes) if phases is None else [float(p) for p in np.atleast_1d(phases)]
    return _core.MagnitudeLaw.harmonic(_finite(mean, "harmonic mean L0"), amplitudes, frequencies, phases)


def tabulated(times: Sequence[float], values: Sequence[float], interpolation: str = "linear") -> _core.MagnitudeLaw:
    """L(t) interpolated in a table (``"linear"`` or ``"cubic"`` Hermite); held constant outside it.
    Times must increase strictly: a zero or negative spacing raises ValueError naming it.

    Parameters
    ----------
    times : sequence of float
        The table's times, in s.
    values : sequence of float
        L at those times, in N m.
    interpolation : {"linear", "cubic"}, optional
        Between the times.

    Examples
    --------
    >>> from gyrostat import orthogonal
    >>> law = orthogonal.tabulated([0.0, 1.0, 2.0], [0.0, 1.0, 0.5])
    >>> law(0.5), law(5.0)
    (0.5, 0.5)
    """
    if interpolation not in ("linear", "cubic"):
        raise ValueError(f"interpolation = {interpolation!r}: choose 'linear' or 'cubic'")
    return _core.MagnitudeLaw.tabulated([float(t) for t in np.ravel(times)], [float(v) for v in np.ravel(values)],
                                        interpolation == "cubic")


def law_from_spec(spec: dict | float) -> _core.MagnitudeLaw:
    """A law from a scene table: a number, or {kind = "constant"|"polynomial"|"harmonic"|"tabulated", …}.

    Parameters
    ----------
    spec : dict or float
        The scene's ``law`` (values in N m, times in s).

    Examples
    --------
    >>> from gyrostat import orthogonal
    >>> round(orthogonal.law_from_spec({"kind": "polynomial", "coefficients": [0.1, 0.02]})(2.0), 12)
    0.14
    """
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
class OrthogonalModel(ModelBase):
    """Gyrostat under the servo torque L(t) Q/|Q| (regularised), plus optional other torques.

    State: (p, q, r, τ) or, with ``attitude=True``, (p, q, r, q_w, q_x, q_y, q_z, τ); ω alone (or
    ω and the quaternion) as y0 starts τ at 0. Outputs: ``angular_momentum_norm`` |G| and ``h`` =
    ω·Jω (exact without other torques), ``g`` = dτ/dt, ``L``, ``Q_norm`` |Q|, ``delta`` δ,
    ``regularised`` (1 where |Q| < δ or Q = 0: the prescribed L was not applied; at Q = 0 the servo applies nothing and g = 1), ``theta_G``, ``phi_G``
    (the angles of G in body axes, paper (15)) and, with attitude, the z-x-z Euler angles.

    ``regularisation``: ``"threshold"`` (default: the paper's torque wherever |Q| ≥ δ = η|ω||G|,
    tapered to L Q/n, n = (|Q|² + δ²)/(2δ), below) or ``"smooth"`` (L Q/√(|Q|² + δ²) everywhere:
    smooth, but the applied L is off by a relative δ²/2|Q|² at every |Q|).

    Parameters
    ----------
    body : gyrostat.Body
        Moments (kg m^2) and rotor momentum k (kg m^2/s).
    law : gyrostat.orthogonal law or float
        The magnitude L(t) of the torque, in N m (:func:`constant`, :func:`polynomial`,
        :func:`harmonic`, :func:`tabulated`; a number is a constant law).
    torques : sequence of torques, optional
        Other torques, added.
    attitude : bool, optional
        Integrate the attitude quaternion too.
    eta : float, optional
        The regularisation's scale η (δ = η|ω||G|; dimensionless).
    regularisation : {"threshold", "smooth"}, optional
        How the torque is tapered near Q = 0 (above).

    Examples
    --------
    The torque is orthogonal to G and ω: |G| and h = ω·Jω stay constant.

    >>> import gyrostat
    >>> from gyrostat import orthogonal
    >>> model = orthogonal.OrthogonalModel(gyrostat.Body([3.0, 2.0, 1.0]), 0.1)
    >>> model.state_names
    ('p', 'q', 'r', 'tau')
    >>> sol = gyrostat.solve(model, [0.1, 0.2, 1.0], (0.0, 10.0))
    >>> bool(abs(sol["angular_momentum_norm"][-1] / sol["angular_momentum_norm"][0] - 1) < 1e-8)
    True

    The examples of its attributes use this ``model``.
    """

    kind = "orthogonal_torque"

    def __init__(self, body: _core.Body, law: _core.MagnitudeLaw | float, torques: Sequence = (),
                 attitude: bool = False, eta: float = ETA, regularisation: str = "threshold"):
        if not isinstance(body, _core.Body):
            raise TypeError(f"body must be a gyrostat.Body, not {type(body).__name__}")
        if not isinstance(law, _core.MagnitudeLaw):
            law = constant(law)
        self.body, self.law = body, law
        self.torques = check_torques(torques)
        self.eta = _finite(eta, "eta")
        if regularisation not in ("threshold", "smooth"):
            raise ValueError(f"regularisation = {regularisation!r}: choose 'threshold' or 'smooth'")
        self.regularisation = regularisation
        self._core = _core.orthogonal_model(body, law, self.torques, flag(attitude, "attitude"), self.eta,
                                            regularisation == "smooth")

    @property
    def moments(self) -> np.ndarray:
        """The body's principal moments (A1, A2, A3), in kg m^2.

        Examples
        --------
        >>> model.moments
        array([3., 2., 1.])
        """
        return np.asarray(self.body.moments, float)

    @property
    def rotor(self) -> np.ndarray:
        """The rotor momentum k in body axes, in kg m^2/s.

        Examples
        --------
        >>> model.rotor
        array([0., 0., 0.])
        """
        return np.asarray(self.body.rotor, float)

    def tau_rate(self, t, omega) -> np.ndarray:
        """g = dτ/dt = 1 − L/|Q| at times t for angular velocities omega (dimensionless).

        Parameters
        ----------
        t : float or array_like, shape (n,)
            Times, in s.
        omega : array_like, shape (n, 3)
            Angular velocities in body axes, in rad/s.

        Examples
        --------
        >>> model.tau_rate([0.0], [[0.1, 0.2, 1.0]]).round(6)
        array([0.647327])
        """
        t = np.atleast_1d(np.asarray(t, float))
        return np.asarray(self._core.tau_rate(t, np.atleast_2d(np.asarray(omega, float))))

    def torque_free(self, attitude: bool | None = None) -> Model:
        """The Zhukovsky–Volterra gyrostat of the same body (the full model without torque).

        Parameters
        ----------
        attitude : bool, optional
            With the attitude quaternion (default: as this model).

        Examples
        --------
        >>> model.torque_free()
        Model(Body(A1=3, A2=2, A3=1, k=[0, 0, 0]), torques=[], attitude=False)
        """
        return Model(self.body, attitude=self.attitude if attitude is None else attitude)

    def __repr__(self) -> str:
        return (f"OrthogonalModel({self.body!r}, law={self.law.kind}, attitude={self.attitude}, eta={self.eta}, "
                f"regularisation={self.regularisation!r})")


G_FALLS, G_RISES = "g falls through 0", "g rises through 0"


def g_zero(terminal: bool | int = False) -> list[Event]:
    """The events where g = dτ/dt = 1 − L/|Q| crosses zero: falling (τ stops and then runs
    backwards) and rising (τ turns forward again), located by the engine on the integrator's
    continuous extension. :func:`tau_report` reads them.

    Parameters
    ----------
    terminal : bool or int, optional
        Stop the run at the first (True) or n-th crossing.

    Examples
    --------
    >>> from gyrostat import orthogonal
    >>> [event.name for event in orthogonal.g_zero()]
    ['g falls through 0', 'g rises through 0']
    """
    return [Event("g", 0.0, -1, terminal, G_FALLS), Event("g", 0.0, 1, terminal, G_RISES)]


def tau_report(model: OrthogonalModel, sol, freeze_tol: float = 1e-6) -> dict:
    """Where g = dτ/dt ≤ 0: its zero crossings (time, τ, L; from the events of :func:`g_zero`,
    which the solve must have watched), intervals with g < 0 and the minimum of g on the output
    grid, a frozen end state (|g| and |ω̇| below freeze_tol), and times where |Q| < δ.

    What the motion does: ω moves along the torque-free orbit with speed g. Where g = 0 the servo
    torque cancels ω × G and ω stands still (a uniform rotation about a fixed inertial axis);
    where g < 0 the body retraces the ZV orbit backwards (τ decreases).

    Parameters
    ----------
    model : OrthogonalModel
        The model solved.
    sol : gyrostat.Solution
        Its run, solved with ``events=orthogonal.g_zero()``.
    freeze_tol : float, optional
        |g| and |ω̇| (rad/s²) below which the end state counts as frozen.

    Examples
    --------
    >>> import gyrostat
    >>> from gyrostat import orthogonal
    >>> model = orthogonal.OrthogonalModel(gyrostat.Body([3.0, 2.0, 1.0]), 0.1)
    >>> sol = gyrostat.solve(model, [0.1, 0.2, 1.0], (0.0, 10.0), events=orthogonal.g_zero())
    >>> report = orthogonal.tau_report(model, sol)
    >>> round(report["min_g"], 4), report["crossings"]  # L < min|Q|: g stays positive
    (0.6162, [])
    """
    names = sol.event_names
    if G_FALLS not in names or G_RISES not in names:
        raise ValueError("tau_report needs the crossings of g = 0: solve with events=orthogonal.g_zero()")
    t, g, tau = sol.t, sol["g"], sol["tau"]
    q_norm, law = sol["Q_norm"], sol["L"]
    regularised = sol["regularised"] > 0
    report = {"min_g": None, "t_min_g": None, "crossings": [], "negative_intervals": [], "frozen": None,
              "regularised_times": [], "messages": []}
    if t.size == 0:
        return report
    i = int(np.argmin(g))
    report["min_g"], report["t_min_g"] = float(g[i]), float(t[i])
    tau_index = sol.state_names.index("tau")
    for name, direction in ((G_FALLS, "down"), (G_RISES, "up")):
        k = names.index(name)
        for tc, yc in zip(sol.t_events[k], sol.y_events[k]):
            L = float(model.law(float(tc)))
            # at g = 0 the regularised denominator equals L: |Q| = L wherever |Q| ≥ δ
            report["crossings"].append({"t": float(tc), "tau": float(yc[tau_index]), "q_norm": L, "L": L,
                                        "direction": direction})
    report["crossings"].sort(key=lambda c: c["t"])
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
                            "q_norm": float(q_norm[-1]), "L": float(law[-1])}
    if np.any(regularised):
        report["regularised_times"] = [float(t[regularised].min()), float(t[regularised].max())]
    msgs = report["messages"]
    msgs.append(f"g = dtau/dt >= {report['min_g']:.4g} (minimum at t = {report['t_min_g']:.6g}); "
                f"tau(t_end) = {tau[-1]:.8g}")
    for c in report["crossings"]:
        what = ("g falls through 0: tau stops and then runs backwards (the body retraces the torque-free orbit; "
                "not L-reducible forward in time)" if c["direction"] == "down" else
                "g rises through 0: tau turns forward again")
        msgs.append(f"t = {c['t']:.6g} (tau = {c['tau']:.6g}, |Q| = L = {c['L']:.6g}): {what}")
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
    τ converges to a τ* with |Q(τ*)| = L (the motion freezes).

    Parameters
    ----------
    model : OrthogonalModel
        The model (its body and rotor).
    omega0 : array_like, shape (3,)
        ω at τ = 0, in rad/s.
    span : float, optional
        The τ sampled, in s (default: 400 rotations' worth).
    n : int, optional
        Samples.

    Examples
    --------
    >>> import gyrostat
    >>> from gyrostat import orthogonal
    >>> model = orthogonal.OrthogonalModel(gyrostat.Body([3.0, 2.0, 1.0]), 0.1)
    >>> [round(x, 4) for x in orthogonal.orbit_q_range(model, [0.1, 0.2, 1.0])]  # in N m
    [0.2606, 0.3116]
    """
    omega0 = np.asarray(omega0, float)
    J, k = model.moments, model.rotor
    if span is None:
        span = 400.0 / (np.linalg.norm(omega0) + np.linalg.norm(k) / J.min() + 1e-300)
    zv = solve(model.torque_free(attitude=False), omega0, (0.0, span), n_out=n, rtol=1e-10, atol=1e-12)
    Q = np.cross(zv.omega, zv.omega @ model.body.inertia.T + k)  # ω × G in the body frame given
    q = np.linalg.norm(Q, axis=1)
    return float(q.min()), float(q.max())


def constant_law_regime(model: OrthogonalModel, omega0) -> str | None:
    """For a constant L: which of the three regimes (docs §Singular cases) applies; None otherwise.

    Parameters
    ----------
    model : OrthogonalModel
        The model, with a constant law.
    omega0 : array_like, shape (3,)
        ω at t = 0, in rad/s.

    Examples
    --------
    >>> import gyrostat
    >>> from gyrostat import orthogonal
    >>> model = orthogonal.OrthogonalModel(gyrostat.Body([3.0, 2.0, 1.0]), 0.1)
    >>> orthogonal.constant_law_regime(model, [0.1, 0.2, 1.0])
    'L = 0.1 < min|Q| = 0.260576 on the torque-free orbit: tau increases without bound'
    """
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
        s = solve(model, y0, (0.0, max(grid[-1], 1e-300)), t_eval=grid, **options).raise_for_status()
        out[forward] = s.y[grid.size - times.size:]
    if np.any(backward):
        times = values[backward][::-1]
        grid = np.concatenate([[0.0], times])
        s = solve(model, y0, (0.0, grid[-1]), t_eval=grid, **options).raise_for_status()
        out[backward] = s.y[1:][::-1]
    return out[inverse]


def torque_free_at_tau(model: OrthogonalModel, omega0, tau, quaternion0=None, **options) -> np.ndarray:
    """The Zhukovsky–Volterra solution through ω0 (and q0 when given) at the times τ: (n, 3) or
    (n, 7). Compare ω(t) with ``torque_free_at_tau(model, ω0, solution.tau)``. The attitude does
    not map through τ (the servo torque turns the inertial G): only ω and the angles of G do.

    Parameters
    ----------
    model : OrthogonalModel
        Whose torque-free gyrostat (:meth:`OrthogonalModel.torque_free`) is evaluated.
    omega0 : array_like, shape (3,)
        The angular velocity where τ = 0, in rad/s.
    tau : array_like
        The times τ, in s (any order).
    quaternion0 : array_like, shape (4,), optional
        The attitude at τ = 0 (then the result has the attitude too).
    **options
        Options of :func:`gyrostat.solve` (default rtol 1e-12, atol 1e-13).

    Examples
    --------
    >>> import gyrostat
    >>> from gyrostat import orthogonal
    >>> model = orthogonal.OrthogonalModel(gyrostat.Body([3.0, 2.0, 1.0]), 0.1)
    >>> sol = gyrostat.solve(model, [0.1, 0.2, 1.0], (0.0, 10.0))
    >>> free = orthogonal.torque_free_at_tau(model, [0.1, 0.2, 1.0], sol["tau"])
    >>> bool(abs(free - sol.omega).max() < 1e-6)  # ω(t) is the free motion at τ(t)
    True
    """
    free = model.torque_free(attitude=quaternion0 is not None)
    y0 = np.asarray(omega0, float) if quaternion0 is None else np.concatenate([omega0, quaternion0])
    return _evaluate_at(free, y0, tau, **options)


# ------------------------------------------------------------------------------ Euler angles
def attitude_along_momentum(G0, psi0: float = 0.0) -> np.ndarray:
    """The quaternion of Rz(ψ0) Rx(θ0) Rz(φ0) with θ0, φ0 the angles of G0 in body axes, so that
    the inertial z3 axis lies along G (the frame of the paper's Euler angles (15)).

    Parameters
    ----------
    G0 : array_like, shape (3,)
        The angular momentum in body axes, in kg m^2/s.
    psi0 : float, optional
        ψ0, in rad.

    Raises
    ------
    ValueError
        For G0 = 0 (no direction) or a component that is not finite; G0 of any size is
        normalised without overflow or underflow.

    Examples
    --------
    >>> from gyrostat import orthogonal
    >>> orthogonal.attitude_along_momentum([0.0, 0.0, 2.0])
    array([1., 0., 0., 0.])
    """
    s = _core.unit_vector(G0, "attitude_along_momentum: G0")  # (G0 of any size: no overflow in |G0|)
    return attitude.quaternion_from_euler([psi0, math.acos(max(-1.0, min(1.0, s[2]))), math.atan2(s[0], s[1])],
                                          "zxz")


def wrap(angle):
    """Angle (differences) to (−π, π].

    Parameters
    ----------
    angle : float or array_like
        In rad.

    Examples
    --------
    >>> from gyrostat import orthogonal
    >>> orthogonal.wrap([0.1, -4.0]).round(6)
    array([0.1     , 2.283185])
    """
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

    Parameters
    ----------
    J : float
        The mean moment of inertia, in kg m^2.
    Jj : sequence of float
        The deviations J_j (A_j = J + μ J_j), in kg m^2.
    mu : float
        μ, the small parameter (dimensionless).
    k : sequence of float, optional
        The rotor momentum, in kg m^2/s.
    G : float, optional
        |G|, in kg m^2/s.
    theta0, phi0, psi0 : float, optional
        The initial Euler angles, in rad (sin θ0 > 0).

    Examples
    --------
    >>> from gyrostat import orthogonal
    >>> ns = orthogonal.NearlySpherical(J=1.0, Jj=[0.3, 0.1, -0.2], mu=0.05)
    >>> ns.moments
    array([1.015, 1.005, 0.99 ])

    The examples of its attributes use this ``ns``.
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
        """b_j = J_j / J (dimensionless).

        Examples
        --------
        >>> ns.b
        array([ 0.3,  0.1, -0.2])
        """
        return self.Jj / self.J

    @property
    def moments(self) -> np.ndarray:
        """The moments A_j = J + μ J_j, in kg m^2.

        Examples
        --------
        >>> ns.moments
        array([1.015, 1.005, 0.99 ])
        """
        return self.J + self.mu * self.Jj

    def body(self) -> _core.Body:
        """The body with these moments and rotor.

        Examples
        --------
        >>> ns.body()
        Body(A1=1.015, A2=1.005, A3=0.99, k=[0, 0, 0])
        """
        return _core.Body(self.moments, self.k)

    @property
    def q0(self) -> np.ndarray:
        """The initial attitude: Rz(ψ0) Rx(θ0) Rz(φ0), inertial z3 along G.

        Examples
        --------
        >>> ns.q0.round(6)
        array([0.877583, 0.479426, 0.      , 0.      ])
        """
        return attitude.quaternion_from_euler([self.psi0, self.theta0, self.phi0], "zxz")

    @property
    def R0(self) -> np.ndarray:
        """The initial rotation matrix of :attr:`q0` (body → inertial).

        Examples
        --------
        >>> ns.R0[2].round(6)  # its last row: G/|G| in body axes
        array([0.      , 0.841471, 0.540302])
        """
        return attitude.rotation_matrix(self.q0)

    def initial_state(self) -> tuple[np.ndarray, np.ndarray]:
        """ω0 = A⁻¹(G s0 − k) (rad/s) and q0 (inertial z3 along G).

        Examples
        --------
        >>> omega0, q0 = ns.initial_state()
        >>> omega0.round(6)
        array([0.      , 0.837285, 0.54576 ])
        """
        s0 = self.R0[2, :]
        return (self.G * s0 - self.k) / self.moments, self.q0

    def exact(self, tau, **options) -> np.ndarray:
        """(n, 3) (ψ, θ, φ) of the ZV gyrostat with the true moments (the reference in τ), in rad.

        Parameters
        ----------
        tau : array_like
            Times τ, in s.
        **options
            Options of :func:`gyrostat.solve`.

        Examples
        --------
        >>> ns.exact([0.0, 1.0]).round(6)
        array([[0.      , 1.      , 0.      ],
               [0.995025, 0.999966, 0.008146]])
        """
        return self._zv_angles(self.moments, tau, **options)

    def zeroth(self, tau) -> np.ndarray:
        """(n, 3) (ψ, θ, φ) of the zeroth approximation (21), closed form, in rad.

        Parameters
        ----------
        tau : array_like
            Times τ, in s.

        Examples
        --------
        >>> ns.zeroth([1.0])[0, :2].round(6)  # ψ = Gτ/J, θ fixed
        array([1., 1.])
        """
        tau = np.atleast_1d(np.asarray(tau, float))
        knorm = float(np.linalg.norm(self.k))
        # R(τ) = Rz(Gτ/J) R0 Rot(k̂, |k|τ/J)ᵀ as quaternions: q_z(Gτ/J) ⊗ q0 ⊗ q_k(−|k|τ/J)
        half_z = 0.5 * self.G * tau / self.J
        spin = np.column_stack([np.cos(half_z), 0 * tau, 0 * tau, np.sin(half_z)])
        q = attitude.multiply(spin, np.broadcast_to(self.q0, (tau.size, 4)))
        if knorm > 0:
            half_k = -0.5 * knorm * tau / self.J
            about_k = np.column_stack([np.cos(half_k), np.outer(np.sin(half_k), self.k / knorm)])
            q = attitude.multiply(q, about_k)
        return attitude.euler_angles(q, "zxz")

    def first(self, tau, **options) -> np.ndarray:
        """(n, 3) (ψ, θ, φ) of the first approximation (21) + μ(22), ψ row corrected, in rad.

        Parameters
        ----------
        tau : array_like
            Times τ, in s (and options of :func:`gyrostat.solve`, as for :meth:`exact`).

        Returns
        -------
        numpy.ndarray, shape (n, 3)
            The ZV gyrostat's angles with the moments J/(1 − μ b_j).

        Examples
        --------
        >>> ns.first([1.0]).round(6)
        array([[0.995   , 0.999966, 0.008105]])
        """
        a = (1 - self.mu * self.b) / self.J
        if np.any(a <= 0):
            raise ValueError(f"1 - mu b_j = {(1 - self.mu * self.b).tolist()} must be positive: mu = {self.mu} too large")
        return self._zv_angles(1 / a, tau, **options)

    def _zv_angles(self, moments, tau, **options) -> np.ndarray:
        model = Model(_core.Body(np.asarray(moments, float), self.k), attitude=True)
        s0 = self.R0[2, :]
        y0 = np.concatenate([(self.G * s0 - self.k) / moments, self.q0])
        y = _evaluate_at(model, y0, tau, **options)
        return attitude.euler_angles(y[:, 3:7], "zxz")

    # ---- k = 0 (rigid nearly spherical body)
    def _P(self, phi):
        b1, b2, _ = self.b
        return b1 * np.sin(phi) ** 2 + b2 * np.cos(phi) ** 2

    @property
    def P_star(self) -> float:
        """P* = (b1 + b2)/2 (dimensionless).

        Examples
        --------
        >>> float(ns.P_star)
        0.2
        """
        return 0.5 * (self.b[0] + self.b[1])

    @property
    def D1(self) -> float:
        """D1 = (b2 − b1) G, in kg m^2/s.

        Examples
        --------
        >>> round(float(ns.D1), 12)
        -0.2
        """
        return (self.b[1] - self.b[0]) * self.G

    @property
    def D2(self) -> float:
        """D2 = (P* − b3) G, in kg m^2/s.

        Examples
        --------
        >>> float(ns.D2)
        0.4
        """
        return (self.P_star - self.b[2]) * self.G

    def _rigid(self):
        if np.any(self.k):
            raise ValueError(f"k = {self.k.tolist()}: the reduced results (28)-(34) hold for k = 0 only "
                             "(docs/papers/004_orthogonal_torque.md)")

    def rigid_orbit(self, phi) -> np.ndarray:
        """sinθ(φ) on the exact first-order orbit sin²θ (P(φ) − b3) = sin²θ0 (P(φ0) − b3) (k = 0).

        Parameters
        ----------
        phi : array_like
            φ, in rad.

        Examples
        --------
        >>> ns.rigid_orbit([0.0, 0.5]).round(6)
        array([0.841471, 0.783575])
        """
        self._rigid()
        c = math.sin(self.theta0) ** 2 * (self._P(self.phi0) - self.b[2])
        return np.sqrt(c / (self._P(np.asarray(phi, float)) - self.b[2]))

    def orbit_29(self, phi) -> np.ndarray:
        """The paper's (29): sinθ ≈ sinθ0 exp[n (sin²φ − sin²φ0)], n = D1/(2 D2) (k = 0).

        Parameters
        ----------
        phi : array_like
            φ, in rad.

        Returns
        -------
        numpy.ndarray
            sin θ at each φ (dimensionless).

        Examples
        --------
        >>> ns.orbit_29([0.0, 0.5]).round(6)
        array([0.841471, 0.794481])
        """
        self._rigid()
        n = self.D1 / (2 * self.D2)
        return math.sin(self.theta0) * np.exp(n * (np.sin(np.asarray(phi, float)) ** 2 - math.sin(self.phi0) ** 2))

    def mean_precession_rate(self) -> float:
        """(34) corrected: Ω = (1 − μP*) G / J (printed: P* G/J), in rad/s.

        Examples
        --------
        >>> float(ns.mean_precession_rate())
        0.99
        """
        self._rigid()
        return (1 - self.mu * self.P_star) * self.G / self.J

    def mean_spin_rate_simple(self) -> float:
        """(34) corrected, crude: μ D2 cosθ0 / J (printed: D2/J), in rad/s.

        Examples
        --------
        >>> round(float(ns.mean_spin_rate_simple()), 6)
        0.010806
        """
        self._rigid()
        return self.mu * self.D2 * math.cos(self.theta0) / self.J

    def mean_spin_rate(self, n: int = 4096) -> float:
        """±2π/T_φ, in rad/s, with T_φ = (J/μ) ∫0^{2π} dφ / (|P(φ) − b3| G |cosθ(φ)|) on the exact
        first-order orbit (k = 0); the sign is that of (P − b3) cosθ0. Trapezoid rule on a periodic
        integrand.

        Parameters
        ----------
        n : int, optional
            Quadrature points.

        Examples
        --------
        >>> round(float(ns.mean_spin_rate()), 6)
        0.012485
        """
        self._rigid()
        phi = np.linspace(0, 2 * np.pi, n, endpoint=False)
        u = self.rigid_orbit(phi)
        if np.any(u >= 1):
            raise ValueError("the first-order orbit reaches sin(theta) = 1: phi does not rotate (no mean spin)")
        P = self._P(phi) - self.b[2]
        integrand = 1.0 / (np.abs(P) * self.G * np.sqrt(1 - u * u))
        period = self.J / abs(self.mu) * integrand.mean() * 2 * np.pi
        return float(np.sign(P[0] * math.cos(self.theta0) * self.mu) * 2 * np.pi / period)


# ------------------------------------------------------------------------------------ analysis
def analyse(scene, solutions: dict, report: dict, derived: dict) -> None:
    """Per run: the g = 0 report, the torque-free gyrostat at τ(t) and, for a nearly spherical body,
    the errors of the approximations of section 4."""
    kind = scene.kind
    spherical = kind.spherical(scene.doc)
    for run in scene.runs:
        sol, model = solutions[run.name], run.model
        entry = report["runs"][run.name]
        if not len(sol):
            continue
        omega0, q0 = run.y0[:3], run.y0[3:7]
        g_report = tau_report(model, sol)  # from the g = 0 events the run watched
        sol.notes.extend(g_report["messages"])
        regime = constant_law_regime(model, omega0)
        if regime:
            sol.notes.append(regime)
        entry["notes"] = list(sol.notes)
        entry["g_report"] = {k: v for k, v in g_report.items() if k != "messages"}
        if g_report["crossings"] or g_report["min_g"] <= 0:
            report["broken_assumptions"].append(
                f"{run.name}: g = 1 - L/|Q| reaches {g_report['min_g']:.3g} <= 0: tau(t) is not a homeomorphism "
                "(the paper's (10) assumes g > 0)")
        if g_report["regularised_times"]:
            report["broken_assumptions"].append(f"{run.name}: |Q| < delta at some times: the prescribed L was not "
                                                "applied there")
        tau = sol["tau"]
        zv = torque_free_at_tau(model, omega0, tau)
        zv_angles = attitude.euler_angles(torque_free_at_tau(model, omega0, tau, q0)[:, 3:7])
        entry["max_error_vs_torque_free_at_tau"] = float(np.max(np.abs(sol.omega - zv)))
        entry["tau_end"] = float(tau[-1])
        entry["min_g"] = g_report["min_g"]
        entry["max_psi_full_minus_zv"] = float(np.max(np.abs(wrap(sol["psi"] - zv_angles[:, 0]))))
        approx = {"exact": zv_angles}
        if spherical is not None:
            approx["zeroth"], approx["first"] = spherical.zeroth(tau), spherical.first(tau)
            for label in ("zeroth", "first"):
                a = approx[label]
                entry[f"max_error_{label}_theta"] = float(np.max(np.abs(sol["theta_G"] - a[:, 1])))
                entry[f"max_error_{label}_phi"] = float(np.max(np.abs(wrap(sol["phi_G"] - a[:, 2]))))
                entry[f"max_error_{label}_psi_vs_zv"] = float(np.max(np.abs(wrap(zv_angles[:, 0] - a[:, 0]))))
            if not np.any(spherical.k):
                entry["mean_precession_rate_corrected_34"] = spherical.mean_precession_rate()
                entry["mean_spin_rate_quadrature"] = spherical.mean_spin_rate()
        derived[run.name] = {"torque_free": zv, "approximations": approx, "g_report": g_report}


# ------------------------------------------------------------------------------------ plots
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


def draw(scene, solutions: dict, derived: dict, folder) -> list:

    laws = {spec["name"]: spec["law"] for spec in scene.doc["runs"]}
    results = {run.name: (solutions[run.name], derived[run.name]["torque_free"], derived[run.name]["approximations"],
                          laws[run.name]) for run in scene.runs if run.name in derived}
    spherical = scene.kind.spherical(scene.doc)
    wanted = set(scene.plots)
    files = []
    n = len(results)
    if n == 0:
        return files
    # angular velocity with the torque-free solution at τ(t)
    fig, axes = plt.subplots(n, 1, figsize=(8, 3.2 * n), sharex=True, squeeze=False)
    for ax, (name, (sol, zv, _, spec)) in zip(axes[:, 0], results.items()):
        for i, c in enumerate(("p", "q", "r")):
            ax.plot(sol.t, sol.omega[:, i], label=f"{c} (full model)")
            ax.plot(sol.t, zv[:, i], "k:", lw=1, label="ω_ZV(τ(t)) (torque-free)" if i == 0 else None)
        ax.set_ylabel(unit_label(sol, "p", "ω"))
        ax.set_title(f"{scene.title}: {_law_text(spec)}")
        legend_outside(ax)
        ax.grid(alpha=0.3)
    axes[-1, 0].set_xlabel("t [s]")
    keep(fig, folder / "omega.png", "omega" in wanted, files)
    # invariants: relative change
    fig, axes = plt.subplots(2, 1, figsize=(8, 5.5), sharex=True)
    for name, (sol, *_rest) in results.items():
        for ax, key, label in zip(axes, ("angular_momentum_norm", "h"), ("|G|", "h = ω·Jω")):
            v = sol[key]
            ax.plot(sol.t, v / v[0] - 1, label=f"{label}, {name}")
            ax.set_ylabel(f"{label}: relative change [1]")
    for ax in axes:
        ax.grid(alpha=0.3)
        legend_outside(ax)
    axes[0].set_title(f"{scene.title}: invariants (exact for the servo torque)")
    axes[1].set_xlabel("t [s]")
    keep(fig, folder / "invariants.png", "invariants" in wanted, files)
    # τ(t) and g(t)
    fig, axes = plt.subplots(2, 1, figsize=(8, 5.5), sharex=True)
    for name, (sol, *_rest) in results.items():
        axes[0].plot(sol.t, sol["tau"], label=f"τ(t), {name}")
        line, = axes[1].plot(sol.t, sol["g"], label=f"g = 1 − L/|Q|, {name}")
        for c in derived[name]["g_report"]["crossings"]:
            axes[0].plot(c["t"], c["tau"], "o", ms=3, color=line.get_color())
            axes[1].plot(c["t"], 0.0, "o", ms=3, color=line.get_color())
    axes[0].plot(sol.t, sol.t - sol.t[0], "k:", lw=1, label="τ = t (no torque)")
    axes[1].axhline(0.0, color="r", lw=0.8, ls="--", label="g = 0: τ stops")
    axes[0].set_ylabel("τ [s]")
    axes[1].set_ylabel("g = dτ/dt [1]")
    axes[1].set_xlabel("t [s]")
    axes[0].set_title(f"{scene.title}: time change τ(t) (paper (10))")
    for ax in axes:
        ax.grid(alpha=0.3)
        legend_outside(ax)
    axes[0].text(0.99, 0.02, "dots: g = 0 (τ stops, then reverses)", transform=axes[0].transAxes, ha="right",
                 fontsize=LEGEND_SIZE)
    keep(fig, folder / "tau.png", "tau" in wanted, files)
    # the nutation ϑ and azimuth φ_G of G in body axes, the z-x-z precession ψ, with the
    # approximations at τ(t); one legend per row, right of the last column (over no curve)
    fig, axes = plt.subplots(3, n, figsize=(6 * n, 8), sharex=True, squeeze=False)
    for j, (name, (sol, zv, approx, spec)) in enumerate(results.items()):
        ang = np.column_stack([sol["theta_G"], sol["phi_G"]])
        euler = sol.euler_angles()
        ax_psi, ax_th, ax_ph = axes[:, j]
        ax_th.plot(sol.t, ang[:, 0], label="full model")
        ax_ph.plot(sol.t, wrap_angle(ang[:, 1]), label="full model")
        ax_psi.plot(sol.t, wrap_angle(euler[:, 0]), label="full model (quaternion; inertial G moves)")
        styles = {"exact": ("k:", "torque-free ZV at τ(t)"), "zeroth": ("--", "zeroth approx. (21) at τ(t)"),
                  "first": ("-.", "first approx. (21)+μ(22) at τ(t)")}
        for key, a in approx.items():
            st, label = styles[key]
            if key != "exact":
                ax_th.plot(sol.t, a[:, 1], st, label=label)
                ax_ph.plot(sol.t, wrap_angle(a[:, 2]), st, label=label)
            ax_psi.plot(sol.t, wrap_angle(a[:, 0]), st, label=label)
        ax_psi.set_title(f"{_law_text(spec)}")
        mark_singular(ax_th, sol.t, ang[:, 0])
        ax_psi.set_ylabel("ψ precession, z-x-z [rad]")
        ax_th.set_ylabel("ϑ nutation: body z to G [rad]")
        ax_ph.set_ylabel("φ_G azimuth of G in body [rad]")
        ax_ph.set_xlabel("t [s]")
        for ax in axes[:, j]:
            ax.grid(alpha=0.3)
    for ax in axes[:, -1]:
        legend_outside(ax)
    fig.suptitle(f"{scene.title}: G in body axes (nutation ϑ, azimuth φ_G) and the precession ψ", fontsize=10)
    keep(fig, folder / "euler_angles.png", "euler_angles" in wanted, files)
    # errors of the approximations (nearly spherical only)
    if spherical is not None and "approximation_errors" in wanted:
        fig, axes = plt.subplots(1, n, figsize=(6 * n, 4), squeeze=False)
        for ax, (name, (sol, zv, approx, spec)) in zip(axes[0], results.items()):
            ang = np.column_stack([sol["theta_G"], sol["phi_G"]])
            for key, st in (("zeroth", "--"), ("first", "-")):
                a = approx[key]
                ax.semilogy(sol.t, np.maximum(np.abs(ang[:, 0] - a[:, 1]), 1e-16), st, label=f"|Δθ| {key}")
                ax.semilogy(sol.t, np.maximum(np.abs(wrap(approx["exact"][:, 0] - a[:, 0])), 1e-16), st,
                            label=f"|Δψ| {key} (vs ZV ψ at τ(t))")
            ax.set_xlabel("t [s]")
            ax.set_ylabel("error [rad]")
            ax.set_ylim(1e-6, 5.0)
            ax.set_title(f"approximations at τ(t) vs full model, μ = {spherical.mu:g}, {_law_text(spec)}",
                         fontsize=9)
            ax.grid(alpha=0.3, which="both")
            ax.legend(fontsize=LEGEND_SIZE)
        files.append(figures.finish(fig, folder / "approximation_errors.png"))
    return files


# ------------------------------------------------------------------------------------ the scene kind
LAW = Variants("kind", {
    "constant": Table({"value": Field(float, required=True, doc="L", unit="N m", check=finite_value)}),
    "polynomial": Table({"coefficients": Field(ListOf(float, min_len=1), required=True, doc="c_i: L = sum c_i t^i")}),
    "harmonic": Table({"mean": Field(float, required=True, doc="L0", unit="N m"),
                       "amplitudes": Field(ListOf(float), default=[], doc="A_i", unit="N m"),
                       "frequencies": Field(ListOf(float), default=[], doc="w_i", unit="rad/s"),
                       "phases": Field(ListOf(float), doc="phi_i (default 0)", unit="rad")}),
    "tabulated": Table({"times": Field(ListOf(float, min_len=2), required=True, doc="t_i", unit="s",
                                       check=increasing),
                        "values": Field(ListOf(float, min_len=2), required=True, doc="L_i", unit="N m"),
                        "interpolation": Field(Choice("linear", "cubic"), default="linear", doc="between points")}),
}, doc="the magnitude law L(t)")


WHY_TOLERANCES = ("the paper's frozen values of tau and g are read at the end of long runs through the "
                  "regularised switch of the servo, where an error of 1e-8 shows")


class OrthogonalTorqueKind(Kind):
    name = "orthogonal_torque"
    doc = ("Paper 004: a gyrostat under the servo torque L(t) Q/|Q|, Q = omega x G, one run per magnitude law, "
           "compared with the torque-free gyrostat at tau(t) and, for a nearly spherical body, with the "
           "approximations of section 4.")
    plots = ("omega", "invariants", "tau", "euler_angles", "approximation_errors")
    splits = True

    @property
    def schema(self) -> Table:
        return Table({
            **title_fields(),
            "body": Field(BODY, doc="a gyrostat (or give [nearly_spherical])"),
            "nearly_spherical": Field(Table({
                "J": Field(float, required=True, doc="mean moment", unit="kg m^2", check=positive),
                "Jj": Field(Vector(3), required=True, doc="A_j = J + mu J_j", unit="kg m^2"),
                "mu": Field(float, required=True, doc="small parameter mu"),
                "rotor": Field(Vector(3), default=[0.0, 0.0, 0.0], doc="rotor momentum k", unit="kg m^2/s"),
                "G": Field(float, default=1.0, doc="|G|", unit="kg m^2/s", check=positive),
                "theta0": Field(float, default=1.0, doc="initial nutation of G in body axes", unit="rad"),
                "phi0": Field(float, default=0.0, doc="initial proper rotation", unit="rad"),
                "psi0": Field(float, default=0.0, doc="initial precession", unit="rad"),
            }), doc="a nearly spherical gyrostat A_j = J + mu J_j, its initial state from G and the Euler angles"),
            "initial": Field(Table({
                "omega": Field(Vector(3), doc="angular velocity (with [body])", unit="rad/s", check=all_finite),
                "attitude": Field(Vector(4), doc="quaternion (w, x, y, z); default: inertial z along G(0)",
                                  check=nonzero_quaternion),
            }), default={}, doc="the initial state (with [body])"),
            "runs": Field(ArrayOf(Table({"name": Field(str, required=True, doc="the run's name"),
                                         "law": Field(OneOf(float, LAW), required=True,
                                                      doc="L(t): a number, or a table with its kind")})),
                          required=True, doc="one run per magnitude law"),
            "integration": Field(Table({"method": METHOD,
                                        "rtol": engine_option("rtol", float, "relative tolerance", 1e-10, WHY_TOLERANCES),
                                        "atol": engine_option("atol", float, "absolute tolerance", 1e-12, WHY_TOLERANCES),
                                        "t_span": Field(Vector(2), default=[0.0, 60.0], doc="(t0, t1)", unit="s",
                                                        check=span_order),
                                        "n_out": engine_option("n_out", int, "number of output times", 1201,
                                                               "20 points per second over the default 60 s span"),
                                        "eta": Field(float, default=ETA,
                                                     doc="regularisation: delta = eta |omega| |G|", check=positive),
                                        **SPLITTING_FIELDS}),
                                 default={}, doc="the runs' integration"),
            "outputs": outputs_field(self.plots, list(self.plots)),
        })

    def spherical(self, doc: dict):
        s = doc.get("nearly_spherical")
        if s is None:
            return None
        return build("nearly_spherical", NearlySpherical, s["J"], s["Jj"], s["mu"], s["rotor"], s["G"],
                      s["theta0"], s["phi0"], s["psi0"])

    def runs(self, doc):
        if ("body" in doc) == ("nearly_spherical" in doc):
            raise SceneError("needs exactly one of [body] or [nearly_spherical]"
                             + ("; both are given" if "body" in doc else "; none is given"))
        spherical = self.spherical(doc)
        if spherical is not None:
            body = spherical.body()
            omega0, q0 = spherical.initial_state()
            if doc["initial"]:
                raise SceneError("[initial] is not used with [nearly_spherical] (the state follows from G and the angles)")
        else:
            body = make_body(doc)
            if "omega" not in doc["initial"]:
                raise SceneError("[initial] is missing required key 'omega' (angular velocity in body axes [rad/s])")
            omega0 = np.asarray(doc["initial"]["omega"], float)
            if "attitude" in doc["initial"]:
                q0 = _core.unit_vector(doc["initial"]["attitude"], "[initial] attitude")
            else:  # inertial z3 along G(0), ψ0 = 0: the Euler angles of (15)-(16)
                q0 = attitude_along_momentum(np.asarray(body.inertia) @ omega0 + np.asarray(body.rotor))
        integ = doc["integration"]
        runs = []
        for i, spec in enumerate(doc["runs"]):
            law = build(f"runs[{i}].law", law_from_spec, spec["law"])
            model = build(f"runs[{i}]", OrthogonalModel, body, law, (), True, integ["eta"])
            runs.append(Run(spec["name"], model, np.concatenate([omega0, q0, [0.0]]), tuple(integ["t_span"]),
                            integration(doc, self, events=g_zero())))
        names = [r.name for r in runs]
        if len(set(names)) != len(names):
            raise SceneError(f"[runs] names must differ; got {names}")
        return (runs, "orthogonal_torque", "full model in t with tau and the attitude quaternion (paper 004); the "
                "torque-free (Zhukovsky-Volterra) solution at tau(t) and, for a nearly spherical body, the "
                "approximations of section 4 for comparison")

    def analyse(self, scene, solutions, report, derived):
        analyse(scene, solutions, report, derived)

    def draw(self, scene, solutions, derived, folder):
        return draw(scene, solutions, derived, folder)

    def why_not_drawn(self, doc, plot):
        if plot == "approximation_errors" and self.spherical(doc) is None:
            return "the zeroth and first approximations are for a nearly spherical body ([nearly_spherical]), not [body]"
        return ""


register(OrthogonalTorqueKind())
