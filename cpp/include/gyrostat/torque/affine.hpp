// The affine form a torque may declare: M(t, ω) = M0 − Σ_k t^k D_k ω.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "gyrostat/body.hpp"

namespace gyrostat::torque {

/// A torque affine in ω with coefficients polynomial in t,
///   M(t, ω) = M0 − D(t) ω,   D(t) = Σ_k D_k t^k,
/// declares `AffineForm affine_form() const` (constant, linear damping, resistive medium). The
/// models that need this form read it: the nutation-averaged Lagrange top (paper 003's class
/// (2.3), model/lagrange_averaged.hpp). A torque whose form does not depend on t (at most D_0)
/// and may be folded with the others into one M0 − D ω declares `static constexpr bool
/// constant_coefficients = true` besides (torque/set.hpp: TorqueSet folds it; the Taylor
/// recursion and the SIMD lanes take only folded torques).
struct AffineForm {
    Vec3 constant = Vec3::Zero();  ///< M0
    std::vector<Mat3> damping;     ///< D_0, D_1, … (none: no ω term)
};

}  // namespace gyrostat::torque
