// Attitude kinematics shared by every model that integrates a quaternion, and the conversions
// between attitude representations: unit quaternion, rotation matrix, Euler angles.
//
// Conventions (every function here): a quaternion is q = (w, x, y, z), w the scalar part, and it
// rotates BODY axes into INERTIAL axes: x_inertial = q ⊗ (0, x_body) ⊗ q*. R(q) is the matching
// body → inertial rotation matrix (x_inertial = R x_body; its columns are the body axes in
// inertial coordinates). q and −q are the same rotation; functions returning a quaternion pick w ≥ 0.
//
// Euler angles (intrinsic, i.e. about the rotated axes; SciPy's upper-case sequences):
//   ZXZ: (ψ precession, θ nutation, φ proper rotation), R = Rz(ψ) Rx(θ) Rz(φ),
//        θ ∈ [0, π], ψ, φ ∈ (−π, π]; singular (gimbal lock) at θ = 0 and θ = π.
//   ZYX: (ψ yaw, θ pitch, φ roll), R = Rz(ψ) Ry(θ) Rx(φ),
//        θ ∈ [−π/2, π/2], ψ, φ ∈ (−π, π]; singular at θ = ±π/2.
// At a singular θ only one combination of ψ and φ is defined; the whole of it is put into ψ and
// φ = 0 (SciPy's rule), so that the identity is (0, 0, 0) and a rotation by α about z is (α, 0, 0)
// in both conventions.
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "gyrostat/body.hpp"
#include "gyrostat/numeric/unit_vector.hpp"

