"""The nearly spherical gyrostat of paper 004's §4 (:class:`NearlySpherical`): the zeroth and
first approximations of its Euler angles in τ and, for k = 0, its orbit and mean rates."""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from gyrostat import _core, attitude
from gyrostat.families.orthogonal_torque.free_motion import _evaluate_at
from gyrostat.families.orthogonal_torque.laws import _finite
from gyrostat.families.rigid_body import Model


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

