"""Attitude representations: unit quaternions, rotation matrices, Euler angles.

Conventions (every function here, and every quaternion in gyrostat):

* A quaternion is ``q = (w, x, y, z)``, scalar first, of unit norm (inputs are normalised).
  It rotates BODY axes into INERTIAL axes: ``x_inertial = q ⊗ (0, x_body) ⊗ q*``.
  ``rotation_matrix(q)`` is the matching body → inertial matrix R (``x_inertial = R @ x_body``;
  its columns are the body axes in inertial coordinates). ``q`` and ``-q`` are the same
  rotation; functions that return a quaternion pick ``w >= 0``.
* Euler angles are intrinsic (about the rotated axes), returned as ``(psi, theta, phi)``:

  - ``"zxz"``: ψ precession, θ nutation, φ proper rotation, ``R = Rz(ψ) Rx(θ) Rz(φ)``,
    θ ∈ [0, π], ψ, φ ∈ (−π, π]. This is SciPy's ``Rotation.as_euler("ZXZ")`` (upper case:
    intrinsic), not ``"zxz"`` (lower case: extrinsic in SciPy).
  - ``"zyx"``: ψ yaw, θ pitch, φ roll (aerospace), ``R = Rz(ψ) Ry(θ) Rx(φ)``,
    θ ∈ [−π/2, π/2], ψ, φ ∈ (−π, π]; SciPy's ``"ZYX"``.

* Singular angles (gimbal lock): at θ = 0 or π (``"zxz"``) and θ = ±π/2 (``"zyx"``) only one
  combination of ψ and φ is defined. The whole of it is put into ψ and φ = 0 (SciPy's rule, without
  its warning): the identity is ``(0, 0, 0)`` and a rotation by α about z is ``(α, 0, 0)`` in both
  conventions. "Singular" means that the sine of the distance of θ from the singular value is
  below 8 ulps of 1 (≈ 1.8e-15); angles are computed from the quaternion with ``atan2`` of
  well-conditioned pairs, so the result is accurate right up to that threshold (the rotation
  rebuilt from the angles agrees with the input to a few 1e-16 rad everywhere). Near a singular θ
  the individual ψ and φ are ill-conditioned (errors ~ 1e-16 / sin(distance)); the rotation is not.

The conversions run in the C++ core (``gyrostat._core``), vectorised: pass one item or a stack.
"""

from __future__ import annotations

import numpy as np

from gyrostat import _core

__all__ = [
    "euler_angles",
    "quaternion_from_euler",
    "rotation_matrix",
    "quaternion_from_matrix",
    "to_rotation",
    "from_rotation",
    "multiply",
    "rotate",
]

CONVENTIONS = ("zxz", "zyx")


def euler_angles(q, convention: str = "zxz") -> np.ndarray:
    """Euler angles of attitude quaternions.

    Parameters
    ----------
    q : array_like, shape (4,) or (n, 4)
        Quaternions (w, x, y, z), body → inertial; normalised before use.
    convention : {"zxz", "zyx"}
        ``"zxz"``: (ψ precession, θ nutation, φ proper rotation), R = Rz(ψ) Rx(θ) Rz(φ),
        θ ∈ [0, π]. ``"zyx"``: (ψ yaw, θ pitch, φ roll), R = Rz(ψ) Ry(θ) Rx(φ), θ ∈ [−π/2, π/2].

    Returns
    -------
    ndarray, shape (3,) or (n, 3)
        (ψ, θ, φ) in radians, ψ and φ in (−π, π]. At a singular θ the free rotation is in ψ
        and φ = 0 (see the module docstring).

    Raises
    ------
    ValueError
        For a bad shape, an unknown convention, or a zero or non-finite quaternion.

    Examples
    --------
    >>> from gyrostat import attitude
    >>> q = attitude.quaternion_from_euler([0.3, 0.5, 0.1])
    >>> attitude.euler_angles(q).round(6)
    array([0.3, 0.5, 0.1])
    """
    return _core.euler_angles(q, convention)


