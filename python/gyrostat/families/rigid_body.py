"""The rigid body family: a rigid body or gyrostat under perturbation torques (papers 000-002).

A family module provides, in this order (copy it for a new family):

1. its models: ``ModelBase`` subclasses over the C++ constructors, each with its own
   ``assumptions`` (beside its torques') and ``check``;
2. its paper helpers and analysis functions (from recorded outputs only);
3. its plots, drawn with :mod:`gyrostat.figures`;
4. its scene kind(s): ``Kind`` subclasses (:mod:`gyrostat.kind`) with the schema and defaults,
   the runs, the ladder rungs, the checks, the analysis, the extra columns and the plots;
5. one ``register(...)`` line at the end.

Here: :class:`Model` (Euler's equations of a gyrostat), :class:`TorqueFreeModel` (the closed
form, :func:`torque_free`) and :class:`AveragedModel` (the system averaged over the symmetric
Euler-Poinsot motion in (a, r)); the averaged system's outputs (the papers' x, y, paper 002's
Lotka-Volterra coefficients and first integral, the slow variables of a full solution); the
kinds ``rigid_body`` (the full model, its closed form or the averaged system; its ladder:
closed form (nothing perturbs a rigid body) -> averaged (a, r) -> full (Euler's equations)) and
``averaged`` (the averaged system alone).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from gyrostat import _core, figures
from gyrostat import ladder as _ladder
from gyrostat.assumptions import SMALL, Assumption, check
from gyrostat.events import Event
from gyrostat.figures import LEGEND_SIZE, error, euler_angles, invariants, omega, plt
from gyrostat.kind import (ACCURACY, ATOL, BODY, MAX_STEPS, METHOD, N_OUT, PHASE, RTOL, SPLITTING_FIELDS, T_SPAN, Kind, Run,
                           build, integration, make_body, make_torques, outputs_field, register, title_fields)
from gyrostat.modelbase import ModelBase, check_body, check_torques, flag, floats, number, shown
from gyrostat.schema import ArrayOf, Choice, Field, SceneError, Table, Vector, all_finite, finite, non_negative, nonzero_quaternion
from gyrostat.solution import Solution
from gyrostat.solve import output_times, solve
from gyrostat.torques import TORQUE


# ------------------------------------------------------------------------------------ models
class Model(ModelBase):
    """The full model: Euler's equations of a gyrostat, J ω̇ + ω × (J ω + k) = Σ M_i(t, ω).

    State ω = (p, q, r) in body axes, in rad/s (with ``attitude=True`` also the quaternion
    (q_w, q_x, q_y, q_z), body → inertial). Outputs: ``angular_momentum_norm`` |G| (kg m^2/s),
    ``kinetic_energy`` T (J) and, with attitude, the z-x-z Euler angles ``psi``, ``theta``,
    ``phi`` (rad).

    Parameters
    ----------
    body : gyrostat.Body
        Principal moments (kg m^2) and rotor momentum k (kg m^2/s).
    torques : sequence of torques, optional
        Perturbation torques (:class:`gyrostat.ConstantTorque`, :class:`gyrostat.LinearDamping`,
        :class:`gyrostat.ResistiveMedium`, :class:`gyrostat.ViscousCavity`,
        :class:`gyrostat.MovingMassDamper`); they add up. Default: none.
    attitude : bool, optional
        Integrate the attitude quaternion as well (state size 7 instead of 3). Only needed when
        an output or a torque depends on the orientation; it costs four more equations.

    Examples
    --------
    >>> import gyrostat
    >>> model = gyrostat.Model(gyrostat.Body([2.0, 1.5, 1.0]), [gyrostat.ConstantTorque(moment=[0.0, 0.0, 0.1])])
    >>> model.state_names, model.output_names
    (('p', 'q', 'r'), ('angular_momentum_norm', 'kinetic_energy', 'nutation_angle'))
    >>> sol = gyrostat.solve(model, [0.0, 0.0, 1.0], (0.0, 10.0))
    >>> round(float(sol["r"][-1]), 6)  # r = 1 + 0.1 t / A3
    2.0
    """

    kind = "full"

    def __init__(self, body: _core.Body, torques: Sequence = (), attitude: bool = False):
        self.body = check_body(body)
        self.torques = check_torques(torques)
        self._core = _core.gyrostat_model(body, self.torques, flag(attitude, "attitude"))

    @property
    def is_torque_free_rigid_body(self) -> bool:
        """No torque and no rotor: the closed form (no integration) answers such a scene.

        Examples
        --------
        >>> import gyrostat
        >>> gyrostat.Model(gyrostat.Body([2.0, 1.5, 1.0])).is_torque_free_rigid_body
        True
        """
        return not self.torques and not any(self.body.rotor)

    def __repr__(self) -> str:
        return f"Model({self.body!r}, torques={list(self.torques)!r}, attitude={self.attitude})"


class TorqueFreeModel(ModelBase):
    """The torque-free rigid body in closed form: Jacobi elliptic functions, no integration.

    State ω = (p, q, r) in rad/s, or with ``attitude=True`` ω and the quaternion (q_w, q_x,
    q_y, q_z) rotating body axes into inertial axes (the exact flow: the rotation about the fixed
    inertial angular momentum from the incomplete elliptic integral of the third kind; see
    docs/integrators.md). Outputs |G| and T (exact to rounding at any t) and, with attitude, the
    z-x-z Euler angles. A gyrostat (rotor k ≠ 0) has a closed form here only for a symmetric body
    with the rotor along its symmetry axis (or a spherical body); any other rotor raises
    ValueError naming the body (use :class:`Model`, which integrates).

    Parameters
    ----------
    body : gyrostat.Body
        Principal moments, in kg m^2.
    attitude : bool, optional
        Give the attitude quaternion as well (default False).

    Examples
    --------
    >>> import gyrostat
    >>> model = gyrostat.TorqueFreeModel(gyrostat.Body([3.0, 2.0, 1.0]))
    >>> sol = gyrostat.solve(model, [0.1, 0.2, 1.0], (0.0, 100.0))
    >>> sol.method
    'closed_form'
    >>> bool(abs(sol["kinetic_energy"][-1] / sol["kinetic_energy"][0] - 1) < 1e-14)
    True
    """

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
    papers' x = a², y = r² form cannot). State (a, r), in rad/s. Outputs: |G|, T, ``x`` = a²,
    ``y`` = r², the fast frequency and ``slow_to_fast`` (must stay ≪ 1).
    :func:`gyrostat.validity.check` reports where the assumptions fail; :func:`gyrostat.solve`
    does so by itself.

    Parameters
    ----------
    body : gyrostat.Body
        A (nearly) symmetric body without rotor; moments in kg m^2.
    torques : sequence of torques, optional
        Perturbation torques, each with its averaged contribution.

    Examples
    --------
    >>> import gyrostat

    A prolate body (C < A) with a viscous nutation damper (the tutorial's satellite), 10 hours:

    >>> body = gyrostat.Body([12.0, 12.0, 4.0])
    >>> averaged = gyrostat.AveragedModel(body, [gyrostat.ViscousCavity(density=970.0, viscosity=2.0, radius=0.25)])
    >>> averaged.state_names
    ('a', 'r')
    >>> sol = gyrostat.solve(averaged, [0.05, 2.0], (0.0, 36000.0))
    >>> bool(sol["r"][-1] < 2.0 and sol["a"][-1] > 0.05)  # towards flat spin about the major axis
    True

    The examples of its attributes use this ``averaged`` model and its solution ``sol``.
    """

    kind = "averaged"

    def __init__(self, body: _core.Body, torques: Sequence = ()):
        self.body = check_body(body)
        self.torques = check_torques(torques)
        self._core = _core.averaged_model(body, self.torques)

    @property
    def A(self) -> float:
        """The equatorial moment of inertia A = A1, in kg m^2.

        Examples
        --------
        >>> averaged.A
        12.0
        """
        return float(self.body.moments[0])

    @property
    def C(self) -> float:
        """The axial moment of inertia C = A3, in kg m^2.

        Examples
        --------
        >>> averaged.C
        4.0
        """
        return float(self.body.moments[2])

    @property
    def exact_reduction(self) -> bool:
        """Whether (a, r) is exact rather than averaged (a symmetric body without rotor under
        torques that commute with rotations about z: the C++ model says): then r = 0 is no limit.

        Examples
        --------
        >>> averaged.exact_reduction
        True
        """
        return self._core.exact_reduction()

    def fast_frequency(self, r: float) -> float:
        """The fast frequency |φ̇| = |(C − A) r / A|, in rad/s.

        Parameters
        ----------
        r : float
            Axial angular velocity, in rad/s.

        Examples
        --------
        >>> averaged.fast_frequency(1.5)
        1.0
        """
        return self._core.fast_frequency(number(r, "r"))

    def slow_rate(self, t: float, y) -> float:
        """max(|ȧ/a|, |ṙ/r|) at (t, a, r), in 1/s: the slow rate the averaging compares with the
        fast frequency.

        Parameters
        ----------
        t : float
            Time, in s.
        y : array_like, shape (2,)
            The slow state (a, r), in rad/s.

        Examples
        --------
        >>> round(averaged.slow_rate(0.0, [0.05, 2.0]), 8)
        0.00010497
        """
        return self._core.slow_rate(number(t, "t"), floats(y, "y"))

    def check(self, solution) -> list:
        return check(self, solution.y, solution.t, warn=False, outputs=solution.outputs)

    def assumptions(self, states, times, outputs=None) -> list:
        """Near symmetry, the distance from the separatrix against the asymmetry, and the fast
        frequency against the slow rates (not needed where the reduction is exact).

        Parameters
        ----------
        states, times, outputs
            As in :meth:`gyrostat.ModelBase.assumptions`: (n, 2) slow states (a, r) in rad/s, their
            times in s, what a solve recorded at them (``slow_to_fast``).

        Examples
        --------
        >>> import numpy as np
        >>> [a.statement for a in averaged.assumptions(np.array([[0.05, 2.0]]), np.array([0.0]))][0]
        'near symmetry |B − A|/A ≪ 1'
        """
        J = np.asarray(self.body.moments, float)
        A, C = J[0], J[2]
        results = []
        asymmetry = abs(J[1] - J[0]) / J[0]
        results.append(Assumption("averaged model", "near symmetry |B − A|/A ≪ 1", asymmetry, SMALL,
                                  asymmetry <= SMALL))
        if asymmetry > 0:
            # The polhode of the near-symmetric body must stay far from the separatrix D = G²/2T = A
            # compared with the asymmetry; |D − A|/A = C r² |C − A| / (A (A a² + C r²)).
            a, r = states[:, 0], states[:, 1]
            distance = C * r**2 * abs(C - A) / (A * (A * a**2 + C * r**2))
            ratio = asymmetry / np.maximum(distance, 1e-300)
            worst = int(np.argmax(ratio))
            results.append(Assumption("averaged model", "asymmetry against the separatrix distance "
                                      "(|B − A|/A)/(|G²/2T − A|/A) ≪ 1", float(ratio[worst]), SMALL,
                                      ratio[worst] <= SMALL, f"worst at t = {times[worst]:.4g}"))
        if self.exact_reduction:
            results.append(Assumption("averaged model", "fast frequency ≫ slow rates", 0.0, SMALL, True,
                                      "not needed: the (a, r) reduction is exact for this symmetric scene"))
        else:
            if outputs is not None and "slow_to_fast" in outputs:
                ratios = np.asarray(outputs["slow_to_fast"], float)
            else:
                ratios = []
                for t, y in zip(times, states):
                    fast = self.fast_frequency(y[1])
                    ratios.append(math.inf if fast == 0 else self.slow_rate(t, y) / fast)
                ratios = np.asarray(ratios, float)
            worst = int(np.argmax(ratios))
            results.append(Assumption("averaged model", "slow rate / fast frequency |(C−A)r/A| ≪ 1", float(ratios[worst]),
                                      SMALL, bool(ratios[worst] <= SMALL),
                                      f"worst at t = {times[worst]:.4g}, r = {states[worst][1]:.3g}"))
        return results
    def __repr__(self) -> str:
        return f"AveragedModel({self.body!r}, torques={list(self.torques)!r})"


