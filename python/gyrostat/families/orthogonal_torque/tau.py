"""Where the clock τ(t) of the orthogonal torque stops: the events g = dτ/dt = 0
(:func:`g_zero`), the report of a run (:func:`tau_report`) and, for a constant law, the range of
|Q| on the torque-free orbit and the regime it decides (:func:`orbit_q_range`,
:func:`constant_law_regime`)."""

from __future__ import annotations

import numpy as np

from gyrostat.events import Event
from gyrostat.families.orthogonal_torque.models import OrthogonalModel
from gyrostat.solve import solve


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

