"""gyrostat.attitude: quaternions, rotation matrices, Euler angles (z-x-z and z-y-x).

Independent reference: SciPy's ``Rotation`` (scalar-last quaternions; intrinsic sequences
"ZXZ" = Rz Rx Rz and "ZYX" = Rz Ry Rx). Rotations are compared through the angle of the relative
rotation, ``(r1.inv() * r2).magnitude()``, which does not depend on how a singular angle pair is
split. Every tolerance says why it has its size.
"""

import math
import re
import warnings

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from gyrostat import attitude

SCIPY = {"zxz": "ZXZ", "zyx": "ZYX"}
CONVENTIONS = tuple(SCIPY)
# The singular θ of each convention: (lower end, upper end) of its θ range.
SINGULAR = {"zxz": (0.0, math.pi), "zyx": (-math.pi / 2, math.pi / 2)}
EPS = np.finfo(float).eps

# Every conversion here is a handful of flops, sqrt and atan2 on numbers of order 1: the results
# carry rounding errors of a few ulps (measured in the scratch C++ test: ≤ 4e-15 rad for the
# rotations, with 2e5 samples). 1e-12 rad is far above that and far below any real mistake (a wrong
# sign or axis is an O(1) error).
ROTATION_TOL = 1e-12


def xyzw(q):
    return np.asarray(q)[..., [1, 2, 3, 0]]


def random_quaternions(n=200, seed=20240611):
    q = np.random.default_rng(seed).normal(size=(n, 4))
    return q / np.linalg.norm(q, axis=1, keepdims=True)


def wrap(a):
    """Angles into (−π, π] (to compare ψ, φ across SciPy's [−π, π])."""
    return -np.remainder(-np.asarray(a) + math.pi, 2 * math.pi) + math.pi


def rotation_gap(q, r):
    """Angle (rad) of the rotation between our quaternions q and SciPy rotations r."""
    return (Rotation.from_quat(xyzw(q)).inv() * r).magnitude()


def distance_sine(theta, convention):
    """Sine of the distance of θ from its nearest singular value: sin θ (zxz), cos θ (zyx)."""
    return np.abs(np.sin(theta)) if convention == "zxz" else np.abs(np.cos(theta))


# ----------------------------------------------------------------------------------------------
# Against SciPy on random rotations
# ----------------------------------------------------------------------------------------------
@pytest.mark.parametrize("convention", CONVENTIONS)
def test_euler_angles_match_scipy(convention):
    q = random_quaternions()
    ours = attitude.euler_angles(q, convention)
    assert ours.shape == (200, 3)
    ref = Rotation.from_quat(xyzw(q)).as_euler(SCIPY[convention])  # none of these is near a singular θ
    lo, hi = SINGULAR[convention]
    assert np.all((ours[:, 1] >= lo) & (ours[:, 1] <= hi))
    assert np.all((ours[:, [0, 2]] > -math.pi) & (ours[:, [0, 2]] <= math.pi))
    # θ is unique in its range: rounding of two independent computations from the same q, a few
    # ulps of order-1 numbers (see ROTATION_TOL).
    np.testing.assert_allclose(ours[:, 1], ref[:, 1], rtol=0, atol=ROTATION_TOL)
    # ψ and φ are unique modulo 2π away from the singular θ, but their conditioning is
    # 1/sin(distance to the singular θ): the tolerance is scaled by it (the samples stay above 1e-2).
    sine = distance_sine(ours[:, 1], convention)
    assert sine.min() > 1e-2
    for k in (0, 2):
        assert np.all(np.abs(wrap(ours[:, k] - ref[:, k])) * sine <= ROTATION_TOL)
    # The rotation rebuilt from our angles by SciPy is the input rotation.
    assert rotation_gap(q, Rotation.from_euler(SCIPY[convention], ours)).max() < ROTATION_TOL


@pytest.mark.parametrize("convention", CONVENTIONS)
def test_quaternion_from_euler_matches_scipy(convention):
    rng = np.random.default_rng(7)
    angles = rng.uniform(-math.pi, math.pi, size=(200, 3))
    q = attitude.quaternion_from_euler(angles, convention)
    assert q.shape == (200, 4)
    assert np.all(q[:, 0] >= 0)
    np.testing.assert_allclose(np.linalg.norm(q, axis=1), 1.0, rtol=0, atol=4 * EPS)
    assert rotation_gap(q, Rotation.from_euler(SCIPY[convention], angles)).max() < ROTATION_TOL


