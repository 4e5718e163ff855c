"""The result of a run: arrays, statistics, status."""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np


@dataclass
class Solution:
    """A trajectory.

    Attributes
    ----------
    t: (n,) output times.
    y: (n, dim) states: ω = (p, q, r) and, with attitude, the quaternion (w, x, y, z) that
       rotates body axes into inertial axes.
    invariants: name → (n,) array: ``angular_momentum_norm`` |G| = |Jω + k| and
       ``kinetic_energy`` T = ½ ω·Jω.
    stats: steps, rhs_evals, rejected_steps, jacobian_evals, nonlinear_conv_failures, last_step.
    status: ``"success"`` or why the run stopped (``max_steps_reached``,
       ``step_size_underflow``, ``non_finite_state``, ``solver_failure``, ``invalid_input``);
       a failed run keeps its partial trajectory.
    message: the reason in words (empty on success).
    method: the integrator (or ``"closed_form"``).
    """

    t: np.ndarray
    y: np.ndarray
    invariants: dict[str, np.ndarray]
    stats: dict[str, float]
    status: str
    message: str
    method: str
    notes: list[str] = field(default_factory=list)

    @property
    def success(self) -> bool:
        return self.status == "success"

    @property
    def omega(self) -> np.ndarray:
        """(n, 3) angular velocity in body axes."""
        return self.y[:, :3]

    @property
    def quaternion(self) -> np.ndarray:
        """(n, 4) attitude quaternion (w, x, y, z); raises if the attitude was not integrated."""
        if self.y.shape[1] < 7:
            raise ValueError("this solution has no attitude: solve a Model(..., attitude=True)")
        return self.y[:, 3:7]

    def euler_angles(self) -> np.ndarray:
        """(n, 3) Euler angles (ψ precession, θ nutation, φ proper rotation), z-x-z convention.

        Output only: they are singular at θ = 0 and π, where ψ and φ are split arbitrarily
        (ψ is set to 0 there). The attitude is integrated as a quaternion.
        """
        w, x, y, z = self.quaternion.T
        # Rotation matrix body → inertial; z-x-z: R = Rz(ψ) Rx(θ) Rz(φ).
        r33 = 1 - 2 * (x * x + y * y)
        r13 = 2 * (x * z + w * y)
        r23 = 2 * (y * z - w * x)
        r31 = 2 * (x * z - w * y)
        r32 = 2 * (y * z + w * x)
        theta = np.arccos(np.clip(r33, -1.0, 1.0))
        psi = np.arctan2(r13, -r23)
        phi = np.arctan2(r31, r32)
        return np.column_stack([psi, theta, phi])

    def raise_for_status(self) -> "Solution":
        """Raises RuntimeError with the message when the run failed; returns self otherwise."""
        if not self.success:
            raise RuntimeError(f"{self.method}: {self.status}: {self.message}")
        return self
