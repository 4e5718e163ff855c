"""The Lagrange top family (paper 003): a heavy symmetric top under a small, slowly varying torque.

A family module provides its models (``ModelBase`` subclasses with their own assumptions), its
paper helpers and analysis, its plots (drawn with :mod:`gyrostat.figures`), its scene kind(s)
(:class:`gyrostat.kind.Kind`: schema and defaults, runs, ladder rungs, checks, analysis, plots)
and one ``register(...)`` line; see :mod:`gyrostat.families.rigid_body` for the full recipe.
Here the kind ``lagrange_top``, whose ladder is: averaged over the nutation (G_z, H, r) -> full
top (ω, quaternion). :mod:`gyrostat.lagrange` re-exports the models and helpers.

Two models, both integrated by the C++ core:

* :class:`LagrangeTop` — the full model. State ``(p, q, r, Q_w, Q_x, Q_y, Q_z)``: angular
  velocity in body axes and the body→space quaternion (z up); the vertical in body axes
  γ = third row of R(Q). No Euler angles are integrated: θ, ψ, φ are outputs only.
* :class:`LagrangeAveraged` — the system averaged over the nutation in the slow variables
  ``(G_z, H, r)`` (the unperturbed first integrals; smooth, no sign bookkeeping), with
  v = ⟨cos θ⟩ = u1 + (u2 − u1)(K − E)/(m K). The roots u1 ≤ u2 ≤ u3 of the nutation cubic are
  reported for every output (the paper's variables).

Both take torques from the library's set; paper 003's (3.1), M = ε(−a(τ)p, −a(τ)q, −b(τ)r),
τ = εt, is :func:`paper_torque` (a ResistiveMedium). Both use the same clock t; the slow time is
τ = εt. The equations, the checks and the discrepancies with the paper are in
docs/papers/003_lagrange_top.md.

Validity of the averaged model (:func:`check`): the nutation period must be short against the
slow time scale, N = rate · T_nut ≪ 1 (rate = max(d/A, d3/C) of the damping), and the motion
must stay away from the separatrix (1 − k² ≳ 1e-3, where K diverges). Broken assumptions are
warned about (:class:`gyrostat.ValidityWarning`) with the number and what to use instead.
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Sequence

import numpy as np

from gyrostat import _core, attitude
from gyrostat import ladder as _ladder
from gyrostat.assumptions import SMALL, Assumption, ValidityWarning
from gyrostat.events import Event
from gyrostat.figures import LEGEND_SIZE, keep, legend_outside, plt, unit_label
from gyrostat.kind import (ACCURACY, METHOD, PHASE, SPLITTING_FIELDS, Kind, Run, build, engine_option, integration,
                           outputs_field, register, title_fields)
from gyrostat.modelbase import ModelBase, check_torques, number
from gyrostat.schema import Choice, Field, ListOf, SceneError, Table, Vector, all_finite, finite, positive

SEPARATRIX_LIMIT = 1e-3
"""1 − k² below this: near the separatrix (K(k) ≈ ln(4/√(1 − k²)), v has an infinite slope)."""


def paper_torque(epsilon: float, a: Sequence[float] = (1.0, 1.0), b: Sequence[float] = (1.0, 1.0)):
    """Paper 003's (3.1): M = ε(−a(τ) p, −a(τ) q, −b(τ) r), τ = εt, a(τ) = Σ a_k τ^k, b likewise.

    As a polynomial in t: D_k = ε^{k+1} diag(a_k, a_k, b_k) of :class:`gyrostat.ResistiveMedium`.

    Parameters
    ----------
    epsilon : float
        ε ≥ 0, the small parameter (τ = εt; dimensionless).
    a, b : sequence of float, optional
        The coefficients a_k, b_k of a(τ) and b(τ), in N m s (default 1 + τ each).

    Examples
    --------
    >>> from gyrostat import lagrange
    >>> lagrange.paper_torque(0.01, a=[1.0, 0.5], b=[2.0])
    ResistiveMedium(coefficients=[[[0.01, 0, 0], [0, 0.01, 0], [0, 0, 0.02]], [[5e-05, 0, 0], [0, 5e-05, 0], [0, 0, 0]]])
    """
    epsilon = float(epsilon)
    if not math.isfinite(epsilon) or epsilon < 0:
        raise ValueError(f"epsilon = {epsilon} must be finite and non-negative")
    n = max(len(a), len(b))
    a = list(a) + [0.0] * (n - len(a))
    b = list(b) + [0.0] * (n - len(b))
    return _core.ResistiveMedium([epsilon ** (k + 1) * np.diag([a[k], a[k], b[k]]) for k in range(n)])


class _TopModel(ModelBase):
    def __init__(self, A: float, C: float, mu: float, torques: Sequence = ()):
        self.A, self.C, self.mu = number(A, "A"), number(C, "C"), number(mu, "mu")
        self.body = _core.Body([self.A, self.A, self.C])
        self.torques = check_torques(torques)
        self._core = self._make(self.body, self.mu, self.torques)

    def __repr__(self) -> str:
        return f"{type(self).__name__}(A={self.A}, C={self.C}, mu={self.mu}, torques={list(self.torques)!r})"


class LagrangeTop(_TopModel):
    """The full heavy symmetric top (A, A, C), μ = m g l > 0, plus torques (C++:
    model/lagrange_top.hpp).

    State (p, q, r) in rad/s and the attitude quaternion (``q_w``…``q_z``); outputs G_z and H
    (its first integrals, kg m^2/s and J), kinetic_energy, u1 ≤ u2 ≤ u3, m = k², v = ⟨cos θ⟩,
    T_nut (s) at its (G_z, H, r), cos_theta and the z-x-z Euler angles psi, theta, phi (rad).

    Parameters
    ----------
    A : float
        Equatorial moment of inertia about the fixed point, in kg m^2.
    C : float
        Axial moment of inertia, in kg m^2.
    mu : float
        μ = m g l, the restoring torque's scale, in N m.
    torques : sequence of torques, optional
        Perturbation torques (e.g. :func:`gyrostat.lagrange.paper_torque`).

    Examples
    --------
    Paper 003's top at θ0 = 60° without perturbation: G_z and H stay constant.

    >>> import numpy as np
    >>> import gyrostat
    >>> from gyrostat import lagrange
    >>> top = lagrange.LagrangeTop(A=1.5, C=1.0, mu=0.5)
    >>> y0 = lagrange.initial_state([0.0, 0.0, np.sqrt(3.0)], theta=np.radians(60.0))
    >>> sol = gyrostat.solve(top, y0, (0.0, 20.0))
    >>> round(float(sol["H"][0]), 6), bool(abs(sol["H"][-1] - sol["H"][0]) < 1e-7)
    (1.75, True)
    """

    kind = "lagrange_top"
    _make = staticmethod(_core.lagrange_top_model)


class LagrangeAveraged(_TopModel):
    """The top averaged over the nutation (C++: model/lagrange_averaged.hpp).

    State (G_z, H, r) (a full top state given as y0 is mapped to its (G_z, H, r)); outputs u1,
    u2, u3, m, v, T_nut (s) and the adiabaticity N = rate·T_nut. Torques of the paper's class
    (2.3) only: resistive media and linear damping with D = diag(d, d, d3), axial constant torques.
    Made from the same parameters as :class:`LagrangeTop` (A, C in kg m^2, mu in N m, torques).

    Examples
    --------
    >>> from gyrostat import lagrange
    >>> averaged = lagrange.LagrangeAveraged(A=1.5, C=1.0, mu=0.5, torques=[lagrange.paper_torque(0.01)])
    >>> averaged.state_names
    ('G_z', 'H', 'r')
    """

    kind = "lagrange_averaged"
    _make = staticmethod(_core.lagrange_averaged_model)

    def rate(self, t) -> np.ndarray:
        """max(|d(t)|/A, |d3(t)|/C): the relaxation rate of the slow variables, in 1/s.

        Parameters
        ----------
        t : float or array_like
            Times, in s.

        Examples
        --------
        >>> averaged.rate([0.0, 1.0])  # d(t) = ε + ε² t with ε = 0.01
        array([0.01  , 0.0101])
        """
        return np.array([self._core.rate(float(s)) for s in np.atleast_1d(t)])

    def check(self, solution) -> list:
        return check(self, solution.y, solution.t, warn=False, outputs=solution.outputs)


def initial_state(omega, theta: float, phi: float = 0.0, psi: float = 0.0) -> np.ndarray:
    """(p, q, r, Q) from ω and the z-x-z Euler angles: Q = q_z(ψ) ⊗ q_x(θ) ⊗ q_z(φ).

    Parameters
    ----------
    omega : array_like, shape (3,)
        Angular velocity in body axes, in rad/s.
    theta : float
        Nutation angle θ (from the upward vertical), in rad.
    phi, psi : float, optional
        Proper rotation φ and precession ψ, in rad (default 0).

    Examples
    --------
    >>> import numpy as np
    >>> from gyrostat import lagrange
    >>> lagrange.initial_state([0.0, 0.0, 1.0], theta=np.pi / 2).round(6)
    array([0.      , 0.      , 1.      , 0.707107, 0.707107, 0.      , 0.      ])
    """
    omega = np.asarray(omega, float).ravel()
    if omega.size != 3 or not np.all(np.isfinite(omega)):
        raise ValueError(f"omega must be 3 finite numbers, got {omega!r}")
    return np.concatenate([omega, attitude.quaternion_from_euler([psi, theta, phi], "zxz")])


def vertical(y) -> np.ndarray:
    """(n, 3) upward vertical γ in body axes from full states: the third row of R(Q).

    Parameters
    ----------
    y : array_like, shape (n, 7)
        Full top states (p, q, r, q_w, q_x, q_y, q_z).

    Examples
    --------
    >>> import numpy as np
    >>> from gyrostat import lagrange
    >>> y = lagrange.initial_state([0.0, 0.0, 1.0], theta=np.radians(60.0))
    >>> lagrange.vertical(y[None, :]).round(6)
    array([[0.      , 0.866025, 0.5     ]])
    """
    y = np.atleast_2d(np.asarray(y, float))
    return attitude.rotation_matrix(y[:, 3:7])[:, 2, :]


def nutation_table(model, slow) -> dict[str, np.ndarray]:
    """u1, u2, u3, m = k², alpha (1/s), v = ⟨cos θ⟩, T_nut = 2K/α (s) for each row (G_z, H, r).

    Parameters
    ----------
    model : LagrangeTop or LagrangeAveraged
        The top (A, C, μ).
    slow : array_like, shape (n, 3)
        Slow states (G_z in kg m^2/s, H in J, r in rad/s).

    Examples
    --------
    >>> import numpy as np
    >>> from gyrostat import lagrange
    >>> top = lagrange.LagrangeTop(A=1.5, C=1.0, mu=0.5)
    >>> G_z, H = 0.5 * np.sqrt(3.0), 1.75  # of y0: G_z = C r cos θ0, H = T + μ cos θ0
    >>> table = lagrange.nutation_table(top, [[G_z, H, np.sqrt(3.0)]])
    >>> float(table["u2"][0].round(6)), float(table["T_nut"][0].round(6))
    (0.5, 5.839611)
    """
    slow = np.atleast_2d(np.asarray(slow, float))
    table = np.asarray(_core.lagrange_nutation_table(model.A, model.C, model.mu, slow[:, 0].tolist(),
                                                     slow[:, 1].tolist(), slow[:, 2].tolist()))
    return {name: table[:, i] for i, name in enumerate(("u1", "u2", "u3", "m", "alpha", "v", "T_nut"))}


def unperturbed(model, y0, t, t0: float = 0.0) -> tuple[np.ndarray, "_core.LagrangeUnperturbed"]:
    """u(t) = cos θ(t) of the unperturbed top through the initial full state y0 (paper (1.3),
    u = u1 + (u2 − u1) sn²(αt + β | k²)); returns (u, the closed-form object).

    Parameters
    ----------
    model : LagrangeTop
        The top (A, C, μ).
    y0 : array_like, shape (7,)
        The full state at t0.
    t : array_like
        Times, in s.
    t0 : float, optional
        The time of y0, in s.

    Examples
    --------
    >>> import numpy as np
    >>> from gyrostat import lagrange
    >>> top = lagrange.LagrangeTop(A=1.5, C=1.0, mu=0.5)
    >>> y0 = lagrange.initial_state([0.0, 0.0, np.sqrt(3.0)], theta=np.radians(60.0))
    >>> u, closed_form = lagrange.unperturbed(top, y0, [0.0, 1.0])
    >>> u.round(6)
    array([0.5     , 0.382275])
    """
    y0 = np.asarray(y0, float).ravel()
    exact = _core.LagrangeUnperturbed(model.A, model.C, model.mu, y0[:3], vertical(y0)[0], float(t0))
    return np.asarray(exact.u(np.asarray(t, float).ravel().tolist())), exact


def check(model: LagrangeAveraged, slow, times, warn: bool = True, outputs: dict | None = None) -> list[Assumption]:
    """The averaged model's assumptions along a trajectory of (G_z, H, r) at `times`:
    adiabaticity N = rate·T_nut ≪ 1, distance from the separatrix 1 − k² ≥ 1e-3, and the regular
    precession limit k² → 0 (reported; the averaging holds there). Warns for broken ones.

    Parameters
    ----------
    model : LagrangeAveraged
        The averaged top.
    slow : array_like, shape (n, 3)
        (G_z, H, r) along the trajectory.
    times : array_like, shape (n,)
        Their times, in s.
    warn : bool, optional
        Warn for broken ones (default True).
    outputs : dict, optional
        The outputs a solve recorded at those times (m, T_nut, adiabaticity), used as they are;
        without them the nutation is evaluated at the given states.

    Examples
    --------
    >>> import numpy as np
    >>> import gyrostat
    >>> from gyrostat import lagrange
    >>> averaged = lagrange.LagrangeAveraged(A=1.5, C=1.0, mu=0.5, torques=[lagrange.paper_torque(0.001)])
    >>> y0 = lagrange.initial_state([0.0, 0.0, np.sqrt(3.0)], theta=np.radians(60.0))
    >>> sol = gyrostat.solve(averaged, y0, (0.0, 100.0), n_out=3)
    >>> [bool(c.holds) for c in lagrange.check(averaged, sol.y, sol.t, warn=False)]
    [True, True, True]
    """
    slow = np.atleast_2d(np.asarray(slow, float))
    times = np.asarray(times, float)
    if outputs is not None:
        table = {"m": outputs["m"], "T_nut": outputs["T_nut"]}
        N = outputs["adiabaticity"]
    else:
        table = nutation_table(model, slow)
        N = model.rate(times) * table["T_nut"]
    with np.errstate(invalid="ignore"):
        N = np.where(np.isfinite(table["T_nut"]), N, np.inf)
    worst = int(np.argmax(N))
    results = [Assumption(
        "Lagrange averaged", "nutation period short against the slow time: N = rate·T_nut ≪ 1", float(N[worst]), SMALL,
        bool(N[worst] <= SMALL),
        f"worst at t = {times[worst]:.4g} (T_nut = {table['T_nut'][worst]:.4g}, k² = {table['m'][worst]:.4g}); "
        + ("" if N[worst] <= SMALL else "the averaged model is not accurate there: use the full LagrangeTop "
           "or a smaller epsilon"))]
    gap = 1.0 - table["m"]
    near = int(np.argmin(gap))
    results.append(Assumption(
        "Lagrange averaged", "away from the separatrix: 1 − k² ≥ 1e-3", float(gap[near]), SEPARATRIX_LIMIT,
        bool(gap[near] >= SEPARATRIX_LIMIT),
        f"closest at t = {times[near]:.4g}" + ("" if gap[near] >= SEPARATRIX_LIMIT else
                                               "; K(k) diverges and v has an infinite slope there, the error of "
                                               "averaging degrades to O(ε^½): use the full LagrangeTop")))
    smallest = int(np.argmin(table["m"]))
    results.append(Assumption(
        "Lagrange averaged", "regular precession limit k² → 0 (averaging holds; the roots u1, u2 are "
        "individually ill-conditioned there)", float(table["m"][smallest]), 0.0, True,
        f"smallest at t = {times[smallest]:.4g}; G_z, H, r and v stay accurate, u1 and u2 individually carry "
        "errors up to ~1e-8 (square-root sensitivity of a double root)"))
    if warn:
        for a in results:
            if not a.holds:
                warnings.warn(str(a), ValidityWarning, stacklevel=2)
    return results


def turning_points(direction: int = 0, terminal: bool | int = False) -> Event:
    """The turning points of the nutation of the full top: d(cos θ)/dt = γ1 q − γ2 p = 0 (the
    output ``cos_theta_rate``); direction −1: θ at a minimum (cos θ at a maximum), +1: θ at a maximum.

    Parameters
    ----------
    direction : {-1, 0, 1}, optional
        Which turning points (default both).
    terminal : bool or int, optional
        Stop the run at the first (True) or n-th one.

    Examples
    --------
    >>> import numpy as np
    >>> import gyrostat
    >>> from gyrostat import lagrange
    >>> top = lagrange.LagrangeTop(A=1.5, C=1.0, mu=0.5)
    >>> y0 = lagrange.initial_state([0.0, 0.0, np.sqrt(3.0)], theta=np.radians(60.0))
    >>> sol = gyrostat.solve(top, y0, (0.0, 20.0), events=[lagrange.turning_points(direction=1)])
    >>> np.diff(sol.t_events[0]).round(4)  # one nutation period apart
    array([5.8396, 5.8396])
    """
    return Event("cos_theta_rate", 0.0, direction, terminal, "nutation turning point")


def near_separatrix(limit: float = SEPARATRIX_LIMIT, terminal: bool | int = False) -> Event:
    """k² rising through 1 − limit: the motion approaches the separatrix, where the nutation
    period diverges and the averaging degrades (full or averaged top: the output ``m``).

    Parameters
    ----------
    limit : float, optional
        1 − k² at the event (dimensionless; default 1e-3).
    terminal : bool or int, optional
        Stop the run there.

    Examples
    --------
    >>> from gyrostat import lagrange
    >>> lagrange.near_separatrix().value
    0.999
    """
    return Event("m", 1.0 - float(limit), 1, terminal, f"1 - k^2 falls to {limit:g}")


def averaging_fails(limit: float = SMALL, terminal: bool | int = False) -> Event:
    """The averaged top's adiabaticity N = rate·T_nut rising through ``limit``.

    Parameters
    ----------
    limit : float, optional
        N at the event (dimensionless; default "≪ 1" = 0.1).
    terminal : bool or int, optional
        Stop the run there.

    Returns
    -------
    gyrostat.events.Event
        On the averaged top's output ``adiabaticity``, upward.

    Examples
    --------
    >>> from gyrostat import lagrange
    >>> lagrange.averaging_fails(terminal=True).quantity
    'adiabaticity'
    """
    return Event("adiabaticity", float(limit), 1, terminal, f"N = rate T_nut reaches {limit:g}")


def r_exact(r0: float, C: float, epsilon: float, b: Sequence[float], t) -> np.ndarray:
    """Paper (3.3) generalised: r = r0 exp(−(1/C) ∫_0^τ b(s) ds), τ = εt, b(τ) = Σ b_k τ^k.

    Parameters
    ----------
    r0 : float
        r at t = 0, in rad/s.
    C : float
        Axial moment of inertia, in kg m^2.
    epsilon : float
        ε (dimensionless).
    b : sequence of float
        The coefficients b_k of b(τ), in N m s.
    t : array_like
        Times, in s.

    Examples
    --------
    >>> from gyrostat import lagrange
    >>> lagrange.r_exact(1.0, 1.0, 0.01, [1.0], [0.0, 100.0]).round(6)  # r0 exp(-1) at τ = 1
    array([1.      , 0.367879])
    """
    tau = epsilon * np.asarray(t, float)
    integral = sum(bk * tau ** (k + 1) / (k + 1) for k, bk in enumerate(b))
    return r0 * np.exp(-integral / C)


def top_slow_variables(solution) -> np.ndarray:
    """(G_z, H, r) of a heavy top, full (outputs) or averaged (state): (n, 3) (what the ladder compares)."""
    return np.column_stack([solution["G_z"], solution["H"], solution["r"]])


# ------------------------------------------------------------------------------------ analysis
def analyse(scene, solutions: dict, report: dict, derived: dict) -> None:
    """The exact r of paper (3.3), the initial nutation, and the averaged against the full top."""
    full, averaged = solutions.get("full"), solutions.get("averaged")
    tq = scene.doc["torque"]
    main = full if full is not None else averaged
    n = min(len(s) for s in (full, averaged) if s is not None)
    r0 = scene.runs[0].y0[2]
    exact_r = r_exact(r0, scene.doc["body"]["C"], tq["epsilon"], tq["b"], main.t[:n])
    derived["exact_r"] = exact_r
    if averaged is not None and len(averaged):
        report["initial_nutation"] = {k: float(averaged[k][0]) for k in ("u1", "u2", "u3", "m", "v", "T_nut")}
    if full is not None and averaged is not None:
        report["averaged_vs_full_slow"] = {f"max_abs_error_{k}": float(np.max(np.abs(full[k][:n] - averaged[k][:n])))
                                           for k in ("G_z", "H", "r", "u1", "u2", "u3", "v")}
    report["r_vs_exact_3_3"] = {name: float(np.max(np.abs(s["r"][:n] - exact_r)))
                                for name, s in (("full", full), ("averaged", averaged)) if s is not None}


# ------------------------------------------------------------------------------------ plots
def draw(scene, solutions: dict, derived: dict, folder) -> list:
    """slow.png (G_z, H, r), roots.png (u1, u2, u3 and cos θ), nutation.png (θ), validity.png; the
    full and the averaged top side by side, or the one the model ladder chose."""
    full, avg, exact_r = solutions.get("full"), solutions.get("averaged"), derived["exact_r"]
    epsilon = scene.doc["torque"]["epsilon"]
    main = full if full is not None else avg
    # drawn against t [s]; the paper's slow time τ = εt is the top axis (its scale, not a unit)
    t_f = full.t if full is not None else None
    t_a = avg.t if avg is not None else None

    def slow_axis(ax):
        top = ax.secondary_xaxis("top", functions=(lambda t: epsilon * t, lambda tau: tau / epsilon))
        top.set_xlabel(f"slow time τ = εt (ε = {epsilon:g})", fontsize=LEGEND_SIZE)
    case = f"{scene.title} (ε = {epsilon:g})"
    sf = dict(lw=0.6, color="tab:blue", alpha=0.8)
    sa = dict(lw=1.8, ls="--", color="tab:orange")
    files = []
    wanted = set(scene.plots)
    both = full is not None and avg is not None

    fig, axes = plt.subplots(4 if both else 3, 1, figsize=(8, 10 if both else 8), sharex=True)
    for ax, key in zip(axes, ("G_z", "H", "r")):
        if full is not None:
            ax.plot(t_f, full[key], label="full model (ω, quaternion)", **sf)
        if avg is not None:
            ax.plot(t_a, avg[key], label="averaged over nutation", **sa)
        if key == "r":
            ax.plot(main.t[: exact_r.size], exact_r, "k:", lw=1.2, label="exact (3.3)")
        ax.set_ylabel(unit_label(avg if avg is not None else full, key))
        ax.grid(alpha=0.3)
        legend_outside(ax)
    if both:  # G_z and H have different units: their differences relative to each one's start
        n = min(t_f.size, t_a.size)
        for key, color in (("G_z", "tab:blue"), ("H", "tab:red")):
            scale = abs(avg[key][0]) or 1.0
            axes[3].plot(t_f[:n], (full[key][:n] - avg[key][:n]) / scale, lw=0.6, color=color,
                         label=f"{key}: (full − averaged)/|{key}(0)|")
        axes[3].set_ylabel("relative difference [1]")
        axes[3].grid(alpha=0.3)
        legend_outside(axes[3])
    axes[0].set_title(f"{case}: first integrals")
    slow_axis(axes[0])
    axes[-1].set_xlabel("t [s]")
    keep(fig, folder / "slow.png", "slow" in wanted, files)

    fig, axes = plt.subplots(2, 1, figsize=(8, 7), sharex=True, gridspec_kw=dict(height_ratios=[1, 1.6]))
    if full is not None:
        axes[0].plot(t_f, full["u3"], label="u3 (full: roots of its G_z, H, r)", **sf)
        axes[1].plot(t_f, full["cos_theta"], lw=0.4, color="0.75", label="cos θ (full model)")
    if avg is not None:
        axes[0].plot(t_a, avg["u3"], label="u3 (averaged)", **sa)
    axes[0].set_ylabel("u3 (≥ 1) [1]")
    for key, color in (("u1", "tab:blue"), ("u2", "tab:green")):
        if full is not None:
            axes[1].plot(t_f, full[key], lw=0.8, color=color, label=f"{key} (full)")
        if avg is not None:
            axes[1].plot(t_a, avg[key], lw=1.8, ls="--", color="tab:orange" if key == "u1" else "tab:red",
                         label=f"{key} (averaged)")
    axes[1].set_ylabel("u = cos θ: u1 ≤ cos θ ≤ u2 [1]")
    for ax in axes:
        ax.grid(alpha=0.3)
        legend_outside(ax)
    axes[0].set_title(f"{case}: roots of the nutation cubic")
    slow_axis(axes[0])
    axes[-1].set_xlabel("t [s]")
    keep(fig, folder / "roots.png", "roots" in wanted, files)

    bounds, t_b = (avg, t_a) if avg is not None else (full, t_f)
    fig, ax = plt.subplots(figsize=(8, 4.5))
    if full is not None:
        ax.plot(t_f, np.degrees(full["theta"]), lw=0.4, color="tab:blue", label="θ (full model)")
    with np.errstate(invalid="ignore"):  # the bounds in the colours of roots.png: u1 orange, u2 red
        for key, style, color in (("u1", "--", "tab:orange"), ("u2", ":", "tab:red")):
            ax.plot(t_b, np.degrees(np.arccos(np.clip(bounds[key], -1, 1))), ls=style, lw=1.8, color=color,
                    label=f"arccos {key}" + (" (averaged)" if bounds is avg else " (full)"))
    ax.set_xlabel("t [s]")
    slow_axis(ax)
    ax.set_ylabel("θ: symmetry axis to the vertical [deg]")
    ax.set_title(f"{case}: nutation between its bounds")
    ax.grid(alpha=0.3)
    legend_outside(ax)
    keep(fig, folder / "nutation.png", "nutation" in wanted, files)

    fig, ax = plt.subplots(figsize=(8, 4.5))
    if "adiabaticity" in bounds:
        ax.semilogy(t_b, bounds["adiabaticity"], label="N = rate · T_nut (must be ≪ 1)")
    ax.semilogy(t_b, np.maximum(1 - bounds["m"], 1e-17), label="1 − k² (separatrix at 0)")
    ax.semilogy(t_b, np.maximum(bounds["m"], 1e-17), label="k² (regular precession at 0)")
    ax.axhline(SMALL, color="tab:blue", ls=":", lw=1, label=f"limit N = {SMALL}")
    ax.axhline(SEPARATRIX_LIMIT, color="tab:orange", ls=":", lw=1, label=f"limit 1 − k² = {SEPARATRIX_LIMIT}")
    ax.set_xlabel("t [s]")
    slow_axis(ax)
    ax.set_ylabel("N, k², 1 − k² [1]")
    ax.set_title(f"{case}: validity of the averaging (along the " + ("averaged" if bounds is avg else "full")
                 + " solution)")
    ax.grid(alpha=0.3, which="both")
    legend_outside(ax)
    keep(fig, folder / "validity.png", "validity" in wanted, files)
    return files


# ------------------------------------------------------------------------------------ the scene kind
WHY_TOLERANCES = ("the scene compares the full top with the nutation-averaged one over a long slow time, whose "
                  "O(eps) difference the integration error must stay far below")


class LagrangeTopKind(Kind):
    name = "lagrange_top"
    doc = ("Paper 003: the heavy symmetric top under M = eps(-a(tau) p, -a(tau) q, -b(tau) r), tau = eps t: the "
           "full top in (omega, quaternion) next to the system averaged over the nutation in (G_z, H, r).")
    plots = ("slow", "roots", "nutation", "validity", "ladder")
    splits = True

    def ladder(self, doc):
        return _lagrange_ladder(self, doc)

    @property
    def schema(self) -> Table:
        return Table({
            **title_fields(),
            "body": Field(Table({"A": Field(float, required=True, doc="equatorial moment", unit="kg m^2",
                                            check=positive),
                                 "C": Field(float, required=True, doc="axial moment", unit="kg m^2", check=positive),
                                 "mu": Field(float, required=True, doc="m g l", unit="N m", check=positive)}),
                          required=True, doc="the top"),
            "torque": Field(Table({"epsilon": Field(float, required=True, doc="eps", check=positive),
                                   "a": Field(ListOf(float, min_len=1), required=True, doc="a_k: a(tau) = sum a_k tau^k"),
                                   "b": Field(ListOf(float, min_len=1), required=True,
                                              doc="b_k: b(tau) = sum b_k tau^k")}),
                            required=True, doc="paper 003's torque (3.1)"),
            "initial": Field(Table({
                "omega": Field(Vector(3), required=True, doc="angular velocity in body axes", unit="rad/s",
                               check=all_finite),
                "theta_deg": Field(float, default=0.0, doc="nutation angle", unit="deg", check=finite),
                "phi_deg": Field(float, default=0.0, doc="proper rotation angle", unit="deg", check=finite),
                "psi_deg": Field(float, default=0.0, doc="precession angle", unit="deg", check=finite),
            }), required=True, doc="the initial state (z-x-z Euler angles)"),
            "integration": Field(Table({"model": Field(Choice("compare", "auto", "full", "averaged"), default="compare",
                                                       doc="compare: the full and the averaged top side by side; auto: "
                                                           "the cheapest that meets the accuracy (the model ladder)"),
                                        "accuracy": ACCURACY, "phase": PHASE,
                                        "method": METHOD,
                                        "rtol": engine_option("rtol", float, "relative tolerance", 1e-10, WHY_TOLERANCES),
                                        "atol": engine_option("atol", float, "absolute tolerance", 1e-12, WHY_TOLERANCES),
                                        "tau_end": Field(float, required=True, doc="end of the slow time tau = eps t",
                                                         unit="s", check=positive),
                                        "n_out": engine_option("n_out", int, "number of output times", 4001,
                                                               "enough points per nutation period over the paper's "
                                                               "slow-time span to draw the nutation"),
                                        **SPLITTING_FIELDS}),
                                 required=True, doc="the run"),
            "outputs": outputs_field(self.plots, ["slow", "roots", "nutation", "validity"]),
        })

    def runs(self, doc):
        b, tq, ini = doc["body"], doc["torque"], doc["initial"]
        torque = build("torque", paper_torque, tq["epsilon"], tq["a"], tq["b"])
        full = build("body", LagrangeTop, b["A"], b["C"], b["mu"], [torque])
        averaged = build("body", LagrangeAveraged, b["A"], b["C"], b["mu"], [torque])
        y0 = initial_state(ini["omega"], math.radians(ini["theta_deg"]), math.radians(ini["phi_deg"]),
                                    math.radians(ini["psi_deg"]))
        span = (0.0, doc["integration"]["tau_end"] / tq["epsilon"])
        options = integration(doc, self)
        choice = doc["integration"]["model"]
        if options["method"] == "splitting" and choice != "full":
            raise SceneError(f"[integration] method = 'splitting' splits the full top only (the averaged top has no "
                             f"free rotation to split on): set model = 'full' (got model = '{choice}')")
        if choice in ("full", "averaged"):
            return ([Run(choice, full if choice == "full" else averaged, y0, span, options)], choice,
                    "asked for by the scene")
        return ([Run("full", full, y0, span, options), Run("averaged", averaged, y0, span, options)],
                "full_and_averaged",
                f"paper 003: full top (omega, quaternion) next to the nutation-averaged (G_z, H, r) system; "
                f"epsilon = {tq['epsilon']:g}, a = {tq['a']}, b = {tq['b']}")

    def analyse(self, scene, solutions, report, derived):
        analyse(scene, solutions, report, derived)

    def extra_columns(self, scene, solution):
        """The slow time τ = εt of paper 003, beside t."""
        return {"tau": (scene.doc["torque"]["epsilon"] * solution.t, "s")}

    def draw(self, scene, solutions, derived, folder):
        return draw(scene, solutions, derived, folder)


def _lagrange_ladder(kind: "LagrangeTopKind", doc: dict) -> list:
    """The heavy top's rungs: averaged over the nutation in (G_z, H, r), then the full top.
    The averaged one is blocked when a plot needs θ(t) itself; it watches the adiabaticity N and
    the distance from the separatrix 1 − k², switching to the full top where either fails."""
    runs, _, _ = kind.runs({**doc, "integration": {**doc["integration"], "model": "compare"}})
    full, averaged = runs
    slow0 = np.asarray(averaged.model._core.initial_state(full.y0))
    period = float(nutation_table(averaged.model, slow0)["T_nut"][0])
    needs = [p for p in doc["outputs"]["plots"] if p == "nutation"]
    top = _ladder.Rung("full", full.model, full.y0, "the full top (omega, quaternion)",
                       compare=top_slow_variables)
    limit = SEPARATRIX_LIMIT
    lower = _ladder.Rung(
        "averaged", averaged.model, slow0, "the top averaged over the nutation, in (G_z, H, r)",
        compare=top_slow_variables, fast_period=period if period > 0 else math.inf,
        blocked=f"the plots {needs} need theta(t): the averaged top gives its bounds only" if needs else "",
        watches=(_ladder.Watch("adiabaticity", SMALL, 0.5 * SMALL,
                               "nutation period short against the slow time, N << 1", scales_error=True),
                 _ladder.Watch("m", 1.0 - limit, 1.0 - 2.0 * limit, "away from the separatrix, 1 - k^2 >= 1e-3")),
        start_checks=lambda: check(averaged.model, slow0, [0.0], warn=False), run="averaged")
    return [lower, top]


register(LagrangeTopKind())
