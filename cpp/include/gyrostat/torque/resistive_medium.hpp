// Linear resistance of the medium with coefficients that vary (slowly) in time.
#pragma once

#include <Eigen/Core>
#include <array>
#include <stdexcept>
#include <vector>

#include "gyrostat/body.hpp"
#include "gyrostat/euler_poinsot.hpp"
#include "gyrostat/torque/affine.hpp"
#include "gyrostat/torque/parameter.hpp"

namespace gyrostat::torque {

/// M = −D(t) ω with D(t) = Σ_k D_k t^k, a polynomial in time of 3×3 matrices (paper 001:
/// −ε I(τ) ω with τ = εt; paper 002: −ε I ω with a full tensor). Put the small parameter into
/// the coefficients: D_k = ε^{k+1} I_k for I(τ) = Σ I_k τ^k.
///
/// Averaged over the symmetric Euler–Poinsot motion, with D frozen at the current t (its slow
/// variation is the slow time of the averaged system):
///   ȧ = −(D11(t) + D22(t)) a / (2A),   ṙ = −D33(t) r / C.
/// Assumptions: D varies slowly against the fast frequency |(C − A) r / A| (reported by the
/// validity check); the symmetric part of D decides dissipation.
struct ResistiveMedium {
    static constexpr const char* name = "resistive_medium";
    static constexpr const char* python_name = "ResistiveMedium";
    static constexpr const char* description = "a resistive medium whose resistance varies with time";
    static constexpr std::array<Parameter, 1> parameters{{
        {"coefficients", "coefficient", Shape::Matrices, "N m s^(k+1)",
         "D_0, D_1, ...: D(t) = sum D_k t^k (M = -D(t) omega)"},
    }};
    /// M is affine in these (a sensitivity's ∂f/∂p is then a one-sided difference, exact).
    static constexpr std::array<const char*, 1> affine_in{{"coefficients"}};

    std::vector<Mat3> coefficients;  ///< D_0, D_1, … (t^0, t^1, …)

    explicit ResistiveMedium(std::vector<Mat3> c) : coefficients(std::move(c)) {
        if (coefficients.empty()) throw std::invalid_argument("ResistiveMedium: at least one coefficient matrix is needed");
        for (std::size_t k = 0; k < coefficients.size(); ++k)
            require(python_name, parameters[0], coefficients[k], static_cast<int>(k));
    }
    static ResistiveMedium from(const Values& v) { return ResistiveMedium(v.matrices("coefficients")); }
    Values values() const {
        Values v;
        v.set("coefficients", coefficients);
        return v;
    }

    /// D(t) by Horner's rule.
    Mat3 at(double t) const {
        Mat3 d = coefficients.back();
        for (std::size_t k = coefficients.size() - 1; k-- > 0;) d = d * t + coefficients[k];
        return d;
    }
    Vec3 operator()(double t, const Vec3& omega, const Vec3& /*moments*/) const { return -(at(t) * omega); }
    /// D_k = coefficients[k] (torque/affine.hpp); not folded: D depends on t.
    AffineForm affine_form() const { return {Vec3::Zero(), coefficients}; }
    void add_jacobian(double t, const Vec3& /*omega*/, const Vec3& /*moments*/, Mat3& dM_domega) const {
        dM_domega -= at(t);
    }
    Eigen::Vector2d averaged(double t, double a, double r, double A, double C) const {
        const Mat3 d = at(t);
        return {-(d(0, 0) + d(1, 1)) * a / (2.0 * A), -d(2, 2) * r / C};
    }
    /// Its averaged power per axis ⟨ω_i M_i⟩ over the triaxial Euler–Poinsot motion (TorqueSet::
    /// averaged_power; docs/papers/triaxial_averaging.md §2(a)), D frozen at t:
    ///   ⟨ω_i M_i⟩ = −Σ_j D_ij ⟨ω_i ω_j⟩ = −D_ii(t) ⟨ω_i²⟩   (⟨ω_i ω_j⟩ = 0 for i ≠ j: sn·cn, sn·dn and
    ///   cn·dn average to zero over a period).
    Vec3 averaged_power(double t, const EulerPoinsot& motion, const Vec3& /*moments*/) const {
        return -at(t).diagonal().cwiseProduct(motion.mean_square());
    }
    /// Commutes with rotations about body z: every D_k diagonal with equal first two entries.
    bool axisymmetric() const {
        for (const Mat3& d : coefficients)
            if (!is_axisymmetric(d)) return false;
        return true;
    }
};

}  // namespace gyrostat::torque
