"""Paper 003: a heavy symmetric top (Lagrange case) under a small, slowly varying torque.

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
from gyrostat.events import Event
from gyrostat.model import ModelBase, check_torques, number
from gyrostat.validity import SMALL, Assumption, ValidityWarning

SEPARATRIX_LIMIT = 1e-3
"""1 − k² below this: near the separatrix (K(k) ≈ ln(4/√(1 − k²)), v has an infinite slope)."""


def paper_torque(epsilon: float, a: Sequence[float] = (1.0, 1.0), b: Sequence[float] = (1.0, 1.0)):
    """Paper 003's (3.1): M = ε(−a(τ) p, −a(τ) q, −b(τ) r), τ = εt, a(τ) = Σ a_k τ^k, b likewise.

    As a polynomial in t: D_k = ε^{k+1} diag(a_k, a_k, b_k) of :class:`gyrostat.ResistiveMedium`."""
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
    model/lagrange_top.hpp). State (p, q, r, Q_w, Q_x, Q_y, Q_z) (``q_w``…``q_z``); outputs G_z,
    H (its first integrals), kinetic_energy, u1 ≤ u2 ≤ u3, m = k², v = ⟨cos θ⟩, T_nut at its
    (G_z, H, r), cos_theta and the z-x-z Euler angles psi, theta, phi."""

    kind = "lagrange_top"
    _make = staticmethod(_core.lagrange_top_model)


class LagrangeAveraged(_TopModel):
    """The top averaged over the nutation (C++: model/lagrange_averaged.hpp). State
    (G_z, H, r) (a full top state given as y0 is mapped to its (G_z, H, r)); outputs u1, u2, u3,
    m, v, T_nut and the adiabaticity N = rate·T_nut. Torques of the paper's class (2.3) only:
    resistive media and linear damping with D = diag(d, d, d3), axial constant torques."""

    kind = "lagrange_averaged"
    _make = staticmethod(_core.lagrange_averaged_model)

    def rate(self, t) -> np.ndarray:
        """max(|d(t)|/A, |d3(t)|/C): the relaxation rate of the slow variables."""
        return np.array([self._core.rate(float(s)) for s in np.atleast_1d(t)])

    def check(self, solution) -> list:
        return check(self, solution.y, solution.t, warn=False, outputs=solution.outputs)


def initial_state(omega, theta: float, phi: float = 0.0, psi: float = 0.0) -> np.ndarray:
    """(p, q, r, Q) from ω and the z-x-z Euler angles (radians): Q = q_z(ψ) ⊗ q_x(θ) ⊗ q_z(φ)."""
    omega = np.asarray(omega, float).ravel()
    if omega.size != 3 or not np.all(np.isfinite(omega)):
        raise ValueError(f"omega must be 3 finite numbers, got {omega!r}")
    return np.concatenate([omega, attitude.quaternion_from_euler([psi, theta, phi], "zxz")])


def vertical(y) -> np.ndarray:
    """(n, 3) upward vertical γ in body axes from full states: the third row of R(Q)."""
    y = np.atleast_2d(np.asarray(y, float))
    return attitude.rotation_matrix(y[:, 3:7])[:, 2, :]


def nutation_table(model, slow) -> dict[str, np.ndarray]:
    """u1, u2, u3, m = k², alpha, v = ⟨cos θ⟩, T_nut = 2K/α for each row (G_z, H, r)."""
    slow = np.atleast_2d(np.asarray(slow, float))
    table = np.asarray(_core.lagrange_nutation_table(model.A, model.C, model.mu, slow[:, 0].tolist(),
                                                     slow[:, 1].tolist(), slow[:, 2].tolist()))
    return {name: table[:, i] for i, name in enumerate(("u1", "u2", "u3", "m", "alpha", "v", "T_nut"))}


def unperturbed(model, y0, t, t0: float = 0.0) -> tuple[np.ndarray, "_core.LagrangeUnperturbed"]:
    """u(t) = cos θ(t) of the unperturbed top through the initial full state y0 (paper (1.3),
    u = u1 + (u2 − u1) sn²(αt + β | k²)); returns (u, the closed-form object)."""
    y0 = np.asarray(y0, float).ravel()
    exact = _core.LagrangeUnperturbed(model.A, model.C, model.mu, y0[:3], vertical(y0)[0], float(t0))
    return np.asarray(exact.u(np.asarray(t, float).ravel().tolist())), exact


def check(model: LagrangeAveraged, slow, times, warn: bool = True, outputs: dict | None = None) -> list[Assumption]:
    """The averaged model's assumptions along a trajectory of (G_z, H, r) at `times`:
    adiabaticity N = rate·T_nut ≪ 1, distance from the separatrix 1 − k² ≥ 1e-3, and the regular
    precession limit k² → 0 (reported; the averaging holds there). Warns for broken ones.
    ``outputs``: the outputs a solve recorded at those times (m, T_nut, adiabaticity), used as
    they are; without them the nutation is evaluated at the given states."""
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
    output ``cos_theta_rate``); direction −1: θ at a minimum (cos θ at a maximum), +1: θ at a maximum."""
    return Event("cos_theta_rate", 0.0, direction, terminal, "nutation turning point")


def near_separatrix(limit: float = SEPARATRIX_LIMIT, terminal: bool | int = False) -> Event:
    """k² rising through 1 − limit: the motion approaches the separatrix, where the nutation
    period diverges and the averaging degrades (full or averaged top: the output ``m``)."""
    return Event("m", 1.0 - float(limit), 1, terminal, f"1 - k^2 falls to {limit:g}")


def averaging_fails(limit: float = SMALL, terminal: bool | int = False) -> Event:
    """The averaged top's adiabaticity N = rate·T_nut rising through ``limit``."""
    return Event("adiabaticity", float(limit), 1, terminal, f"N = rate T_nut reaches {limit:g}")


def r_exact(r0: float, C: float, epsilon: float, b: Sequence[float], t) -> np.ndarray:
    """Paper (3.3) generalised: r = r0 exp(−(1/C) ∫_0^τ b(s) ds), τ = εt, b(τ) = Σ b_k τ^k."""
    tau = epsilon * np.asarray(t, float)
    integral = sum(bk * tau ** (k + 1) / (k + 1) for k, bk in enumerate(b))
    return r0 * np.exp(-integral / C)
