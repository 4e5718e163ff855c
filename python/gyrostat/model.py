"""Models: what the engine integrates. Every family (the gyrostat, the averaged symmetric system,
the explicit moving mass, the closed-form torque-free body, the Lagrange top and its averaged
system, the orthogonal servo torque) is a :class:`ModelBase`: a C++ model with named state
components and named outputs, solved by :func:`gyrostat.solve` and :func:`gyrostat.solve_ensemble`.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from gyrostat import _core

TORQUE_TYPES = (_core.ConstantTorque, _core.LinearDamping, _core.ResistiveMedium, _core.ViscousCavity,
                _core.MovingMassDamper)


def shown(value, limit: int = 60) -> str:
    """``repr(value)`` on one line, shortened to ``limit`` characters: for error messages."""
    text = " ".join(repr(value).split())
    return text if len(text) <= limit else text[:limit - 3] + "..."


def floats(value, name: str, what: str = "real numbers") -> np.ndarray:
    """``value`` as an array of floats, or a one-line ValueError naming ``name``, ``what`` it must
    be and the value: strings, None, booleans alone, complex numbers and ragged lists are refused,
    never cast (NumPy would say "could not convert string to float" or drop an imaginary part)."""
    try:
        array = np.asarray(value)
    except (TypeError, ValueError):  # a ragged list
        array = None
    if array is None or array.dtype.kind not in "iuf":
        raise ValueError(f"{name} must be {what}, got {shown(value)}")
    return array.astype(float, copy=False)


def number(value, name: str) -> float:
    """``value`` as one float, or a one-line ValueError naming ``name`` and the value (as :func:`floats`)."""
    array = floats(value, name, "a number")
    if array.ndim:
        raise ValueError(f"{name} must be a number, got {shown(value)}")
    return float(array)


def flag(value, name: str) -> bool:
    """``value`` as a bool, or a ValueError naming ``name``: only True and False are booleans
    (``bool("no")`` is True; 0 and 1 are numbers)."""
    if isinstance(value, (bool, np.bool_)):
        return bool(value)
    raise ValueError(f"{name} = {shown(value)} must be True or False")


def check_torques(torques) -> tuple:
    """The torques as a tuple (a single torque is a list of one); anything that is not a torque
    raises TypeError naming its type."""
    if isinstance(torques, TORQUE_TYPES):
        return (torques,)
    if isinstance(torques, (str, bytes)) or not hasattr(torques, "__iter__"):
        raise TypeError(f"torques must be a list of torques, got {type(torques).__name__}")
    torques = tuple(torques)
    for torque in torques:
        if not isinstance(torque, TORQUE_TYPES):
            raise TypeError(f"not a torque: {type(torque).__name__} (torques are "
                            + ", ".join(t.__name__ for t in TORQUE_TYPES) + ")")
    return torques


def check_body(body) -> _core.Body:
    if not isinstance(body, _core.Body):
        raise TypeError(f"body must be a gyrostat.Body, not {type(body).__name__}")
    return body


class ModelBase:
    """What every model gives: its C++ model (``_core``), its family, the names of its state
    components and of the outputs recorded at every output time.

    Subclasses set ``_core`` in their constructor; ``kind`` names the model in reports.
    """

    __slots__ = ("_core", "__dict__")
    kind = "model"

    @property
    def family(self) -> str:
        return self._core.family

    @property
    def dim(self) -> int:
        """Size of the state vector."""
        return self._core.dim

    @property
    def state_names(self) -> tuple[str, ...]:
        return tuple(self._core.state_names)

    @property
    def output_names(self) -> tuple[str, ...]:
        """Quantities recorded by the engine at every output time (``solution[name]``)."""
        return tuple(self._core.output_names)

    @property
    def attitude(self) -> bool:
        """Whether the state holds the attitude quaternion (q_w, q_x, q_y, q_z)."""
        return "q_w" in self._core.state_names

    def rhs(self, t: float, y) -> np.ndarray:
        """The right-hand side f(t, y), evaluated by the core (for checks, not for speed)."""
        return np.asarray(self._core.rhs(number(t, "t"), floats(y, "y")))

    def initial_state(self, y0) -> np.ndarray:
        """The full initial state from a shorter one where the model allows it (ω alone for a
        model with attitude: identity quaternion; τ(0) = 0 for the orthogonal torque)."""
        return np.asarray(self._core.initial_state(floats(y0, "y0").ravel()))

    def check(self, solution) -> list:
        """The model's assumptions along a solution (averaged models override this);
        :func:`gyrostat.solve` warns for broken ones."""
        return []


class Model(ModelBase):
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

    Outputs: ``angular_momentum_norm`` |G|, ``kinetic_energy`` T and, with attitude, the z-x-z
    Euler angles ``psi``, ``theta``, ``phi``.
    """

    kind = "full"

    def __init__(self, body: _core.Body, torques: Sequence = (), attitude: bool = False):
        self.body = check_body(body)
        self.torques = check_torques(torques)
        self._core = _core.gyrostat_model(body, self.torques, flag(attitude, "attitude"))

    @property
    def is_torque_free_rigid_body(self) -> bool:
        """No torque and no rotor: the closed form (no integration) answers such a scene."""
        return not self.torques and not any(self.body.rotor)

    def __repr__(self) -> str:
        return f"Model({self.body!r}, torques={list(self.torques)!r}, attitude={self.attitude})"


