"""The rigid body family's models: :class:`Model` (Euler's equations of a gyrostat),
:class:`TorqueFreeModel` (the closed form, and :func:`torque_free`, ω(t) from it) and
:class:`AveragedModel` (the system averaged over the symmetric Euler-Poinsot motion in (a, r),
with its own assumptions)."""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

from gyrostat import _core
from gyrostat.assumptions import SMALL, Assumption, check
from gyrostat.modelbase import ModelBase, check_body, check_torques, flag, floats, number, shown
from gyrostat.solution import Solution
from gyrostat.solve import output_times, solve


class Model(ModelBase):
    """The full model: Euler's equations of a gyrostat, J ω̇ + ω × (J ω + k) = Σ M_i(t, ω).

    State ω = (p, q, r) in body axes, in rad/s (with ``attitude=True`` also the quaternion
    (q_w, q_x, q_y, q_z), body → inertial). Outputs: ``angular_momentum_norm`` |G| (kg m^2/s),
    ``kinetic_energy`` T (J) and, with attitude, the z-x-z Euler angles ``psi``, ``theta``,
    ``phi`` (rad). On an orbit (``orbit=``, or the orbit its orbit torques were given) also the
    attitude relative to the orbit frame (LVLH: x along track, y minus the orbit normal, z
    nadir; docs/orbit_frame.md): the quaternion ``q_orbit_w`` … ``q_orbit_z`` body → orbit
    frame, ``roll``, ``pitch``, ``yaw`` (the 3-2-1 sequence, singular at pitch = ±π/2),
    ``omega_rel_x`` … ``omega_rel_z`` (ω relative to the orbit frame, body axes), and the
    azimuth and inclination of G about the orbit normal.

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
        an output or a torque depends on the orientation; it costs four more equations. Default:
        True with an orbit, else False.
    orbit : gyrostat.Orbit, optional
        The circular orbit the body is on: every orbit torque (:class:`gyrostat.GravityGradient`,
        :class:`gyrostat.DipoleFieldTorque`) given without its own orbit reads this one, and one
        given with its own must have this one (ValueError naming both otherwise). Needs the
        attitude.

    Examples
    --------
    >>> import gyrostat
    >>> model = gyrostat.Model(gyrostat.Body([2.0, 1.5, 1.0]), [gyrostat.ConstantTorque(moment=[0.0, 0.0, 0.1])])
    >>> model.state_names, model.output_names
    (('p', 'q', 'r'), ('angular_momentum_norm', 'kinetic_energy', 'nutation_angle'))
    >>> sol = gyrostat.solve(model, [0.0, 0.0, 1.0], (0.0, 10.0))
    >>> round(float(sol["r"][-1]), 6)  # r = 1 + 0.1 t / A3
    2.0

    On an orbit, at rest in the orbit frame, under the gravity gradient (its axes are the orbit
    frame's: the body stays there):

    >>> orbiting = gyrostat.Model(gyrostat.Body([2.0, 3.0, 1.0]), [gyrostat.GravityGradient()],
    ...                           orbit=gyrostat.Orbit(rate=0.001))
    >>> y0 = orbiting.state_in_orbit_frame()
    >>> sol = gyrostat.solve(orbiting, y0, (0.0, 6000.0))
    >>> bool(abs(sol["pitch"]).max() < 1e-6), y0[:3]  # at rtol 1e-6
    (True, array([ 0.   , -0.001,  0.   ]))
    """

    kind = "full"

    def __init__(self, body: _core.Body, torques: Sequence = (), attitude: bool | None = None,
                 orbit: _core.Orbit | None = None):
        self.body = check_body(body)
        self.torques = check_torques(torques)
        if orbit is not None and not isinstance(orbit, _core.Orbit):
            raise TypeError(f"orbit must be a gyrostat.Orbit, not {type(orbit).__name__}")
        attitude = orbit is not None if attitude is None else flag(attitude, "attitude")
        self._orbit_given = orbit
        self._core = _core.gyrostat_model(body, self.torques, attitude, orbit)

    def _arguments(self) -> dict:
        """What it was built from, as its constructor takes it (gyrostat.sensitivity rebuilds from it):
        the orbit as given (None where its orbit torques bring their own, so that one of theirs moved
        moves the model's with it)."""
        return {"body": self.body, "torques": self.torques, "attitude": self.attitude, "orbit": self._orbit_given}

    @property
    def orbit(self) -> _core.Orbit | None:
        """The model's orbit: the one given, or the one its orbit torques were given (None: none).

        Examples
        --------
        >>> import gyrostat
        >>> gyrostat.Model(gyrostat.Body([2.0, 3.0, 1.0]), [gyrostat.GravityGradient(0.001)], attitude=True).orbit
        Orbit(rate=0.001, normal=[0, 0, 1], phase=0)
        """
        return self._core.orbit

    def state_in_orbit_frame(self, attitude=(1.0, 0.0, 0.0, 0.0), omega=(0.0, 0.0, 0.0), t: float = 0.0) -> np.ndarray:
        """The state (ω, q) at ``t`` of a body given relative to the orbit frame (a model on an orbit).

        Parameters
        ----------
        attitude : array_like, shape (4,), optional
            The quaternion (w, x, y, z) body → orbit frame (default: the body's axes on the
            orbit frame's: x along track, y minus the orbit normal, z nadir).
        omega : array_like, shape (3,), optional
            The angular velocity relative to the orbit frame, in body axes, in rad/s (default:
            at rest in the orbit frame, ω = n Rᵀ N).
        t : float, optional
            The time the state is for, in s (default 0).

        Returns
        -------
        numpy.ndarray, shape (7,)
            ω (rad/s, body axes) and the quaternion body → inertial.

        Examples
        --------
        >>> import gyrostat
        >>> model = gyrostat.Model(gyrostat.Body([2.0, 3.0, 1.0]), orbit=gyrostat.Orbit(rate=0.5))
        >>> model.state_in_orbit_frame().round(12)
        array([ 0. , -0.5,  0. ,  0.5, -0.5, -0.5,  0.5])
        """
        return np.asarray(self._core.from_orbit_frame(number(t, "t"), floats(attitude, "attitude"),
                                                      floats(omega, "omega")))

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
        orbit = f", orbit={self.orbit!r}" if self.orbit is not None else ""
        return f"Model({self.body!r}, torques={list(self.torques)!r}, attitude={self.attitude}{orbit})"


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

    def _arguments(self) -> dict:
        """What it was built from, as its constructor takes it (gyrostat.sensitivity rebuilds from it)."""
        return {"body": self.body, "torques": self.torques}

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

