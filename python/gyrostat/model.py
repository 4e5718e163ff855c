"""A full model: a body, the torques on it, and whether the attitude is integrated."""

from __future__ import annotations

from collections.abc import Sequence

from gyrostat import _core

STATE_NAMES_RATES = ("p", "q", "r")
STATE_NAMES_ATTITUDE = ("p", "q", "r", "q_w", "q_x", "q_y", "q_z")
TORQUE_TYPES = (_core.ConstantTorque, _core.LinearDamping, _core.ResistiveMedium, _core.ViscousCavity,
                _core.MovingMassDamper)
AFFINE_TORQUES = (_core.ConstantTorque, _core.LinearDamping)


def _check_torques(torques) -> tuple:
    torques = tuple(torques)
    for torque in torques:
        if not isinstance(torque, TORQUE_TYPES):
            raise TypeError(f"unknown torque type {type(torque).__name__}")
    return torques


class Model:
    """The full model: Euler's equations of a gyrostat, J ω̇ + ω × (J ω + k) = Σ M_i(t, ω).

    Parameters
    ----------
    body:
        A :class:`gyrostat.Body` (principal moments and rotor momentum k).
    torques:
        Perturbation torques (:class:`gyrostat.ConstantTorque`, :class:`gyrostat.LinearDamping`,
        :class:`gyrostat.ResistiveMedium`, :class:`gyrostat.ViscousCavity`,
        :class:`gyrostat.MovingMassDamper`); they add up.
    attitude:
        Integrate the attitude quaternion as well (state size 7 instead of 3). Only needed when
        an output or a torque depends on the orientation; it costs four more equations.
    """

    def __init__(self, body: _core.Body, torques: Sequence = (), attitude: bool = False):
        if not isinstance(body, _core.Body):
            raise TypeError(f"body must be a gyrostat.Body, not {type(body).__name__}")
        self.body = body
        self.torques = _check_torques(torques)
        self.attitude = bool(attitude)
        self._core = _core.full_model(body, list(self.torques), self.attitude)

    @property
    def dim(self) -> int:
        """Size of the state vector: 3 (ω) or 7 (ω and the quaternion)."""
        return self._core.dim

    @property
    def state_names(self) -> tuple[str, ...]:
        return STATE_NAMES_ATTITUDE if self.attitude else STATE_NAMES_RATES

    @property
    def is_torque_free_rigid_body(self) -> bool:
        """No torque and no rotor: the closed form (no integration) answers such a scene."""
        return not self.torques and not any(self.body.rotor)

    def rhs(self, t: float, y):
        """The right-hand side f(t, y), evaluated by the core (for checks, not for speed)."""
        return self._core.rhs(t, y)

    kind = "full"

    def __repr__(self) -> str:
        return f"Model({self.body!r}, torques={list(self.torques)!r}, attitude={self.attitude})"


class AveragedModel:
    """The system averaged over the symmetric Euler–Poinsot motion, in slow variables (a, r).

    The body is (nearly) symmetric: A = A1 ≈ A2, C = A3, no rotor. The generating motion is
    p = a cos φ, q = a sin φ, r = const, φ̇ = (C − A) r / A; each torque contributes its own
    averaged (ȧ, ṙ) and the contributions add up. r is signed and may pass through zero (the
    papers' x = a², y = r² form cannot); x and y are derived outputs. Averaging holds while the
    fast frequency |(C − A) r / A| dominates the slow rates: :func:`gyrostat.validity.check`
    reports where it does not.
    """

    kind = "averaged"
    state_names = ("a", "r")
    attitude = False

    def __init__(self, body: _core.Body, torques: Sequence = ()):
        if not isinstance(body, _core.Body):
            raise TypeError(f"body must be a gyrostat.Body, not {type(body).__name__}")
        self.body = body
        self.torques = _check_torques(torques)
        self._core = _core.averaged_model(body, list(self.torques))

    @property
    def dim(self) -> int:
        return 2

    @property
    def A(self) -> float:
        return float(self.body.moments[0])

    @property
    def C(self) -> float:
        return float(self.body.moments[2])

    def fast_frequency(self, r: float) -> float:
        """|φ̇| = |(C − A) r / A|."""
        return self._core.fast_frequency(float(r))

    def slow_rate(self, t: float, y) -> float:
        """max(|ȧ/a|, |ṙ/r|) at (t, a, r)."""
        return self._core.slow_rate(float(t), y)

    def rhs(self, t: float, y):
        return self._core.rhs(t, y)

    def __repr__(self) -> str:
        return f"AveragedModel({self.body!r}, torques={list(self.torques)!r})"


class MovingMassModel:
    """The explicit model behind the damper reduction: a carrier plus a point mass on a spring
    (Ω² = c/μ) with a viscous damper (λ = δ/μ), attached on the z axis at distance ρ.

    State (9): ω, the mass's displacement u and its velocity v relative to the carrier (body
    axes). ``body`` holds the whole system's moments with the mass at rest; the carrier's own are
    (A1 − μρ², A2 − μρ², A3). Extra torques act on the carrier. Stiff for a strong damper: solve
    it with ``method="cvode_bdf"``. :meth:`quasi_static_state` gives (u, v) for a start without
    free oscillation of the mass.
    """

    kind = "moving_mass"
    state_names = ("p", "q", "r", "u_1", "u_2", "u_3", "v_1", "v_2", "v_3")
    attitude = False

    def __init__(self, body: _core.Body, mass: float, arm: float, frequency: float, damping: float,
                 torques: Sequence = ()):
        self.body = body
        self.mass, self.arm, self.frequency, self.damping = float(mass), float(arm), float(frequency), float(damping)
        self.torques = _check_torques(torques)
        self._core = _core.moving_mass_model(body, self.mass, self.arm, self.frequency, self.damping,
                                             list(self.torques))

    @property
    def dim(self) -> int:
        return 9

    def damper(self) -> _core.MovingMassDamper:
        """The reduced (quasi-static) torque of the same mass, spring and damper."""
        return _core.MovingMassDamper(self.mass, self.arm, self.frequency, self.damping)

    def quasi_static_state(self, omega):
        return self._core.quasi_static_state(omega)

    def rhs(self, t: float, y):
        return self._core.rhs(t, y)
