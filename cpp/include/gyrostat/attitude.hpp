// Attitude kinematics shared by every model that integrates a quaternion.
#pragma once

#include <Eigen/Core>

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

}  // namespace gyrostat
