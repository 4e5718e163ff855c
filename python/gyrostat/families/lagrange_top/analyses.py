"""The Lagrange top's paper helpers and analysis: the unperturbed motion, the exact r of paper
(3.3), the slow variables the ladder compares, and the scene's analysis (:func:`analyse`)."""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from gyrostat import _core
from gyrostat.families.lagrange_top.models import vertical


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
