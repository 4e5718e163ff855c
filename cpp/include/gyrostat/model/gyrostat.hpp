// The full model of a gyrostat under perturbation torques: Euler's dynamic equations, with the
// attitude quaternion integrated only when asked for.
#pragma once

#include <array>
#include <string>
#include <utility>
#include <cmath>
#include <stdexcept>

#include "gyrostat/attitude.hpp"
#include "gyrostat/body.hpp"
#include "gyrostat/model/system.hpp"
#include "gyrostat/model/torque_free.hpp"
#include "gyrostat/integrate/dop853_tableau.hpp"
#include "gyrostat/torque/set.hpp"

namespace gyrostat::model {

/// Gyrostat (body + constant rotor momentum k) under a set of torques.
///
///   J ω̇ + ω × (J ω + k) = Σ M_i(t, ω),     J = diag(A1, A2, A3),        (Euler)
///   q̇ = ½ q ⊗ (0, ω)                                                    (attitude, optional)
///
/// q is the unit quaternion (w, x, y, z) that rotates body axes into inertial axes:
/// x_inertial = q x_body q*. State layout: y = (p, q, r) or (p, q, r, q_w, q_x, q_y, q_z).
///
/// Outputs recorded along a trajectory:
///   |G| = |J ω + k|  (conserved without torques; the inertial vector G is conserved too),
///   T = ½ ω·J ω      (conserved without torques; dT/dt = ω·ΣM),
///   with the attitude: the z-x-z Euler angles ψ, θ, φ.
template <bool WithAttitude>
class Gyrostat {
public:
    static constexpr int dim = WithAttitude ? 7 : 3;
    using State = Eigen::Matrix<double, dim, 1>;
    using Jacobian = Eigen::Matrix<double, dim, dim>;
    static constexpr auto state_names = rate_state_names<WithAttitude>();

    Gyrostat(Body body, TorqueSet torques) : body_(std::move(body)), torques_(std::move(torques)) {}

    const Body& body() const { return body_; }
    /// The Taylor recursion covers constant and linear torques (a quadratic right-hand side).
    bool supports_taylor() const { return torques_.is_affine(); }
    const TorqueSet& torques() const { return torques_; }

    /// ω̇ = J⁻¹ (ΣM − ω × (Jω + k));  q̇ = ½ q ⊗ (0, ω).
    void rhs(double t, const State& y, State& dy) const {
        const Vec3 omega = y.template head<3>();
        const Vec3 momentum = body_.moments().cwiseProduct(omega) + body_.rotor();
        dy.template head<3>() =
            body_.inverse_moments().cwiseProduct(torques_.total(t, omega, body_.moments()) - omega.cross(momentum));
        if constexpr (WithAttitude) {
            dy.template segment<4>(3) = quaternion_rate(y.template segment<4>(3), omega);
        }
    }

    /// ∂ω̇/∂ω = J⁻¹ (ΣM_ω − skew(ω) J + skew(J ω + k));  ∂q̇/∂ω, ∂q̇/∂q from the product ½ q ⊗ (0, ω).
    void jacobian(double t, const State& y, Jacobian& jac) const {
        jac.setZero();
        const Vec3 omega = y.template head<3>();
        const Vec3 momentum = body_.moments().cwiseProduct(omega) + body_.rotor();
        const Mat3 d_omega = body_.inverse_moments().asDiagonal() *
                             (torques_.jacobian(t, omega, body_.moments()) - skew(omega) * body_.moments().asDiagonal() +
                              skew(momentum));
        jac.template topLeftCorner<3, 3>() = d_omega;
        if constexpr (WithAttitude) quaternion_rate_jacobian(jac, 3, y.template segment<4>(3), omega);
    }

    /// Taylor coefficients y[0..order] of the solution through y(t): y(t + h) = Σ y[n] hⁿ.
    /// The right-hand side is quadratic, so each order is a Cauchy product of earlier ones.
    /// In Euler's form, with (i, j, k) cyclic and P_jk[n] = Σ_{m≤n} ω_j[m] ω_k[n−m]:
    ///   A_i ω_i[n+1] = ((A_j − A_k) P_jk[n] − (ω[n] × k)_i − (D ω[n])_i + M0_i δ_{n0}) / (n + 1)
    ///   (torques affine in ω: M = M0 − D ω),
    ///   q[n+1] = ½ Σ_{m≤n} q[m] ⊗ (0, ω[n−m]) / (n + 1).
    /// `coefficients` has room for order + 1 states; coefficients[0] = y. The order is a
    /// compile-time constant, so the short nested loops unroll completely.
    static constexpr int max_taylor_order = 30;