namespace gyrostat {

/// q̇ = ½ q ⊗ (0, ω) for the unit quaternion q = (w, x, y, z) that rotates body axes into
/// inertial axes (x_inertial = q x_body q*), ω the angular velocity in body axes.
/// Written out: ẇ = −½(x p + y q + z r), ẋ = ½(w p + y r − z q), ẏ = ½(w q + z p − x r),
/// ż = ½(w r + x q − y p).
template <class Quaternion, class Omega>
Eigen::Vector4d quaternion_rate(const Quaternion& quat, const Omega& omega) {
    const double w = quat[0], x = quat[1], y = quat[2], z = quat[3];
    const double p = omega[0], q = omega[1], r = omega[2];
    return {0.5 * (-x * p - y * q - z * r), 0.5 * (w * p + y * r - z * q), 0.5 * (w * q + z * p - x * r),
            0.5 * (w * r + x * q - y * p)};
}

/// The derivatives of quaternion_rate written into a Jacobian whose rows `row`..`row + 3` are
/// (ẇ, ẋ, ẏ, ż), whose columns 0..2 are (p, q, r) and columns `row`..`row + 3` are (w, x, y, z):
///   ∂q̇/∂ω = ½ [−x −y −z; w −z y; z w −x; −y x w],  ∂q̇/∂q = ½ [0 −p −q −r; p 0 r −q; q −r 0 p; r q −p 0].
template <class Jacobian, class Quaternion, class Omega>
void quaternion_rate_jacobian(Jacobian& jac, int row, const Quaternion& quat, const Omega& omega) {
    const double w = quat[0], x = quat[1], y = quat[2], z = quat[3];
    const double p = omega[0], q = omega[1], r = omega[2];
    jac.template block<4, 3>(row, 0) << -x, -y, -z, w, -z, y, z, w, -x, -y, x, w;
    jac.template block<4, 3>(row, 0) *= 0.5;
    jac.template block<4, 4>(row, row) << 0, -p, -q, -r, p, 0, r, -q, q, -r, 0, p, r, q, -p, 0;
    jac.template block<4, 4>(row, row) *= 0.5;
}

// ---------------------------------------------------------------------------------------------
// Euler conventions by name
// ---------------------------------------------------------------------------------------------

enum class EulerConvention {
    ZXZ,  ///< (ψ, θ, φ) precession, nutation, proper rotation: R = Rz(ψ) Rx(θ) Rz(φ)
    ZYX,  ///< (ψ, θ, φ) yaw, pitch, roll (aerospace): R = Rz(ψ) Ry(θ) Rx(φ)
};

/// "zxz" or "zyx"; throws std::invalid_argument naming the bad value and the valid names.
inline EulerConvention euler_convention_from_name(const std::string& name) {
    if (name == "zxz") return EulerConvention::ZXZ;
    if (name == "zyx") return EulerConvention::ZYX;
    throw std::invalid_argument("unknown Euler convention '" + name + "'; known conventions: zxz, zyx");
}

inline const char* euler_convention_name(EulerConvention c) {
    switch (c) {
        case EulerConvention::ZXZ: return "zxz";
        case EulerConvention::ZYX: return "zyx";
    }
    return "unknown";
}

// ---------------------------------------------------------------------------------------------
// Quaternions
// ---------------------------------------------------------------------------------------------

namespace detail {
inline std::string format_quaternion(const Eigen::Vector4d& q) {
    return "(" + format_value(q[0]) + ", " + format_value(q[1]) + ", " + format_value(q[2]) + ", " +
           format_value(q[3]) + ")";
}
/// An angle in (−2π, 2π] (a sum or difference of two atan2 values) → (−π, π].
inline double wrap_angle(double a) {
    constexpr double pi = 3.14159265358979323846, two_pi = 2.0 * pi;
    if (a > pi) return a - two_pi;
    if (a <= -pi) return a + two_pi;
    return a;
}
}  // namespace detail

/// q / |q|. The norm is taken of q / max|q_i| (no overflow or underflow for any finite q:
/// numeric/unit_vector.hpp). Throws std::invalid_argument naming the value when q is not finite
/// or is zero (no rotation).
inline Eigen::Vector4d unit_quaternion(const Eigen::Vector4d& q) {
    if (!q.allFinite())
        throw std::invalid_argument("the quaternion (w, x, y, z) = " + detail::format_quaternion(q) +
                                    " is not a rotation: it is not finite");
    if (q.cwiseAbs().maxCoeff() == 0.0)
        throw std::invalid_argument("the quaternion (w, x, y, z) = " + detail::format_quaternion(q) +
                                    " is not a rotation: it is zero");
    return scaled_unit(q);
}

/// Hamilton product a ⊗ b = (a_w b_w − a_v·b_v, a_w b_v + b_w a_v + a_v × b_v): the rotation b
/// followed by a (R(a ⊗ b) = R(a) R(b)).
inline Eigen::Vector4d quaternion_product(const Eigen::Vector4d& a, const Eigen::Vector4d& b) {
    return {a[0] * b[0] - a[1] * b[1] - a[2] * b[2] - a[3] * b[3],
            a[0] * b[1] + a[1] * b[0] + a[2] * b[3] - a[3] * b[2],
            a[0] * b[2] - a[1] * b[3] + a[2] * b[0] + a[3] * b[1],
            a[0] * b[3] + a[1] * b[2] - a[2] * b[1] + a[3] * b[0]};
}

/// R(q) for q normalised first: x_inertial = R x_body, with
///   R = | 1 − 2(y² + z²)   2(xy − wz)       2(xz + wy)     |
///       | 2(xy + wz)       1 − 2(x² + z²)   2(yz − wx)     |
///       | 2(xz − wy)       2(yz + wx)       1 − 2(x² + y²) |
/// (from q ⊗ (0, v) ⊗ q* = v + 2w (u × v) + 2 u × (u × v), u = (x, y, z)).
/// Throws std::invalid_argument naming q when it is zero or not finite.
inline Mat3 rotation_matrix(const Eigen::Vector4d& quaternion) {
    const Eigen::Vector4d q = unit_quaternion(quaternion);
    const double w = q[0], x = q[1], y = q[2], z = q[3];
    Mat3 R;
    R << 1.0 - 2.0 * (y * y + z * z), 2.0 * (x * y - w * z), 2.0 * (x * z + w * y),  //
        2.0 * (x * y + w * z), 1.0 - 2.0 * (x * x + z * z), 2.0 * (y * z - w * x),   //
        2.0 * (x * z - w * y), 2.0 * (y * z + w * x), 1.0 - 2.0 * (x * x + y * y);
    return R;
}

/// The unit quaternion (w ≥ 0) of a rotation matrix by Shepperd's method (J. Guidance Control 1,
/// 1978, 223): with t = tr R, the four squares
///   4w² = 1 + t,  4x² = 1 + 2R11 − t,  4y² = 1 + 2R22 − t,  4z² = 1 + 2R33 − t
/// are read off the diagonal; the largest (≥ 1: they add up to 4) is used, and the other three
/// components come from the off-diagonal sums and differences
///   4wx = R32 − R23, 4wy = R13 − R31, 4wz = R21 − R12, 4xy = R12 + R21, 4xz = R13 + R31, 4yz = R23 + R32
/// divided by 4 × (that component): never a division by a small number, so the result is accurate
/// for every rotation. The vector (4 q_k × q) is formed and normalised (no square root needed).
/// Throws std::invalid_argument naming R when it is not finite or not a rotation
/// (|RᵀR − I| > 1e-6 in some entry, or det R < 0).
inline Eigen::Vector4d quaternion_from_matrix(const Mat3& R) {
    const auto describe = [&R] {
        std::string s = "[";
        for (int i = 0; i < 3; ++i) {
            s += i ? ", [" : "[";
            for (int j = 0; j < 3; ++j) s += (j ? ", " : "") + format_value(R(i, j));
            s += "]";
        }
        return s + "]";
    };
    if (!R.allFinite()) throw std::invalid_argument("the rotation matrix R = " + describe() + " is not finite");
    const double orthogonality = (R.transpose() * R - Mat3::Identity()).cwiseAbs().maxCoeff();
    const double det = R(0, 0) * (R(1, 1) * R(2, 2) - R(1, 2) * R(2, 1)) - R(0, 1) * (R(1, 0) * R(2, 2) - R(1, 2) * R(2, 0)) +
                       R(0, 2) * (R(1, 0) * R(2, 1) - R(1, 1) * R(2, 0));
    if (!(orthogonality <= 1e-6) || !(det > 0.0))
        throw std::invalid_argument("R = " + describe() + " is not a rotation matrix: max |RᵀR − I| = " +
                                    format_value(orthogonality) + ", det R = " + format_value(det));
    const double t = R.trace();
    const double squares[4] = {1.0 + t, 1.0 + 2.0 * R(0, 0) - t, 1.0 + 2.0 * R(1, 1) - t, 1.0 + 2.0 * R(2, 2) - t};
    int k = 0;
    for (int i = 1; i < 4; ++i)
        if (squares[i] > squares[k]) k = i;
    const double wx = R(2, 1) - R(1, 2), wy = R(0, 2) - R(2, 0), wz = R(1, 0) - R(0, 1);
    const double xy = R(0, 1) + R(1, 0), xz = R(0, 2) + R(2, 0), yz = R(1, 2) + R(2, 1);
    Eigen::Vector4d q;  // 4 q_k × (w, x, y, z)
    switch (k) {
        case 0: q << squares[0], wx, wy, wz; break;
        case 1: q << wx, squares[1], xy, xz; break;
        case 2: q << wy, xy, squares[2], yz; break;
        default: q << wz, xz, yz, squares[3]; break;
    }
    q /= q.norm();
    return q[0] < 0.0 ? Eigen::Vector4d(-q) : q;
}

// ---------------------------------------------------------------------------------------------
// Euler angles
// ---------------------------------------------------------------------------------------------

/// The unit quaternion (w ≥ 0) of Euler angles (ψ, θ, φ): the product of the elementary
/// quaternions of the three intrinsic rotations, q_a(α) = (cos α/2, sin α/2 e_a),
///   ZXZ: q = q_z(ψ) ⊗ q_x(θ) ⊗ q_z(φ),    ZYX: q = q_z(ψ) ⊗ q_y(θ) ⊗ q_x(φ),
/// normalised and made w ≥ 0. Any finite angles are accepted (outside the ranges of
/// euler_angles they describe the same rotation). Throws std::invalid_argument naming a
/// non-finite angle.
inline Eigen::Vector4d quaternion_from_euler(const Vec3& angles, EulerConvention c) {
    if (!angles.allFinite())
        throw std::invalid_argument("the Euler angles (" + format_value(angles[0]) + ", " + format_value(angles[1]) +
                                    ", " + format_value(angles[2]) + ") are not finite");
    const auto elementary = [](int axis, double angle) {
        Eigen::Vector4d e(std::cos(0.5 * angle), 0.0, 0.0, 0.0);
        e[1 + axis] = std::sin(0.5 * angle);
        return e;
    };
    const int second = c == EulerConvention::ZXZ ? 0 : 1, third = c == EulerConvention::ZXZ ? 2 : 0;
    Eigen::Vector4d q =
        quaternion_product(quaternion_product(elementary(2, angles[0]), elementary(second, angles[1])), elementary(third, angles[2]));
    q /= q.norm();
    return q[0] < 0.0 ? Eigen::Vector4d(-q) : q;
}

/// Below this value the sine of the distance of θ from its singular value (ZXZ: sin θ; ZYX: cos θ)
/// is taken as zero: 8 ulps of 1. That sine is computed from a unit quaternion whose components
/// carry rounding errors of about one ulp, so smaller values cannot be told from 0; and putting
/// the whole free rotation into ψ moves the rotation by at most about that sine (≤ 2e-15 rad).
inline constexpr double euler_singular_tolerance = 8.0 * std::numeric_limits<double>::epsilon();

/// Euler angles (ψ, θ, φ) of the rotation q (normalised first), computed from the quaternion
/// with atan2 of well-conditioned pairs only (no acos/asin of a matrix entry: accurate for
/// every θ, right up to the singular values).
///
/// ZXZ. Multiplying out q_z(ψ) ⊗ q_x(θ) ⊗ q_z(φ), with σ = (ψ + φ)/2, δ = (ψ − φ)/2:
///   w = cos(θ/2) cos σ,  z = cos(θ/2) sin σ,  x = sin(θ/2) cos δ,  y = sin(θ/2) sin δ,
/// so (θ/2 ∈ [0, π/2]):
///   θ = 2 atan2(√(x² + y²), √(w² + z²)),  σ = atan2(z, w),  δ = atan2(y, x),
///   ψ = σ + δ,  φ = σ − δ  (wrapped into (−π, π]; q → −q shifts σ and δ by ±π, ψ and φ by 2π),
///   sin θ = 2 √(x² + y²) √(w² + z²).
/// Singular when sin θ ≤ euler_singular_tolerance: θ ≈ 0 gives R = Rz(ψ + φ), so ψ = 2σ, φ = 0;
/// θ ≈ π gives R = Rz(ψ − φ) Rx(π), so ψ = 2δ, φ = 0.
///
/// ZYX. Multiplying out q_z(ψ) ⊗ q_y(θ) ⊗ q_x(φ) and combining, with c = cos θ/2, s = sin θ/2:
///   w − y = (c − s) cos σ,  z + x = (c − s) sin σ,  w + y = (c + s) cos δ,  z − x = (c + s) sin δ,
/// where c − s = √2 cos(θ/2 + π/4) ≥ 0 and c + s = √2 sin(θ/2 + π/4) ≥ 0 for θ ∈ [−π/2, π/2]. With
/// a = √((w − y)² + (z + x)²) = c − s and b = √((w + y)² + (z − x)²) = c + s:
///   b² − a² = 4cs = 2 sin θ,  2ab = 2(c² − s²) = 2 cos θ,  so θ = atan2((b − a)(b + a), 2ab),
///   σ = atan2(z + x, w − y),  δ = atan2(z − x, w + y),  ψ = σ + δ,  φ = σ − δ  (wrapped).
/// Singular when cos θ = ab ≤ euler_singular_tolerance: θ ≈ π/2 gives Ry(π/2) Rx(φ) =
/// Rz(−φ) Ry(π/2), R = Rz(ψ − φ) Ry(π/2), so ψ = 2δ, φ = 0; θ ≈ −π/2 gives R = Rz(ψ + φ) Ry(−π/2),
/// so ψ = 2σ, φ = 0.
/// Throws std::invalid_argument naming q when it is zero or not finite.
inline Vec3 euler_angles(const Eigen::Vector4d& quaternion, EulerConvention c) {
    using detail::wrap_angle;
    const Eigen::Vector4d q = unit_quaternion(quaternion);
    const double w = q[0], x = q[1], y = q[2], z = q[3];
    double theta = 0.0, sigma = 0.0, delta = 0.0, distance_sine = 0.0;
    bool near_first = false;  // singular θ: 0 (ZXZ) or −π/2 (ZYX), where σ is defined
    if (c == EulerConvention::ZXZ) {
        const double s = std::hypot(x, y), cw = std::hypot(w, z);
        theta = 2.0 * std::atan2(s, cw);
        sigma = std::atan2(z, w);
        delta = std::atan2(y, x);
        distance_sine = 2.0 * s * cw;
        near_first = s < cw;
    } else {
        const double a = std::hypot(w - y, z + x), b = std::hypot(w + y, z - x);
        theta = std::atan2((b - a) * (b + a), 2.0 * a * b);
        sigma = std::atan2(z + x, w - y);
        delta = std::atan2(z - x, w + y);
        distance_sine = a * b;
        near_first = b < a;
    }
    if (distance_sine <= euler_singular_tolerance) return {wrap_angle(2.0 * (near_first ? sigma : delta)), theta, 0.0};
    return {wrap_angle(sigma + delta), theta, wrap_angle(sigma - delta)};
}

}  // namespace gyrostat