def test_rotation_matrix_matches_scipy_and_is_a_rotation():
    q = random_quaternions()
    R = attitude.rotation_matrix(q)
    assert R.shape == (200, 3, 3)
    np.testing.assert_allclose(R, Rotation.from_quat(xyzw(q)).as_matrix(), rtol=0, atol=ROTATION_TOL)
    # Orthonormal with det +1 to rounding (entries of order 1, a few ulps each).
    np.testing.assert_allclose(np.einsum("nki,nkj->nij", R, R), np.broadcast_to(np.eye(3), R.shape), rtol=0, atol=1e-14)
    np.testing.assert_allclose(np.linalg.det(R), 1.0, rtol=0, atol=1e-14)
    # Body → inertial: the columns of R are the body axes in inertial axes, R e_i = q e_i q*.
    np.testing.assert_allclose(attitude.rotate(q, [1.0, 0.0, 0.0]), R[:, :, 0], rtol=0, atol=1e-15)
    # Unnormalised input is normalised first.
    np.testing.assert_allclose(attitude.rotation_matrix(3.5 * q[0]), R[0], rtol=0, atol=1e-15)


def test_rotation_sense_body_to_inertial():
    # A body turned by +90° about the inertial z axis: its x axis points along inertial y.
    q = [math.cos(math.pi / 4), 0.0, 0.0, math.sin(math.pi / 4)]
    np.testing.assert_allclose(attitude.rotate(q, [1.0, 0.0, 0.0]), [0.0, 1.0, 0.0], rtol=0, atol=1e-15)
    np.testing.assert_allclose(attitude.rotation_matrix(q) @ [0.0, 1.0, 0.0], [-1.0, 0.0, 0.0], rtol=0, atol=1e-15)


# ----------------------------------------------------------------------------------------------
# Round trips
# ----------------------------------------------------------------------------------------------
def same_up_to_sign(a, b):
    return np.minimum(np.linalg.norm(a - b, axis=-1), np.linalg.norm(a + b, axis=-1))


def test_quaternion_matrix_round_trip():
    q = random_quaternions()
    back = attitude.quaternion_from_matrix(attitude.rotation_matrix(q))
    assert np.all(back[:, 0] >= 0)
    assert same_up_to_sign(back, q).max() < ROTATION_TOL
    # Every branch of Shepperd's method: rotations by π about each axis (w = 0) and one close to it.
    for axis in np.eye(3):
        for angle in (math.pi, math.pi - 1e-9, 1e-9):
            qa = np.concatenate([[math.cos(angle / 2)], math.sin(angle / 2) * axis])
            assert same_up_to_sign(attitude.quaternion_from_matrix(attitude.rotation_matrix(qa)), qa) < ROTATION_TOL


@pytest.mark.parametrize("convention", CONVENTIONS)
def test_quaternion_euler_round_trip(convention):
    q = random_quaternions(seed=3)
    back = attitude.quaternion_from_euler(attitude.euler_angles(q, convention), convention)
    assert same_up_to_sign(back, q).max() < ROTATION_TOL


def test_scipy_rotation_round_trip():
    q = random_quaternions()
    q[:, 0] = np.abs(q[:, 0])
    r = attitude.to_rotation(q)
    assert len(r) == 200
    np.testing.assert_allclose(r.as_matrix(), attitude.rotation_matrix(q), rtol=0, atol=ROTATION_TOL)
    back = attitude.from_rotation(r)
    assert back.shape == (200, 4) and np.all(back[:, 0] >= 0)
    np.testing.assert_allclose(back, q, rtol=0, atol=ROTATION_TOL)
    # A single rotation gives a single quaternion; w ≥ 0 even when SciPy's is w < 0.
    single = attitude.from_rotation(Rotation.from_quat([0.0, 0.0, 0.6, -0.8]))
    np.testing.assert_allclose(single, [0.8, 0.0, 0.0, -0.6], rtol=0, atol=1e-15)
    assert attitude.to_rotation([1.0, 0.0, 0.0, 0.0]).single


def test_multiply_composes_rotations():
    a, b = random_quaternions(seed=11), random_quaternions(seed=12)
    ab = attitude.multiply(a, b)
    np.testing.assert_allclose(attitude.rotation_matrix(ab), attitude.rotation_matrix(a) @ attitude.rotation_matrix(b),
                               rtol=0, atol=ROTATION_TOL)
    assert rotation_gap(ab, Rotation.from_quat(xyzw(a)) * Rotation.from_quat(xyzw(b))).max() < ROTATION_TOL
    # Broadcasting a single quaternion; the identity is neutral.
    np.testing.assert_array_equal(attitude.multiply([1.0, 0.0, 0.0, 0.0], b), b)
    # i ⊗ j = k
    np.testing.assert_array_equal(attitude.multiply([0, 1, 0, 0], [0, 0, 1, 0]), [0, 0, 0, 1])