class TorqueFreeModel(ModelBase):
    """The torque-free rigid body in closed form: Jacobi elliptic functions, no integration.

    State ω = (p, q, r), or with ``attitude=True`` ω and the quaternion (q_w, q_x, q_y, q_z)
    rotating body axes into inertial axes (the exact flow: the rotation about the fixed inertial
    angular momentum from the incomplete elliptic integral of the third kind; see
    docs/integrators.md). Outputs |G| and T (exact to rounding at any t) and, with attitude, the
    z-x-z Euler angles. A gyrostat (rotor k ≠ 0) has a closed form here only for a symmetric body
    with the rotor along its symmetry axis (or a spherical body); any other rotor raises
    ValueError naming the body (use :class:`Model`, which integrates)."""

    kind = "closed_form"

    def __init__(self, body: _core.Body, attitude: bool = False):
        self.body = check_body(body)
        self.torques = ()
        self._core = _core.torque_free_model(body, flag(attitude, "attitude"))

    def __repr__(self) -> str:
        return f"TorqueFreeModel({self.body!r}, attitude={self.attitude})"


class AveragedModel(ModelBase):
    """The system averaged over the symmetric Euler–Poinsot motion, in slow variables (a, r).

    The body is (nearly) symmetric: A = A1 ≈ A2, C = A3, no rotor. The generating motion is
    p = a cos φ, q = a sin φ, r = const, φ̇ = (C − A) r / A; each torque contributes its own
    averaged (ȧ, ṙ) and the contributions add up. r is signed and may pass through zero (the
    papers' x = a², y = r² form cannot). Outputs: |G|, T, ``x`` = a², ``y`` = r², the fast
    frequency and ``slow_to_fast`` (must stay ≪ 1). :func:`gyrostat.validity.check` reports
    where the assumptions fail; :func:`gyrostat.solve` does so by itself.
    """

    kind = "averaged"

    def __init__(self, body: _core.Body, torques: Sequence = ()):
        self.body = check_body(body)
        self.torques = check_torques(torques)
        self._core = _core.averaged_model(body, self.torques)

    @property
    def A(self) -> float:
        return float(self.body.moments[0])

    @property
    def C(self) -> float:
        return float(self.body.moments[2])

    def fast_frequency(self, r: float) -> float:
        """|φ̇| = |(C − A) r / A|."""
        return self._core.fast_frequency(number(r, "r"))

    def slow_rate(self, t: float, y) -> float:
        """max(|ȧ/a|, |ṙ/r|) at (t, a, r)."""
        return self._core.slow_rate(number(t, "t"), floats(y, "y"))

    def check(self, solution) -> list:
        from gyrostat import validity

        return validity.check(self, solution.y, solution.t, warn=False, outputs=solution.outputs)

    def __repr__(self) -> str:
        return f"AveragedModel({self.body!r}, torques={list(self.torques)!r})"


class MovingMassModel(ModelBase):
    """The explicit model behind the damper reduction: a carrier plus a point mass on a spring
    (Ω² = c/μ) with a viscous damper (λ = δ/μ), attached on the z axis at distance ρ.

    State (9): ω, the mass's displacement u and its velocity v relative to the carrier (body
    axes). ``body`` holds the whole system's moments with the mass at rest; the carrier's own are
    (A1 − μρ², A2 − μρ², A3). Extra torques act on the carrier. Stiff for a strong damper: solve
    it with ``method="cvode_bdf"``. :meth:`quasi_static_state` gives (u, v) for a start without
    free oscillation of the mass. Outputs: |K| (conserved) and the energy E (dissipated).
    """

    kind = "moving_mass"

    def __init__(self, body: _core.Body, mass: float, arm: float, frequency: float, damping: float,
                 torques: Sequence = ()):
        self.body = check_body(body)
        self.torques = check_torques(torques)
        self._core = _core.moving_mass_model(body, mass, arm, frequency, damping, self.torques)  # checks the numbers
        self.mass, self.arm, self.frequency, self.damping = float(mass), float(arm), float(frequency), float(damping)

    def damper(self) -> _core.MovingMassDamper:
        """The reduced (quasi-static) torque of the same mass, spring and damper."""
        return _core.MovingMassDamper(self.mass, self.arm, self.frequency, self.damping)

    def quasi_static_state(self, omega) -> np.ndarray:
        return np.asarray(self._core.quasi_static_state(floats(omega, "omega")))

    def check(self, solution) -> list:
        """The model's assumptions along a solution: the mass's displacement |u|/ρ ≪ 1 (and the
        damper torque's, for the reduction it stands behind)."""
        from gyrostat import validity

        return validity.check(self, solution.y, solution.t, warn=False, outputs=solution.outputs)

    def __repr__(self) -> str:
        return (f"MovingMassModel({self.body!r}, mass={self.mass}, arm={self.arm}, frequency={self.frequency}, "
                f"damping={self.damping}, torques={list(self.torques)!r})")