    template <int order>
    void taylor_coefficients(double /*t*/, const State& y, State* coefficients) const {
        const Vec3& J = body_.moments();
        const Vec3& J_inv = body_.inverse_moments();
        const Vec3& k = body_.rotor();
        const bool damped = torques_.has_damping();
        const Mat3& D = torques_.damping_part();
        const Vec3& M0 = torques_.constant_part();
        const double a1 = J[1] - J[2], a2 = J[2] - J[0], a3 = J[0] - J[1];
        const bool has_rotor = k.squaredNorm() != 0.0;
        double w1[order + 1], w2[order + 1], w3[order + 1];
        w1[0] = y[0], w2[0] = y[1], w3[0] = y[2];
        coefficients[0] = y;
#pragma GCC unroll 32
        for (int n = 0; n < order; ++n) {
            // Products j·k summed in pairs from both ends (terms m and n − m share their
            // factors' loads), with two partial sums to shorten the chain of dependent additions;
            // m runs down so that the newest coefficient (m = 0, r = n) is added last: the step is
            // a chain of dependent operations, and the older terms' sums can then start early.
            double p23 = 0.0, p31 = 0.0, p12 = 0.0, q23 = 0.0, q31 = 0.0, q12 = 0.0;
#pragma GCC unroll 16
            for (int m = (n + 1) / 2 - 1; m >= 0; --m) {
                const int r = n - m;
                p23 += w2[m] * w3[r];
                q23 += w2[r] * w3[m];
                p31 += w3[m] * w1[r];
                q31 += w3[r] * w1[m];
                p12 += w1[m] * w2[r];
                q12 += w1[r] * w2[m];
            }
            if (n % 2 == 0) {  // the middle term m = n/2
                const int m = n / 2;
                p23 += w2[m] * w3[m];
                p31 += w3[m] * w1[m];
                p12 += w1[m] * w2[m];
            }
            p23 += q23;
            p31 += q31;
            p12 += q12;
            // Scalar code: Eigen temporaries here cost store-forwarding stalls in this hot loop.
            const double w_n[3] = {w1[n], w2[n], w3[n]};
            double r1 = a1 * p23, r2 = a2 * p31, r3 = a3 * p12;
            if (has_rotor) {  // − ω[n] × k
                r1 -= w_n[1] * k[2] - w_n[2] * k[1];
                r2 -= w_n[2] * k[0] - w_n[0] * k[2];
                r3 -= w_n[0] * k[1] - w_n[1] * k[0];
            }
            if (damped) {  // − D ω[n]
                r1 -= D(0, 0) * w_n[0] + D(0, 1) * w_n[1] + D(0, 2) * w_n[2];
                r2 -= D(1, 0) * w_n[0] + D(1, 1) * w_n[1] + D(1, 2) * w_n[2];
                r3 -= D(2, 0) * w_n[0] + D(2, 1) * w_n[1] + D(2, 2) * w_n[2];
            }
            if (n == 0) r1 += M0[0], r2 += M0[1], r3 += M0[2];
            const double inv = 1.0 / (n + 1);  // J⁻¹/(n + 1) first: one multiplication after the sum
            w1[n + 1] = r1 * (J_inv[0] * inv);
            w2[n + 1] = r2 * (J_inv[1] * inv);
            w3[n + 1] = r3 * (J_inv[2] * inv);
            State& next = coefficients[n + 1];
            next[0] = w1[n + 1];
            next[1] = w2[n + 1];
            next[2] = w3[n + 1];
            if constexpr (WithAttitude) {
                double s0 = 0.0, s1 = 0.0, s2 = 0.0, s3 = 0.0;
                for (int m = 0; m <= n; ++m) {
                    const State& qm = coefficients[m];
                    const State& wm = coefficients[n - m];
                    const double qw = qm[3], qx = qm[4], qy = qm[5], qz = qm[6];
                    const double p = wm[0], q = wm[1], r = wm[2];
                    s0 += -qx * p - qy * q - qz * r;
                    s1 += qw * p + qy * r - qz * q;
                    s2 += qw * q + qz * p - qx * r;
                    s3 += qw * r + qx * q - qy * p;
                }
                const double half = 0.5 * inv;
                coefficients[n + 1][3] = half * s0;
                coefficients[n + 1][4] = half * s1;
                coefficients[n + 1][5] = half * s2;
                coefficients[n + 1][6] = half * s3;
            }
        }
    }

    // --- Splitting (integrate/splitting.hpp) ---------------------------------------------------
    // f = f_free + f_pert with
    //   f_free = (J⁻¹ (Jω + k) × ω,  ½ q ⊗ (0, ω))   the free gyrostat: its exact flow FreeBodyFlow,
    //   f_pert = (J⁻¹ ΣM(t, ω),      0)              the torques with t frozen (t advances in the
    //                                                 free part), q unchanged.
    // Constant and linear torques alone (M = M0 − D ω) have the exact perturbation flow
    //   ω ← exp(−h J⁻¹D) ω + φ1(−h J⁻¹D) h J⁻¹M0,
    // from the exponential of the 4×4 matrix h [[−J⁻¹D, J⁻¹M0], [0, 0]] (scaling and squaring of
    // its Taylor series, to rounding). Any other torque (cavity, damper, medium) is not exact: the
    // perturbation sub-flow is then one step of the 8th-order Dormand–Prince method (DOP853's
    // 12 stages) over each sub-step, above the order of every composition offered (≤ 6), so the
    // composition keeps its order (measured in tests/test_splitting.py).

