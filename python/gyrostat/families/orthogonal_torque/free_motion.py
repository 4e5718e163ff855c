"""The torque-free (Zhukovsky-Volterra) gyrostat at the times τ (:func:`torque_free_at_tau`)
and the frame of the paper's Euler angles (15): the attitude with inertial z along G
(:func:`attitude_along_momentum`), angles wrapped to (−π, π] (:func:`wrap`)."""

from __future__ import annotations

import math

import numpy as np

from gyrostat import _core, attitude
from gyrostat.families.orthogonal_torque.models import OrthogonalModel
from gyrostat.families.rigid_body import Model
from gyrostat.solve import solve


def _evaluate_at(model: Model, y0, tau, **options) -> np.ndarray:
    """States of a torque-free model at arbitrary (not monotone) times τ from y0 at τ = 0."""
    tau = np.asarray(tau, float).ravel()
    values, inverse = np.unique(tau, return_inverse=True)
    out = np.empty((values.size, model.dim))
    options = {"rtol": 1e-12, "atol": 1e-13, **options}
    forward, backward = values >= 0, values < 0
    if np.any(forward):
        times = values[forward]
        grid = times if times[0] == 0 else np.concatenate([[0.0], times])
        s = solve(model, y0, (0.0, max(grid[-1], 1e-300)), t_eval=grid, **options).raise_for_status()
        out[forward] = s.y[grid.size - times.size:]
    if np.any(backward):
        times = values[backward][::-1]
        grid = np.concatenate([[0.0], times])
        s = solve(model, y0, (0.0, grid[-1]), t_eval=grid, **options).raise_for_status()
        out[backward] = s.y[1:][::-1]
    return out[inverse]


def torque_free_at_tau(model: OrthogonalModel, omega0, tau, quaternion0=None, **options) -> np.ndarray:
    """The Zhukovsky–Volterra solution through ω0 (and q0 when given) at the times τ: (n, 3) or
    (n, 7). Compare ω(t) with ``torque_free_at_tau(model, ω0, solution.tau)``. The attitude does
    not map through τ (the servo torque turns the inertial G): only ω and the angles of G do.

    Parameters
    ----------
    model : OrthogonalModel
        Whose torque-free gyrostat (:meth:`OrthogonalModel.torque_free`) is evaluated.
    omega0 : array_like, shape (3,)
        The angular velocity where τ = 0, in rad/s.
    tau : array_like
        The times τ, in s (any order).
    quaternion0 : array_like, shape (4,), optional
        The attitude at τ = 0 (then the result has the attitude too).
    **options
        Options of :func:`gyrostat.solve` (default rtol 1e-12, atol 1e-13).

    Examples
    --------
    >>> import gyrostat
    >>> from gyrostat import orthogonal
    >>> model = orthogonal.OrthogonalModel(gyrostat.Body([3.0, 2.0, 1.0]), 0.1)
    >>> sol = gyrostat.solve(model, [0.1, 0.2, 1.0], (0.0, 10.0))
    >>> free = orthogonal.torque_free_at_tau(model, [0.1, 0.2, 1.0], sol["tau"])
    >>> bool(abs(free - sol.omega).max() < 1e-6)  # ω(t) is the free motion at τ(t)
    True
    """
    free = model.torque_free(attitude=quaternion0 is not None)
    y0 = np.asarray(omega0, float) if quaternion0 is None else np.concatenate([omega0, quaternion0])
    return _evaluate_at(free, y0, tau, **options)


# ------------------------------------------------------------------------------ Euler angles
def attitude_along_momentum(G0, psi0: float = 0.0) -> np.ndarray:
    """The quaternion of Rz(ψ0) Rx(θ0) Rz(φ0) with θ0, φ0 the angles of G0 in body axes, so that
    the inertial z3 axis lies along G (the frame of the paper's Euler angles (15)).

    Parameters
    ----------
    G0 : array_like, shape (3,)
        The angular momentum in body axes, in kg m^2/s.
    psi0 : float, optional
        ψ0, in rad.

    Raises
    ------
    ValueError
        For G0 = 0 (no direction) or a component that is not finite; G0 of any size is
        normalised without overflow or underflow.

    Examples
    --------
    >>> from gyrostat import orthogonal
    >>> orthogonal.attitude_along_momentum([0.0, 0.0, 2.0])
    array([1., 0., 0., 0.])
    """
    s = _core.unit_vector(G0, "attitude_along_momentum: G0")  # (G0 of any size: no overflow in |G0|)
    return attitude.quaternion_from_euler([psi0, math.acos(max(-1.0, min(1.0, s[2]))), math.atan2(s[0], s[1])],
                                          "zxz")


def wrap(angle):
    """Angle (differences) to (−π, π].

    Parameters
    ----------
    angle : float or array_like
        In rad.

    Examples
    --------
    >>> from gyrostat import orthogonal
    >>> orthogonal.wrap([0.1, -4.0]).round(6)
    array([0.1     , 2.283185])
    """
    return (np.asarray(angle) + np.pi) % (2 * np.pi) - np.pi