class TriaxialAveragedModel(ModelBase):
    """The system averaged over the triaxial Euler–Poinsot motion, in (|G|², p_b, s, φ).

    Any rigid body (no rotor; principal moments all different, or two equal) under small torques
    fixed in the body. The generating motion is the torque-free body's on the level set of |G| and
    T, in Jacobi elliptic functions; with the averaged power per axis P_i = ⟨ω_i M_i⟩ over one
    period (closed forms in K and E for the constant and linear torques, the resistive medium and
    the viscous cavity; the trapezoidal rule in the phase for every other torque, a
    :class:`gyrostat.CustomTorque` included)::

        d|G|²/dt = 2 Σ A_i P_i,   dp_b/dt = 2 Σ (A_i − A_b) P_i,   ds/dt = 0,   dφ/dt = πλ/(2K(k)).

    p_b = |G|² − 2T A_b (A_b the middle moment) is the distance to the separatrix: > 0 while the
    body rotates about the axis of the largest moment, < 0 about the smallest. s = ±1 says which
    way; φ is the fast phase, so that ω(t) is given along the run (outputs ``p``, ``q``, ``r``:
    the free motion at the carried phase; its phase error grows to O(1) by t ~ 1/ε). The initial
    state may be given as ω (the full model's) or as (|G|², p_b, s, φ). The averaging fails next
    to the separatrix (``slow_to_fast`` grows without bound there): a scene with ``model = "auto"``
    switches to the full model before it and back after the crossing. Derivation:
    ``docs/papers/triaxial_averaging.md``.

    Parameters
    ----------
    body : gyrostat.Body
        A rigid body (rotor k = 0), not spherical; moments (or inertia tensor) in kg m^2.
    torques : sequence of torques, optional
        Perturbation torques fixed in the body (none that needs the attitude).

    Examples
    --------
    >>> import gyrostat
    >>> body = gyrostat.Body([3.0, 2.0, 1.0])
    >>> model = gyrostat.TriaxialAveragedModel(body, [gyrostat.LinearDamping(diagonal=[0.001, 0.002, 0.003])])
    >>> model.state_names
    ('G2', 'pb', 'branch', 'phase')
    >>> sol = gyrostat.solve(model, [1.0, 0.2, 0.1], (0.0, 100.0), n_out=3)
    >>> bool(sol["angular_momentum_norm"][-1] < sol["angular_momentum_norm"][0])  # damped
    True
    """

    kind = "averaged_triaxial"

    def __init__(self, body: _core.Body, torques: Sequence = ()):
        self.body = check_body(body)
        self.torques = check_torques(torques)
        self._core = _core.averaged_triaxial_model(body, self.torques)

    def omegas_of(self, states, outputs: dict | None = None) -> np.ndarray:
        """ω of the free motion at each state's phase (in the model's principal axes): the motion
        the torques' own validity numbers are measured over.

        Parameters
        ----------
        states : array_like, shape (n, 4)
            Slow states (|G|², p_b, s, φ).
        outputs : dict, optional
            What a solve recorded at those states: its ``p``, ``q``, ``r`` are these ω, taken as
            they are (no call into the core per state; a row where they are undefined, at rest, is
            lifted).

        Returns
        -------
        numpy.ndarray, shape (n, 3)
            ω in rad/s.

        Examples
        --------
        >>> model.omegas_of([model.initial_state([1.0, 0.2, 0.1])]).round(12)
        array([[1. , 0.2, 0.1]])
        """
        states = np.atleast_2d(np.asarray(states, float))
        if outputs is not None and "p" in outputs and "q" in outputs and "r" in outputs:
            omegas = np.array((outputs["p"], outputs["q"], outputs["r"]), float).T
            if len(omegas) == len(states):
                if np.isnan(omegas).any():
                    for i in np.flatnonzero(np.isnan(omegas).any(axis=1)):
                        omegas[i] = self._lifted(states[i])
                return omegas
        return np.array([self._lifted(y) for y in states])

    def _lifted(self, y) -> np.ndarray:
        """ω of the free motion at the state's phase, in principal axes (the core lifts to the
        body's given frame)."""
        return np.asarray(self._core.full_state(y, 0.0)) @ np.asarray(self.body.principal_axes)

    def check(self, solution) -> list:
        return check(self, solution.y, solution.t, warn=False, outputs=solution.outputs)

    def assumptions(self, states, times, outputs=None) -> list:
        """The slow drift over one period against the distance to the separatrix and the slow
        rates against the fast frequency (``slow_to_fast`` ≪ 1).

        Parameters
        ----------
        states, times, outputs
            As in :meth:`gyrostat.ModelBase.assumptions`: (n, 4) slow states, their times in s, what
            a solve recorded at them (``slow_to_fast``).

        Examples
        --------
        >>> import numpy as np
        >>> y = model.initial_state([1.0, 0.2, 0.1])
        >>> [a.holds for a in model.assumptions(np.array([y]), np.array([0.0]))]
        [True]
        """
        if outputs is not None and "slow_to_fast" in outputs:
            ratios = np.asarray(outputs["slow_to_fast"], float)
        else:
            names = list(self.output_names)
            ratios = np.array([self._core.outputs_at(t, y)[names.index("slow_to_fast")] for t, y in zip(times, states)])
        worst = int(np.argmax(ratios))
        return [Assumption("averaged model", "slow rates / fast frequency ≪ 1 (far from the separatrix)",
                           float(ratios[worst]), SMALL, bool(ratios[worst] <= SMALL),
                           f"worst at t = {times[worst]:.4g}")]

    def __repr__(self) -> str:
        return f"TriaxialAveragedModel(body={self.body!r}, torques={list(self.torques)!r})"


