"""The rigid body family's model averaged over the triaxial Euler-Poinsot motion:
:class:`TriaxialAveragedModel` in (|G|², p_b, s, φ), with its own assumptions."""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from gyrostat import _core
from gyrostat.assumptions import SMALL, Assumption, check
from gyrostat.modelbase import ModelBase, check_body, check_torques


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

    def _arguments(self) -> dict:
        """What it was built from, as its constructor takes it (gyrostat.sensitivity rebuilds from it)."""
        return {"body": self.body, "torques": self.torques}

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

