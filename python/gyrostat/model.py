"""A full model: a body, the torques on it, and whether the attitude is integrated."""

from __future__ import annotations

from collections.abc import Sequence

from gyrostat import _core

STATE_NAMES_RATES = ("p", "q", "r")
STATE_NAMES_ATTITUDE = ("p", "q", "r", "q_w", "q_x", "q_y", "q_z")


class Model:
    """Euler's equations of a gyrostat, J ω̇ + ω × (J ω + k) = Σ M_i(t, ω).

    Parameters
    ----------
    body:
        A :class:`gyrostat.Body` (principal moments and rotor momentum k).
    torques:
        Perturbation torques (:class:`gyrostat.ConstantTorque`, :class:`gyrostat.LinearDamping`);
        they add up.
    attitude:
        Integrate the attitude quaternion as well (state size 7 instead of 3). Only needed when
        an output or a torque depends on the orientation; it costs four more equations.
    """

    def __init__(self, body: _core.Body, torques: Sequence = (), attitude: bool = False):
        if not isinstance(body, _core.Body):
            raise TypeError(f"body must be a gyrostat.Body, not {type(body).__name__}")
        self.body = body
        self.torques = tuple(torques)
        for torque in self.torques:
            if not isinstance(torque, (_core.ConstantTorque, _core.LinearDamping)):
                raise TypeError(f"unknown torque type {type(torque).__name__}")
        self.attitude = bool(attitude)
        self._core = _core.FullModel(body, list(self.torques), self.attitude)

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

    def __repr__(self) -> str:
        return f"Model({self.body!r}, torques={list(self.torques)!r}, attitude={self.attitude})"