def torque_free(body: _core.Body, omega0, t_eval) -> Solution:
    """ω(t) of a torque-free rigid body in closed form (Jacobi elliptic functions): no
    integration. The same as ``solve(TorqueFreeModel(body), omega0, (t_eval[0], t_eval[-1]),
    t_eval=t_eval)``.

    Parameters
    ----------
    body : gyrostat.Body
        A body without rotor; moments in kg m^2.
    omega0 : array_like, shape (3,)
        ω at ``t_eval[0]`` in body axes, in rad/s.
    t_eval : array_like
        Increasing output times, in s.

    Examples
    --------
    >>> import gyrostat
    >>> sol = gyrostat.torque_free(gyrostat.Body([3.0, 2.0, 1.0]), [0.1, 0.2, 1.0], [0.0, 5.0, 10.0])
    >>> sol.omega.shape
    (3, 3)
    """
    t = output_times(t_eval)
    if np.any(np.diff(t) < 0):
        raise ValueError(f"t_eval = {shown(t_eval)} is unsorted: the times must be increasing")
    return solve(TorqueFreeModel(body), omega0, (t[0], t[-1]), t_eval=t)


# ------------------------------------------------------------------------------------ the averaged system's outputs
def slow_variables(solution: Solution) -> tuple[np.ndarray, np.ndarray]:
    """(a, r) of a solution, in rad/s: the state of the averaged model; a = √(p² + q²) and r of a
    full one.

    Parameters
    ----------
    solution : gyrostat.Solution
        A run of the full or the averaged rigid-body model.

    Examples
    --------
    >>> import gyrostat
    >>> from gyrostat import averaged
    >>> body = gyrostat.Body([12.0, 12.0, 4.0])
    >>> model = gyrostat.AveragedModel(body, [gyrostat.ViscousCavity(density=970.0, viscosity=2.0, radius=0.25)])
    >>> sol = gyrostat.solve(model, [0.05, 2.0], (0.0, 36000.0), n_out=3)
    >>> a, r = averaged.slow_variables(sol)
    >>> bool(a[-1] > a[0] and r[-1] < r[0])  # towards flat spin
    True
    """
    if solution.state_names[:2] == ("a", "r"):
        return solution["a"], solution["r"]
    return np.hypot(solution["p"], solution["q"]), solution["r"]