def quaternion_from_euler(angles, convention: str = "zxz") -> np.ndarray:
    """Attitude quaternions of Euler angles.

    Parameters
    ----------
    angles : array_like, shape (3,) or (n, 3)
        (ψ, θ, φ) in radians; any finite values (outside the ranges of :func:`euler_angles`
        they describe the same rotation).
    convention : {"zxz", "zyx"}
        As in :func:`euler_angles`: q = q_z(ψ) ⊗ q_x(θ) ⊗ q_z(φ) or q_z(ψ) ⊗ q_y(θ) ⊗ q_x(φ).

    Returns
    -------
    ndarray, shape (4,) or (n, 4)
        Unit quaternions (w, x, y, z) with w ≥ 0.

    Raises
    ------
    ValueError
        For a bad shape, an unknown convention, or a non-finite angle.

    Examples
    --------
    >>> from gyrostat import attitude
    >>> attitude.quaternion_from_euler([0.3, 0.5, 0.1]).round(6)
    array([0.949599, 0.246168, 0.024699, 0.192493])
    """
    return _core.quaternion_from_euler(angles, convention)


def rotation_matrix(q) -> np.ndarray:
    """Body → inertial rotation matrices of quaternions.

    Parameters
    ----------
    q : array_like, shape (4,) or (n, 4)
        Quaternions (w, x, y, z); normalised before use.

    Returns
    -------
    ndarray, shape (3, 3) or (n, 3, 3)
        R(q): ``x_inertial = R @ x_body``; the columns are the body axes in inertial axes.

    Raises
    ------
    ValueError
        For a bad shape or a zero or non-finite quaternion.

    Examples
    --------
    >>> import numpy as np
    >>> from gyrostat import attitude
    >>> attitude.rotation_matrix([np.cos(np.pi / 4), 0.0, 0.0, np.sin(np.pi / 4)]).round(6)  # 90° about z
    array([[ 0., -1.,  0.],
           [ 1.,  0.,  0.],
           [ 0.,  0.,  1.]])
    """
    return _core.rotation_matrix(q)


def quaternion_from_matrix(R) -> np.ndarray:
    """Quaternions of body → inertial rotation matrices (Shepperd's method).

    Parameters
    ----------
    R : array_like, shape (3, 3) or (n, 3, 3)
        Rotation matrices (orthonormal to 1e-6, determinant +1).

    Returns
    -------
    ndarray, shape (4,) or (n, 4)
        Unit quaternions (w, x, y, z) with w ≥ 0.

    Raises
    ------
    ValueError
        For a bad shape or a matrix that is not finite or not a rotation.

    Examples
    --------
    >>> import numpy as np
    >>> from gyrostat import attitude
    >>> attitude.quaternion_from_matrix(np.eye(3))
    array([1., 0., 0., 0.])
    """
    return _core.quaternion_from_matrix(R)


def _quaternions(q, name: str = "q") -> np.ndarray:
    """q as a float array of shape (4,) or (n, 4), finite and non-zero (ValueError otherwise)."""
    q = np.asarray(q, dtype=float)
    if q.ndim not in (1, 2) or q.shape[-1] != 4:
        raise ValueError(f"{name} must have shape (4,) or (n, 4), got shape {q.shape}")
    rows = q.reshape(-1, 4)
    bad = ~np.all(np.isfinite(rows), axis=1) | ~np.any(rows != 0, axis=1)
    if np.any(bad):
        i = int(np.argmax(bad))
        where = "" if q.ndim == 1 else f"[{i}]"
        value = ", ".join(repr(float(v)) for v in rows[i])
        raise ValueError(f"{name}{where} = ({value}) is not a rotation: it must be finite and non-zero")
    return q


def to_rotation(q):
    """SciPy ``Rotation`` of attitude quaternions.

    Parameters
    ----------
    q : array_like, shape (4,) or (n, 4)
        Quaternions (w, x, y, z), body → inertial (scalar first; SciPy stores scalar last).

    Returns
    -------
    scipy.spatial.transform.Rotation
        A single rotation for shape (4,), a stack of n for shape (n, 4); ``as_matrix()`` of it is
        :func:`rotation_matrix` of q.

    Raises
    ------
    ValueError
        For a bad shape or a zero or non-finite quaternion.

    Examples
    --------
    >>> from gyrostat import attitude
    >>> rotation = attitude.to_rotation(attitude.quaternion_from_euler([0.3, 0.5, 0.1]))
    >>> rotation.as_euler("ZXZ").round(6)  # SciPy's intrinsic z-x-z
    array([0.3, 0.5, 0.1])
    """
    from scipy.spatial.transform import Rotation

    q = _quaternions(q)
    return Rotation.from_quat(q[..., [1, 2, 3, 0]])