    /// Throws std::invalid_argument naming the body when the free gyrostat has no exact flow here.
    void require_splitting() const { FreeBodyFlow::require_closed_form(body_, "splitting"); }

    /// y ← the exact free flow over h (t is not needed: the free gyrostat is autonomous). The
    /// constants in double (Phases::Double): over one sub-step |ω| h ~ 1, so their rounding
    /// costs ~1e-16 per step, as any step's; the double-double constants would cost 6× (12 µs
    /// instead of 2 µs per flow with attitude, measured).
    void free_flow(double h, State& y) const {
        if constexpr (WithAttitude) {
            const FreeBodyFlow flow(body_, y.template head<3>(), y.template segment<4>(3), 0.0, true, Phases::Double);
            y = flow.at(h);
        } else {
            const FreeBodyFlow flow(body_, y, Eigen::Vector4d(1, 0, 0, 0), 0.0, false, Phases::Double);
            y = flow.omega(h);
        }
    }

    /// The perturbation's flow over h, prepared once per sub-step size.
    struct Perturbation {
        double h = 0.0;
        bool exact = true;
        Mat3 propagator = Mat3::Identity();
        Vec3 shift = Vec3::Zero();
    };
    Perturbation perturbation(double h) const {
        Perturbation p;
        p.h = h;
        p.exact = torques_.is_affine();
        if (!p.exact || torques_.empty()) return p;
        Eigen::Matrix4d X = Eigen::Matrix4d::Zero();
        X.template topLeftCorner<3, 3>() = -(body_.inverse_moments().asDiagonal() * torques_.damping_part()) * h;
        X.template topRightCorner<3, 1>() = body_.inverse_moments().cwiseProduct(torques_.constant_part()) * h;
        // exp(X): scale to |X| ≤ 1/2, 20 Taylor terms (remainder < 2⁻²⁰/20! ≈ 4e-25), square back
        const double norm = X.cwiseAbs().rowwise().sum().maxCoeff();
        int squarings = 0;
        if (norm > 0.5) squarings = static_cast<int>(std::ceil(std::log2(norm / 0.5)));
        const Eigen::Matrix4d Y = X / std::ldexp(1.0, squarings);
        Eigen::Matrix4d E = Eigen::Matrix4d::Identity(), term = Eigen::Matrix4d::Identity();
        for (int n = 1; n <= 20; ++n) {
            term = term * Y / n;
            E += term;
        }
        for (int i = 0; i < squarings; ++i) E = E * E;
        p.propagator = E.template topLeftCorner<3, 3>();
        p.shift = E.template topRightCorner<3, 1>();
        return p;
    }
    /// y ← the perturbation's flow over p.h at frozen time t.
    void perturb(const Perturbation& p, double t, State& y) const {
        if (torques_.empty()) return;
        Vec3 omega = y.template head<3>();
        if (p.exact) {
            omega = p.propagator * omega + p.shift;
        } else {
            namespace tab = integrate::dop853_tableau;
            const Vec3& J = body_.moments();
            Vec3 k[tab::n_stages];
            for (int s = 0; s < tab::n_stages; ++s) {
                Vec3 stage = omega;
                for (int j = 0; j < s; ++j)
                    if (tab::a[s][j] != 0.0) stage += (p.h * tab::a[s][j]) * k[j];
                k[s] = body_.inverse_moments().cwiseProduct(torques_.total(t, stage, J));
            }
            Vec3 increment = Vec3::Zero();
            for (int s = 0; s < tab::n_stages; ++s)
                if (tab::b[s] != 0.0) increment += tab::b[s] * k[s];
            omega += p.h * increment;
        }
        y.template head<3>() = omega;
    }

    /// Keeps |q| = 1 to rounding: called by the integrators after each accepted step (only with
    /// the attitude: without it the model has no projection at all).
    template <bool A = WithAttitude, std::enable_if_t<A, int> = 0>
    void project(State& y) const {
        y.template segment<4>(3).normalize();
    }
    template <bool A = WithAttitude, std::enable_if_t<A, int> = 0>
    void check_state(const State& y) const {
        check_quaternion(y.template segment<4>(3), "Gyrostat");
    }
    /// ω alone starts from the identity attitude.
    State initial_state(const Eigen::VectorXd& given) const {
        return complete_rate_state<State>(given, WithAttitude, state_names.data());
    }

    static constexpr std::array<OutputInfo, 2> own_outputs{{{"angular_momentum_norm", true}, {"kinetic_energy", true}}};
    static constexpr auto outputs_info = with_euler_outputs<WithAttitude>(own_outputs);
    void outputs(double /*t*/, const State& y, double* out) const {
        const Vec3 omega = y.template head<3>();
        out[0] = body_.angular_momentum(omega).norm();
        out[1] = body_.kinetic_energy(omega);
        if constexpr (WithAttitude) euler_outputs(y.template segment<4>(3), out + 2);
    }

private:
    Body body_;
    TorqueSet torques_;
};

}  // namespace gyrostat::model