def r_zero(direction: int = 0, terminal: bool | int = False) -> Event:
    """The event r = 0 (the axial rate changes sign) of the full or the averaged model: there the
    averaging over the symmetric motion stops being valid (the fast frequency vanishes).

    Parameters
    ----------
    direction : {-1, 0, 1}, optional
        Only downward (-1), only upward (1) or both (0) crossings.
    terminal : bool or int, optional
        Stop the run at the first (True) or n-th crossing.

    Examples
    --------
    >>> from gyrostat import averaged
    >>> averaged.r_zero(direction=-1)
    Event(quantity='r', value=0.0, direction=-1, terminal=False, name='r = 0')
    """
    return Event("r", 0.0, direction, terminal, "r = 0")


def averaging_fails(limit: float = SMALL, terminal: bool | int = False) -> Event:
    """The event where the averaged model's slow rate reaches ``limit`` times its fast frequency
    (the output ``slow_to_fast`` rising through ``limit``): past it the averaging is not valid.

    Parameters
    ----------
    limit : float, optional
        The ratio slow rate / fast frequency (dimensionless; default "≪ 1" = 0.1).
    terminal : bool or int, optional
        Stop the run there.

    Examples
    --------
    >>> from gyrostat import averaged
    >>> averaged.averaging_fails(terminal=True).quantity
    'slow_to_fast'
    """
    return Event("slow_to_fast", float(limit), 1, terminal, f"slow/fast reaches {limit:g}")


def xy(solution: Solution) -> tuple[np.ndarray, np.ndarray]:
    """Papers 000/001: x = a², y = r², in rad²/s² (paper 002 swaps the names: its x is r², its y is a²).

    Parameters
    ----------
    solution : gyrostat.Solution
        A run of the full or the averaged rigid-body model.

    Returns
    -------
    (numpy.ndarray, numpy.ndarray)
        x and y at the output times.

    Examples
    --------
    >>> from gyrostat import averaged
    >>> import gyrostat
    >>> sol = gyrostat.solve(gyrostat.Model(gyrostat.Body([2.0, 2.0, 1.0])), [0.3, 0.4, 1.0], (0.0, 1.0), n_out=2)
    >>> x, y = averaged.xy(sol)
    >>> round(float(x[0]), 6), round(float(y[0]), 6)
    (0.25, 1.0)
    """
    a, r = slow_variables(solution)
    return a**2, r**2


@dataclass(frozen=True)
class LotkaVolterra:
    """Paper 002, eq. (6): with X = r², Y = a² (the paper's x, y) and no constant torque,
    dX/dt = X (λ1 + μ1 Y), dY/dt = Y (λ2 + μ2 X), where

        λ1 = −2 D33 / C,  λ2 = −(D11 + D22) / A,  μ1 = 2κ (C − A)/(A C),  μ2 = 2κ C (A − C)/A³,

    D the summed linear-resistance matrix (ε included), κ = ρ P0 / ν summed over cavities.
    A² μ2 + C² μ1 = 0 (the cavity keeps |G|).

    Parameters
    ----------
    lambda1, lambda2 : float
        λ1, λ2, in 1/s.
    mu1, mu2 : float
        μ1, μ2, in s (per rad²/s² of X or Y).

    Examples
    --------
    >>> from gyrostat import averaged
    >>> system = averaged.LotkaVolterra(lambda1=-0.01, lambda2=-0.002, mu1=-0.0005, mu2=5e-05)
    >>> float(system.first_integral(1.0, 1.0))  # λ2 ln 1 + μ2 − λ1 ln 1 − μ1
    0.00055
    """

    lambda1: float
    lambda2: float
    mu1: float
    mu2: float

    def first_integral(self, X, Y):
        """Paper 002 eq. (7) in logarithmic form (the exponential form overflows on the paper's
        own scene): Φ = λ2 ln X + μ2 X − λ1 ln Y − μ1 Y, constant along the averaged solution.

        Parameters
        ----------
        X, Y : array_like
            r² and a², in rad²/s².

        Examples
        --------
        >>> import gyrostat
        >>> from gyrostat import averaged
        >>> body = gyrostat.Body([12.0, 12.0, 4.0])
        >>> torques = [gyrostat.ViscousCavity(density=970.0, viscosity=2.0, radius=0.25),
        ...            gyrostat.LinearDamping(diagonal=[1e-3, 1e-3, 2e-3])]
        >>> model = gyrostat.AveragedModel(body, torques)
        >>> sol = gyrostat.solve(model, [0.05, 2.0], (0.0, 3600.0), rtol=1e-12, atol=1e-14, n_out=3)
        >>> y, x = averaged.xy(sol)  # the paper's X = r² is xy's y
        >>> phi = averaged.lotka_volterra(model).first_integral(x, y)
        >>> bool(abs(phi[-1] - phi[0]) < 1e-8 * abs(phi[0]))
        True
        """
        X, Y = np.asarray(X, float), np.asarray(Y, float)
        return self.lambda2 * np.log(X) + self.mu2 * X - self.lambda1 * np.log(Y) - self.mu1 * Y


def lotka_volterra(model) -> LotkaVolterra:
    """The coefficients of paper 002's system (6) from each torque's averaged contribution, as its
    C++ header gives it (``torque.averaged``): with Y = a², X = r², the system is Lotka–Volterra
    when each contribution has ṙ/r = (λ1 + μ1 a²)/2 and ȧ/a = (λ2 + μ2 r²)/2, which is read off at
    (a, r) = (0, 1), (1, 0) and (1, 1) and checked at a fourth point. A torque without that form
    (a constant axial torque, the damper's r⁴ terms) raises ValueError naming it.

    Parameters
    ----------
    model : gyrostat.AveragedModel or gyrostat.Model
        A symmetric body with its torques.

    Examples
    --------
    >>> import gyrostat
    >>> from gyrostat import averaged
    >>> body = gyrostat.Body([12.0, 12.0, 4.0])
    >>> model = gyrostat.AveragedModel(body, [gyrostat.LinearDamping(diagonal=[0.01, 0.01, 0.02])])
    >>> system = averaged.lotka_volterra(model)
    >>> round(float(system.lambda1), 6), round(float(system.lambda2), 6)  # -2 D33 / C, -(D11 + D22) / A
    (-0.01, -0.001667)
    """
    A, C = float(model.body.moments[0]), float(model.body.moments[2])
    lambda1 = lambda2 = mu1 = mu2 = 0.0
    for torque in model.torques:
        def rates(a, r):
            return np.asarray(torque.averaged(0.0, a, r, A, C), float)
        l1, l2 = 2.0 * rates(0.0, 1.0)[1], 2.0 * rates(1.0, 0.0)[0]
        m1, m2 = 2.0 * rates(1.0, 1.0)[1] - l1, 2.0 * rates(1.0, 1.0)[0] - l2
        a, r = 1.5, 0.75
        expected = np.array([a * (l2 + m2 * r * r), r * (l1 + m1 * a * a)]) / 2.0
        if not np.allclose(rates(a, r), expected, rtol=1e-12, atol=1e-300):
            raise ValueError(f"paper 002's Lotka-Volterra form has no term for {torque!r}: its averaged "
                             "contribution is not (a (λ2 + μ2 r²), r (λ1 + μ1 a²))/2")
        lambda1, lambda2, mu1, mu2 = lambda1 + l1, lambda2 + l2, mu1 + m1, mu2 + m2
    return LotkaVolterra(lambda1=lambda1, lambda2=lambda2, mu1=mu1, mu2=mu2)


