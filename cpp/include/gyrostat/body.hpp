// A rigid body or gyrostat: principal moments of inertia and a constant rotor momentum.
#pragma once

#include <Eigen/Core>
#include <limits>
#include <string>

namespace gyrostat {

using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;

/// Cross-product matrix: skew(a) b = a × b.
inline Mat3 skew(const Vec3& a) {
    Mat3 s;
    s << 0.0, -a.z(), a.y(), a.z(), 0.0, -a.x(), -a.y(), a.x(), 0.0;
    return s;
}

/// Principal moments J = diag(A1, A2, A3) and the constant gyrostatic momentum k of rotors
/// spinning at constant rate relative to the carrier. The angular momentum is G = J ω + k.
/// A body is a gyrostat with k = 0.
///
/// Every model runs in the principal axes: moments() and rotor() are in them. A body given by its
/// inertia tensor I in some other body frame (the user's) records the rotation between the two,
///   v_user = R v_principal,   I = R diag(A1, A2, A3) Rᵀ,   det R = +1,
/// and the engine gives and returns every state in the user's frame (engine.cpp, model/frame.hpp):
/// ω_user = R ω_p, and the attitude quaternions q_p = q_user ⊗ q_R with R(q_R) = R. A body given
/// by its moments has R = I (principal() is true) and nothing is converted.
class Body {
public:
    /// Throws std::invalid_argument naming the bad value when a moment is not finite, not
    /// positive, or larger than the sum of the other two (no mass distribution has it),
    /// or when a rotor component is not finite.
    Body(const Vec3& moments, const Vec3& rotor = Vec3::Zero());

    /// A body from its inertia tensor in the user's body frame, and the rotor's momentum k in that
    /// frame. I must be finite and symmetric (to 1e-12 relative to its largest entry; it is then
    /// symmetrised) and its eigenvalues, the principal moments, satisfy the constructor's checks
    /// (positive, triangle inequality), which name them. The principal axes are the eigenvectors
    /// of Eigen's SelfAdjointEigenSolver, ordered and signed so that R is the rotation (det +1)
    /// closest to the identity among the axes' 24 proper relabellings: a diagonal I gives R = I
    /// and the moments in the order given.
    static Body from_inertia(const Mat3& inertia, const Vec3& rotor = Vec3::Zero());

    /// The same body (moments and principal axes, bit for bit) with the rotor momentum k given in
    /// the user's frame: a rotor moved without a tensor decomposed again (whose axes and moments
    /// would differ in their last bits: gyrostat.sensitivity's moved models).
    Body with_rotor(const Vec3& rotor) const;

    const Vec3& moments() const { return moments_; }
    const Vec3& inverse_moments() const { return inverse_moments_; }
    /// k in principal axes.
    const Vec3& rotor() const { return rotor_; }

    /// Whether the user's body frame is the principal one (R = I).
    bool principal() const { return principal_; }
    /// R: the principal axes as columns, in the user's body frame (v_user = R v_principal).
    const Mat3& principal_axes() const { return axes_; }
    /// The unit quaternion q_R of R (w ≥ 0).
    const Eigen::Vector4d& principal_quaternion() const { return axes_quaternion_; }
    /// The inertia tensor in the user's frame, R diag(A) Rᵀ.
    Mat3 inertia() const { return axes_ * moments_.asDiagonal() * axes_.transpose(); }

    Vec3 angular_momentum(const Vec3& omega) const { return moments_.cwiseProduct(omega) + rotor_; }
    /// Kinetic energy of the carrier's rotation, T = ω·Jω / 2 (conserved for a free gyrostat).
    double kinetic_energy(const Vec3& omega) const { return 0.5 * omega.dot(moments_.cwiseProduct(omega)); }
    /// The signed distance of ω's free motion to the separatrix, (|G|² − 2T A_mid)/|G|² (G = Jω,
    /// A_mid the middle moment): > 0 a rotation about the axis of the largest moment, < 0 of the
    /// smallest. A change of sign along a run is a separatrix crossing. NaN with a rotor (its
    /// separatrices are others), at |G| = 0 and for a body with two equal moments (no separatrix
    /// between distinct rotations about one of them).
    double separatrix(const Vec3& omega) const {
        const double low = moments_.minCoeff(), high = moments_.maxCoeff(), middle = moments_.sum() - low - high;
        const Vec3 G = moments_.cwiseProduct(omega);
        const double G2 = G.squaredNorm();
        if (rotor_.squaredNorm() != 0.0 || !(G2 > 0.0) || middle == low || middle == high)
            return std::numeric_limits<double>::quiet_NaN();
        return (G2 - omega.dot(G) * middle) / G2;
    }

    std::string describe() const;

private:
    Vec3 moments_;
    Vec3 inverse_moments_;
    Vec3 rotor_;
    bool principal_ = true;
    Mat3 axes_ = Mat3::Identity();
    Eigen::Vector4d axes_quaternion_ = Eigen::Vector4d(1.0, 0.0, 0.0, 0.0);
};

/// The shortest decimal text that reads back as x (as Python's repr): for error messages.
std::string format_value(double x);

/// Throws std::invalid_argument "<what>: component i = value is not finite" when v has a NaN/inf.
void require_finite(const Eigen::Ref<const Eigen::VectorXd>& v, const std::string& what);

}  // namespace gyrostat
