"""The Lagrange top's models: the full top :class:`LagrangeTop`, the nutation-averaged
:class:`LagrangeAveraged` with its assumptions (:func:`check`: adiabaticity and the distance from
the separatrix, over the nutation table of the slow variables), paper 003's torque
(:func:`paper_torque`) and the initial state and vertical of a top."""

from __future__ import annotations

import math
import warnings
from collections.abc import Sequence

import numpy as np

from gyrostat import _core, attitude
from gyrostat.assumptions import SMALL, Assumption, ValidityWarning
from gyrostat.modelbase import ModelBase, check_torques, number


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

    _numbers = ("A", "C", "mu")  # its own parameters (gyrostat.sensitivity)

    def _arguments(self) -> dict:
        """What it was built from, as its constructor takes it (gyrostat.sensitivity rebuilds from it)."""
        return {"A": self.A, "C": self.C, "mu": self.mu, "torques": self.torques}

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