def slow_columns(solution) -> np.ndarray:
    """(a, r) of a rigid-body solution, full or averaged: (n, 2) (what the ladder compares)."""
    return np.column_stack(slow_variables(solution))


def initial_assumptions(run: Run, warn: bool) -> list:
    """The assumptions of a run's model at its initial state (the full, averaged and moving-mass
    models: their torques' and their own)."""
    if run.model.kind in ("full", "averaged", "moving_mass"):
        return check(run.model, run.model.initial_state(run.y0), warn=warn)
    return []


# ------------------------------------------------------------------------------------ analysis
def first_reaching(solution: Solution, name: str, level: float) -> float | None:
    """The first time the output ``name`` reaches ``level`` from below (linear interpolation
    between output times), or None."""
    values = np.asarray(solution[name], float)
    above = np.nonzero(values >= level)[0]
    if not len(above) or above[0] == 0:
        return None
    i = int(above[0])
    t0, t1, v0, v1 = solution.t[i - 1], solution.t[i], values[i - 1], values[i]
    return float(t0 + (level - v0) * (t1 - t0) / (v1 - v0))


def separatrix_crossings(solution: Solution) -> list[float]:
    """The times at which a triaxial averaged run (joined with its full-model pieces) crossed the
    separatrix: where p_b changes sign between output times."""
    pb = np.asarray(solution["pb"], float)
    changes = np.nonzero(np.sign(pb[1:]) != np.sign(pb[:-1]))[0]
    return [float(solution.t[i] - pb[i] * (solution.t[i + 1] - solution.t[i]) / (pb[i + 1] - pb[i])) for i in changes]


def analyse(scene, solutions: dict, report: dict, derived: dict) -> None:
    """Paper 002's averaged against the full model, the error against the closed form, and where
    the runs record a nutation angle the first time it reaches 90° (a spin about the axis of least
    inertia turned flat) and the triaxial averaged run's separatrix crossings."""
    flat = {name: first_reaching(sol, "nutation_angle", 0.5 * math.pi) for name, sol in solutions.items()
            if "nutation_angle" in sol.output_names and len(sol)}
    if any(t is not None for t in flat.values()):
        report["nutation_90_degrees_at"] = flat
        if flat.get("full") and flat.get("averaged"):
            report["nutation_90_degrees_relative_difference"] = abs(flat["averaged"] - flat["full"]) / flat["full"]
    averaged = solutions.get("averaged")
    if averaged is not None and "pb" in averaged.state_names and len(averaged):
        report["separatrix_crossings"] = separatrix_crossings(averaged)
    if "full" in solutions and "averaged" in solutions and "pb" in solutions["averaged"].state_names:
        full, avg = solutions["full"], solutions["averaged"]
        n = min(len(full), len(avg))
        report["averaged_vs_full"] = {
            f"max_relative_error_{name}": float(np.max(np.abs(avg[name][:n] - full[name][:n]) / np.abs(full[name][:n])))
            for name in ("angular_momentum_norm", "kinetic_energy")}
        averaged_run = next(run for run in scene.runs if run.name == "averaged")
        report["averaged_vs_full"]["max_relative_error_omega"] = omega_error(averaged_run.model, full, avg, n)
    elif "full" in solutions and "averaged" in solutions:
        a_full, r_full = slow_variables(solutions["full"])
        a_avg, r_avg = slow_variables(solutions["averaged"])
        n = min(len(a_full), len(a_avg))
        report["averaged_vs_full"] = {"max_abs_error_a": float(np.max(np.abs(a_full[:n] - a_avg[:n]))),
                                      "max_abs_error_r": float(np.max(np.abs(r_full[:n] - r_avg[:n])))}
    main = solutions.get("full", solutions.get("closed_form"))
    if scene.doc["outputs"].get("reference") == "closed_form" and main is not None and len(main):
        reference = torque_free(scene.runs[0].model.body, scene.doc["initial"]["omega"], main.t)
        derived["reference"] = reference
        report["max_error_vs_closed_form"] = float(np.max(np.linalg.norm(main.omega - reference.omega, axis=1)))


def carried_omega(model, averaged: Solution) -> np.ndarray:
    """(n, 3) ω of the free motion at the phase a triaxial averaged run carries, in the body's
    given frame (its outputs p, q, r are in principal axes; NaN at rest and on the separatrix)."""
    carried = np.column_stack([averaged["p"], averaged["q"], averaged["r"]])
    return carried @ np.asarray(model.body.principal_axes).T


def omega_error(model, full: Solution, averaged: Solution, n: int) -> float:
    """The largest |ω_averaged − ω_full| / |ω_full| over the first n outputs: ω at the phase the
    triaxial averaged run carries (:func:`carried_omega`) against the full model's. The phase's
    error is the integral of the O(ε) error of the frequency: this grows to O(1) by t ~ 1/ε where
    the slow variables' stays O(ε)."""
    carried = carried_omega(model, averaged)[:n]
    exact = np.asarray(full.omega[:n], float)
    finite = np.all(np.isfinite(carried), axis=1)  # undefined at rest and on the separatrix
    if not finite.any():
        return math.nan
    apart = np.linalg.norm(carried[finite] - exact[finite], axis=1) / np.linalg.norm(exact[finite], axis=1)
    return float(np.max(apart))


# ------------------------------------------------------------------------------------ plots
FULL_STYLE = dict(lw=1.0, ls="--", color="k")  # the full model drawn dashed over the averaged one
AVERAGED_STYLE = dict(lw=3.0, alpha=0.6)