def test_rotate_matches_scipy():
    q = random_quaternions()
    v = np.random.default_rng(5).normal(size=(200, 3))
    np.testing.assert_allclose(attitude.rotate(q, v), Rotation.from_quat(xyzw(q)).apply(v), rtol=0, atol=ROTATION_TOL)
    assert attitude.rotate(q[0], v).shape == (200, 3)
    assert attitude.rotate(q, v[0]).shape == (200, 3)


# ----------------------------------------------------------------------------------------------
# Singular angles
# ----------------------------------------------------------------------------------------------
@pytest.mark.parametrize("convention", CONVENTIONS)
def test_identity_is_exactly_zero(convention):
    for q in ([1.0, 0.0, 0.0, 0.0], [-1.0, 0.0, 0.0, 0.0], [2.0, 0.0, 0.0, 0.0]):
        angles = attitude.euler_angles(q, convention)
        assert angles.shape == (3,)
        np.testing.assert_array_equal(angles, [0.0, 0.0, 0.0])


@pytest.mark.parametrize("convention", CONVENTIONS)
def test_rotation_about_z_is_all_psi(convention):
    q = [math.cos(0.25), 0.0, 0.0, math.sin(0.25)]
    psi, theta, phi = attitude.euler_angles(q, convention)
    assert psi == pytest.approx(0.5, abs=2 * EPS)  # 2 atan2(sin .25, cos .25): one rounding of 0.25
    assert theta == 0.0 and phi == 0.0
    psi, theta, phi = attitude.euler_angles(attitude.quaternion_from_euler([0.5, 0.0, 0.0], convention), convention)
    assert psi == pytest.approx(0.5, abs=2 * EPS) and theta == 0.0 and phi == 0.0


def from_scipy(r):
    return attitude.from_rotation(r)


def scipy_euler_in_gimbal_lock(rotation, seq):
    """SciPy's angles where it detects gimbal lock (it warns there; the warning is expected)."""
    with warnings.catch_warnings():
        warnings.filterwarnings("ignore", message="Gimbal lock detected", category=UserWarning)
        return rotation.as_euler(seq)


@pytest.mark.parametrize("convention", CONVENTIONS)
@pytest.mark.parametrize("end", [0, 1])
def test_exactly_singular_theta_follows_scipy(convention, end):
    theta = SINGULAR[convention][end]
    rng = np.random.default_rng(17 + end)
    angles = np.column_stack([rng.uniform(-3, 3, 50), np.full(50, theta), rng.uniform(-3, 3, 50)])
    r = Rotation.from_euler(SCIPY[convention], angles)
    ours = attitude.euler_angles(from_scipy(r), convention)
    # φ = 0 exactly, the free rotation in ψ (ψ + φ at the lower end of zxz/θ = −π/2 of zyx,
    # ψ − φ at the other end), as SciPy does.
    np.testing.assert_array_equal(ours[:, 2], 0.0)
    ref = scipy_euler_in_gimbal_lock(r, SCIPY[convention])
    np.testing.assert_array_equal(ref[:, 2], 0.0)
    sign = 1.0 if end == 0 else -1.0
    assert np.all(np.abs(wrap(ours[:, 0] - (angles[:, 0] + sign * angles[:, 2]))) < ROTATION_TOL)
    assert np.all(np.abs(wrap(ours[:, 0] - ref[:, 0])) < ROTATION_TOL)
    np.testing.assert_allclose(ours[:, 1], theta, rtol=0, atol=ROTATION_TOL)
    assert rotation_gap(attitude.quaternion_from_euler(ours, convention), r).max() < ROTATION_TOL


