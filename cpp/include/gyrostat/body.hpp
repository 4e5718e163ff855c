// A rigid body or gyrostat: principal moments of inertia and a constant rotor momentum.
#pragma once

#include <Eigen/Core>
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

/// Principal moments J = diag(A1, A2, A3) (body axes are principal axes) and the constant
/// gyrostatic momentum k of rotors spinning at constant rate relative to the carrier.
/// The angular momentum is G = J ω + k. A body is a gyrostat with k = 0.
class Body {
public:
    /// Throws std::invalid_argument naming the bad value when a moment is not finite, not
    /// positive, or larger than the sum of the other two (no mass distribution has it),
    /// or when a rotor component is not finite.
    Body(const Vec3& moments, const Vec3& rotor = Vec3::Zero());

    const Vec3& moments() const { return moments_; }
    const Vec3& inverse_moments() const { return inverse_moments_; }
    const Vec3& rotor() const { return rotor_; }

    Vec3 angular_momentum(const Vec3& omega) const { return moments_.cwiseProduct(omega) + rotor_; }
    /// Kinetic energy of the carrier's rotation, T = ω·Jω / 2 (conserved for a free gyrostat).
    double kinetic_energy(const Vec3& omega) const { return 0.5 * omega.dot(moments_.cwiseProduct(omega)); }

    std::string describe() const;

private:
    Vec3 moments_;
    Vec3 inverse_moments_;
    Vec3 rotor_;
};

/// The shortest decimal text that reads back as x (as Python's repr): for error messages.
std::string format_value(double x);

/// Throws std::invalid_argument "<what>: component i = value is not finite" when v has a NaN/inf.
void require_finite(const Eigen::Ref<const Eigen::VectorXd>& v, const std::string& what);

}  // namespace gyrostat