def slow_curves(solutions: dict[str, Solution], title: str, path: Path, kind: str) -> Path:
    """a² and r² (kind "xy") or a and signed r (kind "slow") over time: the averaged model thick
    and solid, the full model's a = √(p²+q²), r dashed over it; when both are there, a lower
    panel shows their difference (where the curves coincide)."""
    both = "full" in solutions and "averaged" in solutions
    fig, axes = plt.subplots(2 if both else 1, 1, figsize=(8, 6.5 if both else 4.8), sharex=True, squeeze=False,
                             gridspec_kw=dict(height_ratios=[2, 1] if both else [1]))
    ax = axes[0, 0]
    labels = ("a²", "r²") if kind == "xy" else ("a", "r")
    curves = {}
    for name in ("averaged", "full"):
        if name not in solutions:
            continue
        a, r = slow_variables(solutions[name])
        curves[name] = (a**2, r**2) if kind == "xy" else (a, r)
        first, second = curves[name]
        # the two curves on top of each other (x = y, as paper 001's claim has it) would read as
        # one: the second is then drawn dashed over the first, and the legend says so
        apart = float(np.max(np.abs(first - second)))
        alike = name == "averaged" and apart <= 0.02 * max(float(np.max(np.abs(first))), 1e-300)  # 2%: one line width
        for label, values, color in zip(labels, curves[name], ("tab:blue", "tab:red")):
            style = dict(AVERAGED_STYLE, color=color) if name == "averaged" else FULL_STYLE
            legend = f"{label} (averaged)" if name == "averaged" else ("full model" if label == labels[0] else None)
            if alike and label == labels[1]:
                style = dict(lw=1.6, ls=(0, (5, 4)), color=color)
                legend += f", dashed: within {apart:.2g} of {labels[0]}"
            ax.plot(solutions[name].t, values, label=legend, **style)
    unit = "[rad²/s²]" if kind == "xy" else "[rad/s]"
    ax.set_ylabel(f"{', '.join(labels)} {unit}")
    ax.set_title(title)
    ax.legend(fontsize=LEGEND_SIZE, loc="best")
    ax.grid(alpha=0.3)
    if both:
        diff = axes[1, 0]
        t_full, t_avg = solutions["full"].t, solutions["averaged"].t
        for label, full, averaged, color in zip(labels, curves["full"], curves["averaged"], ("tab:blue", "tab:red")):
            diff.plot(t_full, full - np.interp(t_full, t_avg, averaged), color=color, lw=1.0, label=f"{label}")
        diff.set_ylabel(f"full − averaged {unit}")
        diff.legend(fontsize=LEGEND_SIZE)
        diff.grid(alpha=0.3)
    axes[-1, 0].set_xlabel("t [s]")
    return figures.finish(fig, path)


def phase(solutions: dict[str, Solution], title: str, path: Path) -> Path:
    """The phase curve a² against r² (paper 002's y against its x): the full model dashed over
    the averaged one, both starting at the black dot."""
    fig, ax = plt.subplots(figsize=(6.5, 5.5))
    for name, style in (("averaged", dict(AVERAGED_STYLE, color="tab:blue")), ("full", FULL_STYLE)):
        if name in solutions:
            a, r = slow_variables(solutions[name])
            ax.plot(r**2, a**2, label=name, **style)
            ax.plot(r[:1] ** 2, a[:1] ** 2, "ko", ms=4)
    ax.set_xlabel("r² [rad²/s²]")
    ax.set_ylabel("a² = p² + q² [rad²/s²]")
    ax.set_title(f"{title}: phase curve")
    ax.legend(fontsize=LEGEND_SIZE)
    ax.grid(alpha=0.3)
    return figures.finish(fig, path)


def nutation(solutions: dict[str, Solution], title: str, path: Path) -> Path:
    """The nutation angle (body z to G, recorded by every rigid-body model) of each run, in
    degrees, with 90° marked: where a spin about the axis of least inertia has turned into a flat
    spin; a run the ladder switched shows where it ran on the full model."""
    fig, ax = plt.subplots(figsize=(8, 3.8))
    for name, style in (("full", FULL_STYLE), ("averaged", dict(AVERAGED_STYLE, color="tab:blue"))):
        sol = solutions.get(name)
        if sol is None or "nutation_angle" not in sol.output_names:
            continue
        ax.plot(sol.t, np.degrees(sol["nutation_angle"]), label=name, **style)
        on_top = np.asarray(sol.rung) > 0 if sol.rung is not None else np.zeros(len(sol), bool)
        if on_top.any():
            ax.plot(sol.t[on_top], np.degrees(sol["nutation_angle"][on_top]), ".", ms=2, color="tab:red",
                    label="switched to the full model")
    ax.axhline(90.0, color="0.5", ls=":", lw=1)
    ax.set_xlabel("t [s]")
    ax.set_ylabel("nutation angle [deg]")
    ax.set_title(f"{title}: nutation angle")
    ax.legend(fontsize=LEGEND_SIZE)
    ax.grid(alpha=0.3)
    return figures.finish(fig, path)


def draw(scene, solutions: dict[str, Solution], derived: dict, folder: Path, own: dict | None = None) -> list[Path]:
    """The plots of a rigid-body scene; ``own``: plot name → f(main solution, title, path) of a
    family that draws these and some of its own (the moving mass)."""
    files = []
    main = solutions.get("full", solutions.get("closed_form"))
    reference = derived.get("reference")
    for plot in scene.plots:
        path = folder / f"{plot}.png"
        if plot in ("xy", "slow"):
            files.append(slow_curves(solutions, scene.title, path, plot))
        elif plot == "phase":
            files.append(phase(solutions, scene.title, path))
        elif plot == "nutation":
            files.append(nutation(solutions, scene.title, path))
        elif plot == "invariants" and main is None and "averaged" in solutions:
            files.append(invariants(solutions["averaged"], scene.title, path))
        elif main is None:
            continue
        elif plot == "omega":
            files.append(omega(main, scene.title, path, reference))
        elif plot == "invariants":
            files.append(invariants(main, scene.title, path))
        elif plot == "euler_angles" and "q_w" in main.state_names:
            files.append(euler_angles(main, scene.title, path))
        elif plot == "error" and reference is not None:
            files.append(error(main, reference, scene.title, path))
        elif own and plot in own:
            files.append(own[plot](main, scene.title, path))
    return files