def from_rotation(rotation) -> np.ndarray:
    """Attitude quaternions of a SciPy ``Rotation``.

    Parameters
    ----------
    rotation : scipy.spatial.transform.Rotation
        A single rotation or a stack of them.

    Returns
    -------
    ndarray, shape (4,) or (n, 4)
        Unit quaternions (w, x, y, z), scalar first, with w ≥ 0.

    Examples
    --------
    >>> from scipy.spatial.transform import Rotation
    >>> from gyrostat import attitude
    >>> attitude.from_rotation(Rotation.from_euler("ZXZ", [0.3, 0.5, 0.1])).round(6)
    array([0.949599, 0.246168, 0.024699, 0.192493])
    """
    from scipy.spatial.transform import Rotation

    if not isinstance(rotation, Rotation):
        raise TypeError(f"expected a scipy.spatial.transform.Rotation, got {type(rotation).__name__}")
    xyzw = np.asarray(rotation.as_quat(), dtype=float)
    q = xyzw[..., [3, 0, 1, 2]]
    return np.where(q[..., :1] < 0, -q, q)


def multiply(a, b) -> np.ndarray:
    """Hamilton product a ⊗ b: the rotation b followed by a (R(a ⊗ b) = R(a) R(b)).

    Parameters
    ----------
    a, b : array_like, shape (4,) or (n, 4)
        Quaternions (w, x, y, z); a single one is broadcast against a stack. Not normalised.

    Returns
    -------
    ndarray, shape (4,) or (n, 4)
        (a_w b_w − a_v·b_v, a_w b_v + b_w a_v + a_v × b_v).

    Examples
    --------
    >>> import numpy as np
    >>> from gyrostat import attitude
    >>> quarter = [np.cos(np.pi / 4), 0.0, 0.0, np.sin(np.pi / 4)]  # 90° about z
    >>> attitude.multiply(quarter, quarter).round(6)  # 180° about z
    array([0., 0., 0., 1.])
    """
    a = np.asarray(a, dtype=float)
    b = np.asarray(b, dtype=float)
    for name, x in (("a", a), ("b", b)):
        if x.ndim not in (1, 2) or x.shape[-1] != 4:
            raise ValueError(f"{name} must have shape (4,) or (n, 4), got shape {x.shape}")
    aw, av = a[..., 0], a[..., 1:]
    bw, bv = b[..., 0], b[..., 1:]
    w = aw * bw - np.sum(av * bv, axis=-1)
    v = aw[..., None] * bv + bw[..., None] * av + np.cross(av, bv)
    return np.concatenate([w[..., None], v], axis=-1)


def rotate(q, v) -> np.ndarray:
    """Body-axes vectors in inertial axes: ``R(q) @ v``.

    Parameters
    ----------
    q : array_like, shape (4,) or (n, 4)
        Quaternions (w, x, y, z), body → inertial; normalised before use.
    v : array_like, shape (3,) or (n, 3)
        Vectors in body axes; a single q or v is broadcast against a stack.

    Returns
    -------
    ndarray, shape (3,) or (n, 3)
        The vectors in inertial axes.

    Examples
    --------
    >>> import numpy as np
    >>> from gyrostat import attitude
    >>> attitude.rotate([np.cos(np.pi / 4), 0.0, 0.0, np.sin(np.pi / 4)], [1.0, 0.0, 0.0]).round(6)
    array([0., 1., 0.])
    """
    v = np.asarray(v, dtype=float)
    if v.ndim not in (1, 2) or v.shape[-1] != 3:
        raise ValueError(f"v must have shape (3,) or (n, 3), got shape {v.shape}")
    R = rotation_matrix(q)
    if R.ndim == 3 and v.ndim == 2 and len(R) != len(v):
        raise ValueError(f"q and v must hold as many rows, or one of them a single item: got {len(R)} and {len(v)}")
    return np.einsum("...ij,...j->...i", R, v)
