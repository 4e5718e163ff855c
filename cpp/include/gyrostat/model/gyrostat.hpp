// The full model of a gyrostat under perturbation torques: Euler's dynamic equations, with the
// attitude quaternion integrated only when asked for.
#pragma once

#include <array>
#include <cmath>

#include "gyrostat/body.hpp"
#include "gyrostat/torque/set.hpp"

namespace gyrostat::model {

/// Cross-product matrix: skew(a) b = a × b.
inline Mat3 skew(const Vec3& a) {
    Mat3 s;
    s << 0.0, -a.z(), a.y(), a.z(), 0.0, -a.x(), -a.y(), a.x(), 0.0;
    return s;
}

/// Gyrostat (body + constant rotor momentum k) under a set of torques.
///
///   J ω̇ + ω × (J ω + k) = Σ M_i(t, ω),     J = diag(A1, A2, A3),        (Euler)
///   q̇ = ½ q ⊗ (0, ω)                                                    (attitude, optional)
///
/// q is the unit quaternion (w, x, y, z) that rotates body axes into inertial axes:
/// x_inertial = q x_body q*. State layout: y = (p, q, r) or (p, q, r, q_w, q_x, q_y, q_z).
///
/// Invariants reported along a trajectory:
///   |G| = |J ω + k|  (conserved without torques; the inertial vector G is conserved too),
///   T = ½ ω·J ω      (conserved without torques; dT/dt = ω·ΣM).
template <bool WithAttitude>
class Gyrostat {
public:
    static constexpr int dim = WithAttitude ? 7 : 3;
    static constexpr bool has_jacobian = true;
    static constexpr bool has_projection = WithAttitude;
    static constexpr int n_invariants = 2;
    using State = Eigen::Matrix<double, dim, 1>;
    using Jacobian = Eigen::Matrix<double, dim, dim>;

    Gyrostat(Body body, TorqueSet torques) : body_(std::move(body)), torques_(std::move(torques)) {}

    const Body& body() const { return body_; }
    const TorqueSet& torques() const { return torques_; }

    /// ω̇ = J⁻¹ (ΣM − ω × (Jω + k));  q̇ = ½ q ⊗ (0, ω).
    void rhs(double t, const State& y, State& dy) const {
        const Vec3 omega = y.template head<3>();
        const Vec3 momentum = body_.moments().cwiseProduct(omega) + body_.rotor();
        dy.template head<3>() =
            body_.inverse_moments().cwiseProduct(torques_.total(t, omega) - omega.cross(momentum));
        if constexpr (WithAttitude) {
            const double w = y[3], x = y[4], yy = y[5], z = y[6];
            const double p = omega.x(), q = omega.y(), r = omega.z();
            dy[3] = 0.5 * (-x * p - yy * q - z * r);
            dy[4] = 0.5 * (w * p + yy * r - z * q);
            dy[5] = 0.5 * (w * q + z * p - x * r);
            dy[6] = 0.5 * (w * r + x * q - yy * p);
        }
    }

    /// ∂ω̇/∂ω = J⁻¹ (ΣM_ω − skew(ω) J + skew(J ω + k));  ∂q̇/∂ω, ∂q̇/∂q from the product ½ q ⊗ (0, ω).
    void jacobian(double t, const State& y, Jacobian& jac) const {
        jac.setZero();
        const Vec3 omega = y.template head<3>();
        const Vec3 momentum = body_.moments().cwiseProduct(omega) + body_.rotor();
        const Mat3 d_omega = body_.inverse_moments().asDiagonal() *
                             (torques_.jacobian(t, omega) - skew(omega) * body_.moments().asDiagonal() +
                              skew(momentum));
        jac.template topLeftCorner<3, 3>() = d_omega;
        if constexpr (WithAttitude) {
            const double w = y[3], x = y[4], yy = y[5], z = y[6];
            const double p = omega.x(), q = omega.y(), r = omega.z();
            // d(q̇)/d(ω): rows (w, x, y, z), columns (p, q, r)
            jac.template block<4, 3>(3, 0) << -x, -yy, -z, w, -z, yy, z, w, -x, -yy, x, w;
            jac.template block<4, 3>(3, 0) *= 0.5;
            // d(q̇)/d(q): ½ right-multiplication matrix of (0, ω)
            jac.template block<4, 4>(3, 3) << 0, -p, -q, -r, p, 0, r, -q, q, -r, 0, p, r, q, -p, 0;
            jac.template block<4, 4>(3, 3) *= 0.5;
        }
    }

    /// Keeps |q| = 1 to rounding: called by the integrators after each accepted step.
    void project(State& y) const {
        if constexpr (WithAttitude) y.template segment<4>(3).normalize();
    }

    static constexpr std::array<const char*, n_invariants> invariant_names{"angular_momentum_norm",
                                                                           "kinetic_energy"};
    void invariants(double /*t*/, const State& y, double* out) const {
        const Vec3 omega = y.template head<3>();
        out[0] = body_.angular_momentum(omega).norm();
        out[1] = body_.kinetic_energy(omega);
    }

private:
    Body body_;
    TorqueSet torques_;
};

}  // namespace gyrostat::model