# ------------------------------------------------------------------------------------ scene kinds
def averaged_rung(doc: dict, body, torques, omega, drawable: tuple[str, ...], attitude: bool = False) -> _ladder.Rung:
    """The averaged (a, r) rung of the ladder of a rigid body or, with the damper's quasi-static
    torque among ``torques``, of the moving-mass family. Blocked when the scene's outputs need
    ω(t) (plots not in ``drawable``, the attitude, a closed-form reference) or when the torques
    have no average (the model's own message)."""
    y0 = np.array([math.hypot(omega[0], omega[1]), omega[2]])
    description = "the system averaged over the symmetric Euler-Poinsot motion, in (a, r)"
    needs = [p for p in doc["outputs"]["plots"] if p not in drawable]
    blocked = ("the scene integrates the attitude: the averaged model has none" if attitude else
               f"the plots {needs} need omega(t): the averaged model gives a and r only" if needs else
               "the closed-form reference is of omega(t)" if doc["outputs"].get("reference") else "")
    model = None
    if not blocked:
        try:
            model = AveragedModel(body, torques)
        except ValueError as error:
            blocked = f"no averaged model: {error}"
    if blocked:
        return _ladder.Rung("averaged", None, y0, description, blocked=blocked, run="averaged")
    exact = model.exact_reduction
    fast = model.fast_frequency(y0[1])
    span = doc["integration"]["t_span"]
    # an exact reduction has no fast motion to resolve: its probe is the longest one, a twentieth of the span
    # an exact reduction has no fast oscillation to sample: its probe may be shorter than 20 periods
    share = _ladder.PROBE_FRACTION * abs(span[1] - span[0]) / _ladder.PROBE_PERIODS
    period = 2.0 * math.pi / fast if fast > 0 else math.inf
    period = min(period, share) if exact else period
    watches = () if exact else (_ladder.Watch("slow_to_fast", SMALL, 0.5 * SMALL,
                                              "slow rate / fast frequency << 1", scales_error=True),)
    return _ladder.Rung("averaged", model, y0, description, compare=slow_columns, fast_period=period,
                        watches=watches, exact=exact,
                        start_checks=lambda: [a for a in check(model, y0, warn=False)
                                              if a.part == "averaged model"],
                        basis="the (a, r) reduction is exact for this symmetric scene: r = 0 is not a limit" if exact
                        else "", run="averaged")


def invariant_columns(solution) -> np.ndarray:
    """(|G|, T) of a rigid-body solution of any model that records them (the full model, the
    averaged ones, a run joined from both), each over its value at the start: (n, 2) (what the
    ladder compares for the triaxial averaged rung)."""
    G, T = solution["angular_momentum_norm"], solution["kinetic_energy"]
    return np.column_stack([G / G[0], T / T[0]])


def nearly_symmetric(body) -> float:
    """|A2 − A1|/A1 of the principal moments: the asymmetry the (a, r) rung assumes small."""
    J = np.asarray(body.moments, float)
    return abs(J[1] - J[0]) / J[0]


TRIAXIAL_PLOTS = ("invariants", "nutation", "ladder")
"""Plots the triaxial averaged rung draws: functions of its slow variables and of ω at its phase."""


def triaxial_rung(doc: dict, body, torques, omega, attitude: bool = False) -> _ladder.Rung:
    """The triaxial averaged rung (|G|², p_b, s, φ) of a rigid body's or, with the damper's
    quasi-static torque among ``torques``, of the moving-mass family's ladder. Blocked for a
    nearly symmetric body (the (a, r) rung averages it), when the scene's outputs need ω(t)
    exactly (plots not in :data:`TRIAXIAL_PLOTS`, the attitude, a closed-form reference) and when
    the torques have no average (the model's own message). It compares |G| and T with the top and
    watches ``slow_to_fast``: the run switches to the top before the separatrix and back after."""
    description = "the system averaged over the triaxial Euler-Poinsot motion, in (|G|^2, p_b, s, phase)"
    needs = [p for p in doc["outputs"]["plots"] if p not in TRIAXIAL_PLOTS]
    asymmetry = nearly_symmetric(body)
    blocked = (f"a nearly symmetric body (|A2 - A1|/A1 = {asymmetry:.3g} <= {SMALL:g}): the (a, r) rung averages it"
               if asymmetry <= SMALL else
               "the scene integrates the attitude: the averaged model has none" if attitude else
               f"the plots {needs} need omega(t): the averaged model carries its phase only to O(1) at t ~ 1/eps"
               if needs else "the closed-form reference is of omega(t)" if doc["outputs"].get("reference") else "")
    model, y0 = None, np.asarray(omega, float)
    if not blocked:
        try:
            model = TriaxialAveragedModel(body, torques)
            y0 = np.asarray(model._core.initial_state(np.asarray(omega, float)))
            model._core.outputs_at(0.0, y0)
            model._core.full_state(y0, 0.0)  # refuses a start on the separatrix, naming it
        except ValueError as error:
            blocked, model = f"no triaxial averaged model: {error}", None
    if blocked:
        return _ladder.Rung("averaged_triaxial", None, y0, description, blocked=blocked, run="averaged")
    names = list(model.output_names)
    period = float(model._core.outputs_at(doc["integration"]["t_span"][0], y0)[names.index("period")])
    watches = (_ladder.Watch("slow_to_fast", SMALL, 0.5 * SMALL,
                             "slow rates / fast frequency << 1 (far from the separatrix)", scales_error=True),)
    return _ladder.Rung("averaged_triaxial", model, y0, description, compare=invariant_columns, fast_period=period,
                        watches=watches, fast_compare=lambda solution: carried_omega(model, solution),
                        start_checks=lambda: [a for a in check(model, y0, warn=False) if a.part == "averaged model"],
                        run="averaged")