@pytest.mark.parametrize("convention", CONVENTIONS)
@pytest.mark.parametrize("offset", [1e-9, 1e-12, 1e-14, 3e-15, 1e-15, 1e-16, 0.0])
def test_near_singular_theta_round_trips(convention, offset):
    """θ within `offset` of either singular value: the angles rebuild the same rotation.

    Near a singular θ the individual ψ and φ are ill-conditioned (their errors grow like
    1e-16 / sin(distance): 1e-7 rad at a distance of 1e-9), but only along the direction that
    barely moves the rotation; the rotation rebuilt from the angles must still agree with the
    input to rounding, whichever branch (regular or singular, threshold ≈ 1.8e-15) was taken:
    measured ≤ 4e-15 rad in the scratch C++ test, so 1e-12 leaves ample margin while a branch that
    dropped φ too early (an error ~ φ · distance = 1e-9 at offset 1e-9) would fail.
    """
    rng = np.random.default_rng(int(offset * 1e16) % 1000 + 5)
    lo, hi = SINGULAR[convention]
    for theta in (lo + offset, hi - offset):
        angles = np.column_stack([rng.uniform(-3, 3, 100), np.full(100, theta), rng.uniform(-3, 3, 100)])
        r = Rotation.from_euler(SCIPY[convention], angles)
        q = from_scipy(r)
        ours = attitude.euler_angles(q, convention)
        assert np.all((ours[:, 1] >= lo) & (ours[:, 1] <= hi))
        np.testing.assert_allclose(ours[:, 1], theta, rtol=0, atol=ROTATION_TOL)
        assert rotation_gap(attitude.quaternion_from_euler(ours, convention), r).max() < ROTATION_TOL
        assert (Rotation.from_euler(SCIPY[convention], ours).inv() * r).magnitude().max() < ROTATION_TOL
        if offset >= 1e-9:  # the regular branch keeps φ: its error ~ 1e-16 / offset, not O(1)
            assert np.all(np.abs(wrap(ours[:, 2] - angles[:, 2])) < 1e-4)


# ----------------------------------------------------------------------------------------------
# Shapes and errors
# ----------------------------------------------------------------------------------------------
def test_shapes():
    assert attitude.euler_angles(np.zeros((0, 4))).shape == (0, 3)
    assert attitude.quaternion_from_euler([0.1, 0.2, 0.3]).shape == (4,)
    assert attitude.rotation_matrix([1, 0, 0, 0]).shape == (3, 3)
    assert attitude.quaternion_from_matrix(np.eye(3)).shape == (4,)
    assert attitude.quaternion_from_matrix(np.broadcast_to(np.eye(3), (5, 3, 3))).shape == (5, 4)
    np.testing.assert_array_equal(attitude.quaternion_from_matrix(np.eye(3)), [1.0, 0.0, 0.0, 0.0])


@pytest.mark.parametrize("call, shape", [
    (lambda: attitude.euler_angles(np.ones(3)), "(3,)"),
    (lambda: attitude.euler_angles(np.ones((2, 5))), "(2, 5)"),
    (lambda: attitude.euler_angles(np.ones((2, 2, 4))), "(2, 2, 4)"),
    (lambda: attitude.quaternion_from_euler(np.ones(4)), "(4,)"),
    (lambda: attitude.rotation_matrix(np.ones((3, 3))), "(3, 3)"),
    (lambda: attitude.quaternion_from_matrix(np.ones((2, 4))), "(2, 4)"),
    (lambda: attitude.quaternion_from_matrix(np.ones(9)), "(9,)"),
])
def test_bad_shape_raises_naming_it(call, shape):
    with pytest.raises(ValueError, match=re.escape(f"got shape {shape}")):
        call()


@pytest.mark.parametrize("function", [attitude.euler_angles, attitude.rotation_matrix])
def test_zero_quaternion_raises_naming_it(function):
    with pytest.raises(ValueError, match=re.escape("(0, 0, 0, 0)")):
        function([0.0, 0.0, 0.0, 0.0])
    # In a stack, the row is named too.
    with pytest.raises(ValueError, match=re.escape("q[1]: ") + ".*" + re.escape("(0, 0, 0, 0)")):
        function([[1.0, 0.0, 0.0, 0.0], [0.0, 0.0, 0.0, 0.0]])
    with pytest.raises(ValueError, match=re.escape("(nan, 1, 0, 0)")):
        function([math.nan, 1.0, 0.0, 0.0])
    with pytest.raises(ValueError, match=re.escape("(0.0, 0.0, 0.0, 0.0)")):
        attitude.to_rotation([0.0, 0.0, 0.0, 0.0])


@pytest.mark.parametrize("function, argument", [(attitude.euler_angles, [1.0, 0.0, 0.0, 0.0]),
                                                (attitude.quaternion_from_euler, [0.0, 0.0, 0.0])])
def test_unknown_convention_raises_naming_it(function, argument):
    with pytest.raises(ValueError, match="unknown Euler convention 'xyz'; known conventions: zxz, zyx"):
        function(argument, "xyz")
    with pytest.raises(ValueError, match="'ZXZ'"):
        function(argument, "ZXZ")


def test_not_a_rotation_matrix_raises():
    with pytest.raises(ValueError, match="not a rotation matrix.*det R = -1"):
        attitude.quaternion_from_matrix(-np.eye(3))
    with pytest.raises(ValueError, match="not finite"):
        attitude.quaternion_from_euler([0.0, math.inf, 0.0])