class RigidBody(Kind):
    name = "rigid_body"
    doc = ("A rigid body or gyrostat under perturbation torques: the full model, its closed form when nothing "
           "perturbs it, or the system averaged over the symmetric Euler-Poinsot motion in (a, r).")
    plots = ("omega", "invariants", "euler_angles", "error", "xy", "slow", "phase", "nutation", "ladder")
    models = ("auto", "full", "closed_form", "averaged", "averaged_triaxial", "compare")
    default = True
    splits = True

    @property
    def schema(self) -> Table:
        return Table({
            **title_fields(),
            "body": Field(BODY, required=True, doc="the body"),
            "torques": Field(ArrayOf(TORQUE), default=[], doc="perturbation torques; they add up"),
            "initial": Field(Table({
                "omega": Field(Vector(3), required=True, doc="angular velocity in body axes", unit="rad/s",
                               check=all_finite),
                "attitude": Field(Vector(4), doc="attitude quaternion (w, x, y, z), body to inertial; "
                                                 "giving it integrates the attitude", check=nonzero_quaternion),
            }), required=True, doc="the initial state"),
            "integration": Field(Table({
                "model": Field(Choice(*self.models), default="auto",
                               doc="auto: the cheapest model that meets the accuracy (the model ladder); averaged: over the "
                                   "symmetric motion in (a, r); averaged_triaxial: over the triaxial motion in "
                                   "(|G|^2, p_b, s, phase); compare: full and averaged side by side (the triaxial "
                                   "averaged model for a body far from symmetric)"),
                "accuracy": ACCURACY, "phase": PHASE,
                "method": METHOD, "rtol": RTOL, "atol": ATOL, "t_span": T_SPAN, "n_out": N_OUT,
                "max_steps": MAX_STEPS, **SPLITTING_FIELDS,
            }), required=True, doc="the run"),
            "outputs": outputs_field(self.plots, ["omega", "invariants"],
                                reference=Field(Choice("closed_form"), doc="draw and measure against the closed form")),
        })

    def needs_attitude(self, doc: dict) -> bool:
        """The attitude is integrated only when the scene asks for it (an initial quaternion or
        an Euler-angle plot)."""
        return "attitude" in doc["initial"] or "euler_angles" in doc["outputs"]["plots"]

    def choose(self, doc: dict, body, torques) -> tuple[str, str]:
        """The cheapest model that answers the scene, and the reason for the choice."""
        choice = doc["integration"]["model"]
        free = not torques and not np.any(np.asarray(body.rotor))
        attitude = self.needs_attitude(doc)
        if choice == "closed_form":
            if not free:
                raise SceneError("[integration] model = 'closed_form' needs a rigid body (rotor k = 0) with no torque")
            return choice, "asked for by the scene"
        if choice != "auto":
            return choice, "asked for by the scene"
        if free:
            return "closed_form", ("no torque, no rotor: the exact flow (elliptic functions" +
                                   (", attitude included" if attitude else "") + ") needs no integration")
        reasons = [f"{len(torques)} torque(s)"] if torques else []
        if np.any(np.asarray(body.rotor)):
            reasons.append("a rotor (k != 0)")
        if attitude:
            reasons.append("attitude asked for")
        return "full", "full model: " + ", ".join(reasons)

    # plots an averaged model can draw: functions of its slow variables
    slow_plots = ("xy", "slow", "phase", "invariants", "ladder")

    def start(self, doc: dict, attitude: bool) -> np.ndarray:
        """The full model's initial state: ω, followed with ``attitude`` by the initial quaternion
        normalised (the identity when the scene gives none)."""
        initial = doc["initial"]
        if not attitude:
            return np.array(initial["omega"], float)
        q = _core.unit_vector(initial.get("attitude", (1.0, 0.0, 0.0, 0.0)), "[initial] attitude")
        return np.array([*initial["omega"], *q], float)

    def ladder(self, doc):
        body, torques = make_body(doc), make_torques(doc)
        omega = np.asarray(doc["initial"]["omega"], float)
        attitude = self.needs_attitude(doc)
        y0 = self.start(doc, attitude)
        free = not torques and not np.any(np.asarray(body.rotor))
        closed = _ladder.Rung("closed_form", TorqueFreeModel(body, attitude) if free else None, y0,
                              "the exact torque-free flow (elliptic functions)",
                              blocked="" if free else "torques or a rotor perturb the body", run="closed_form")
        full = _ladder.Rung("full", build("torques", Model, body, torques, attitude), y0,
                            "Euler's equations" + (" with the attitude" if attitude else ""),
                            compare=slow_columns)
        triaxial = triaxial_rung(doc, body, torques, omega, attitude)
        if triaxial.model is not None:  # a body far from symmetric: the top is compared in |G| and T
            full.compare = invariant_columns
        return [closed, averaged_rung(doc, body, torques, omega, self.slow_plots, attitude), triaxial, full]

    def runs(self, doc):
        body, torques = make_body(doc), make_torques(doc)
        choice, reason = self.choose(doc, body, torques)
        omega = np.asarray(doc["initial"]["omega"], float)
        t_span = tuple(doc["integration"]["t_span"])
        options = integration(doc, self)
        runs = []
        attitude = self.needs_attitude(doc)
        if choice == "closed_form":
            runs.append(Run("closed_form", build("body", TorqueFreeModel, body, attitude), self.start(doc, attitude),
                            t_span, options))
        if choice in ("full", "compare"):
            model = build("torques", Model, body, torques, attitude)
            runs.append(Run("full", model, self.start(doc, attitude), t_span, options))
        triaxial = choice == "averaged_triaxial" or (choice == "compare" and nearly_symmetric(body) > SMALL)
        if triaxial:
            model = build("torques", TriaxialAveragedModel, body, torques)
            runs.append(Run("averaged", model, np.asarray(model._core.initial_state(omega)), t_span, options))
        elif choice in ("averaged", "compare"):
            model = build("torques", AveragedModel, body, torques)
            runs.append(Run("averaged", model, np.array([math.hypot(omega[0], omega[1]), omega[2]]), t_span, options))
        return runs, choice, reason

    def initial_assumptions(self, run, warn):
        return initial_assumptions(run, warn)

    def assumptions(self, run, solution):
        return check(run.model, solution.y, solution.t, warn=False, outputs=solution.outputs)

    def analyse(self, scene, solutions, report, derived):
        analyse(scene, solutions, report, derived)

    def draw(self, scene, solutions, derived, folder):
        return draw(scene, solutions, derived, folder)

    def why_not_drawn(self, doc, plot):
        if plot == "error" and doc["outputs"].get("reference") is None:
            return ("it needs a reference: [outputs] reference = \"closed_form\" (a rigid body with neither torques "
                    "nor a rotor)")
        return ""


class Averaged(RigidBody):
    name = "averaged"
    doc = ("The system averaged over the symmetric Euler-Poinsot motion in the slow variables (a, r) alone "
           "(a rigid_body scene with model = 'averaged'; the initial state may be given as a and r).")
    plots = ("xy", "slow", "phase")
    default = False
    splits = False

    @property
    def schema(self) -> Table:
        return Table({
            **title_fields(),
            "body": Field(BODY, required=True, doc="the (nearly) symmetric body A1 ~ A2, no rotor"),
            "torques": Field(ArrayOf(TORQUE), default=[], doc="perturbation torques; their averages add up"),
            "initial": Field(Table({
                "omega": Field(Vector(3), doc="angular velocity in body axes (gives a = |(p, q)|, r)", unit="rad/s",
                               check=all_finite),
                "a": Field(float, doc="equatorial amplitude a = sqrt(p^2 + q^2)", unit="rad/s", check=non_negative),
                "r": Field(float, doc="axial rate r (signed)", unit="rad/s", check=finite),
            }), required=True, doc="the initial state: omega, or a and r"),
            "integration": Field(Table({"method": METHOD, "rtol": RTOL, "atol": ATOL, "t_span": T_SPAN,
                                        "n_out": N_OUT}), required=True, doc="the run"),
            "outputs": outputs_field(self.plots, ["xy", "slow"]),
        })

    def runs(self, doc):
        body, torques = make_body(doc), make_torques(doc)
        initial = doc["initial"]
        if "omega" in initial and ("a" in initial or "r" in initial):
            raise SceneError("[initial] give omega, or a and r, not both")
        if "omega" in initial:
            omega = initial["omega"]
            y0 = np.array([math.hypot(omega[0], omega[1]), omega[2]])
        elif "a" in initial and "r" in initial:
            y0 = np.array([initial["a"], initial["r"]])
        else:
            raise SceneError("[initial] needs omega, or both a and r")
        model = build("torques", AveragedModel, body, torques)
        return ([Run("averaged", model, y0, tuple(doc["integration"]["t_span"]), integration(doc, self))], "averaged",
                "asked for by the scene kind")


register(RigidBody(), Averaged())
