// The full model of a gyrostat under perturbation torques: Euler's dynamic equations, with the
// attitude quaternion integrated only when asked for.
#pragma once

#include <array>
#include <string>
#include <utility>
#include <cmath>
#include <stdexcept>
#include <type_traits>

#include "gyrostat/attitude.hpp"
#include "gyrostat/body.hpp"
#include "gyrostat/lanes.hpp"
#include "gyrostat/model/system.hpp"
#include "gyrostat/model/torque_free.hpp"
#include "gyrostat/integrate/substep.hpp"
#include "gyrostat/torque/set.hpp"

namespace gyrostat::model {

/// Euler's equations with torques affine in ω (M = M0 − D ω), in the form the Taylor recursion
/// and the SIMD batches use:
///   ω̇_i = J_i⁻¹ ((A_j − A_k) ω_j ω_k − (ω × k)_i − (D ω)_i + M0_i),   (i, j, k) cyclic.
/// T = double for one body; T = lanes::Lanes for one body per SIMD lane (integrate/batch.hpp).
template <class T>
struct AffineEuler {
    T inverse_moments[3];
    T differences[3];  ///< A2 − A3, A3 − A1, A1 − A2
    T rotor[3];
    T damping[9];      ///< D, row-major
    T constant[3];     ///< M0
    bool has_rotor = false, damped = false;

    /// The coefficients of a body under a torque set (its affine part: the constant and linear
    /// torques folded by TorqueSet).
    static AffineEuler of(const Body& body, const TorqueSet& torques) {
        static_assert(std::is_same_v<T, double>, "gather lanes from AffineEuler<double>");
        AffineEuler e;
        const Vec3& J = body.moments();
        for (int i = 0; i < 3; ++i) {
            e.inverse_moments[i] = body.inverse_moments()[i];
            e.differences[i] = J[(i + 1) % 3] - J[(i + 2) % 3];
            e.rotor[i] = body.rotor()[i];
            e.constant[i] = torques.constant_part()[i];
            for (int j = 0; j < 3; ++j) e.damping[3 * i + j] = torques.damping_part()(i, j);
        }
        e.has_rotor = body.rotor().squaredNorm() != 0.0;
        e.damped = torques.has_damping();
        return e;
    }
};

/// ω̇ of the affine Euler equations above, and with the attitude q̇ = ½ q ⊗ (0, ω):
///   q̇_w = −½(q_x p + q_y q + q_z r),  q̇_x = ½(q_w p + q_y r − q_z q),
///   q̇_y = ½(q_w q + q_z p − q_x r),   q̇_z = ½(q_w r + q_x q − q_y p).
template <bool WithAttitude, class T>
void affine_euler_rhs(const AffineEuler<T>& e, const T* y, T* dy) {
    T r[3] = {e.differences[0] * y[1] * y[2], e.differences[1] * y[2] * y[0], e.differences[2] * y[0] * y[1]};
    if (e.has_rotor) {
        r[0] -= y[1] * e.rotor[2] - y[2] * e.rotor[1];
        r[1] -= y[2] * e.rotor[0] - y[0] * e.rotor[2];
        r[2] -= y[0] * e.rotor[1] - y[1] * e.rotor[0];
    }
    if (e.damped)
        for (int i = 0; i < 3; ++i) r[i] -= e.damping[3 * i] * y[0] + e.damping[3 * i + 1] * y[1] + e.damping[3 * i + 2] * y[2];
    for (int i = 0; i < 3; ++i) dy[i] = (r[i] + e.constant[i]) * e.inverse_moments[i];
    if constexpr (WithAttitude) {
        const T &qw = y[3], &qx = y[4], &qy = y[5], &qz = y[6];
        dy[3] = -0.5 * (qx * y[0] + qy * y[1] + qz * y[2]);
        dy[4] = 0.5 * (qw * y[0] + qy * y[2] - qz * y[1]);
        dy[5] = 0.5 * (qw * y[1] + qz * y[0] - qx * y[2]);
        dy[6] = 0.5 * (qw * y[2] + qx * y[1] - qy * y[0]);
    }
}

/// The affine terms of order n of the Euler recursion below, added to r_i:
///   r_i += −(ω[n] × k)_i − (D ω[n])_i + M0_i δ_{n0}.
/// (Always inlined: as a call, at every order of the unrolled recursion, it costs 14 % of it.)
template <class T>
__attribute__((always_inline)) inline void add_affine_euler_terms(const AffineEuler<T>& e, int n, const T& w1,
                                                                  const T& w2, const T& w3, T& r1, T& r2, T& r3) {
    if (e.has_rotor) {  // − ω[n] × k
        r1 -= w2 * e.rotor[2] - w3 * e.rotor[1];
        r2 -= w3 * e.rotor[0] - w1 * e.rotor[2];
        r3 -= w1 * e.rotor[1] - w2 * e.rotor[0];
    }
    if (e.damped) {  // − D ω[n]
        r1 -= e.damping[0] * w1 + e.damping[1] * w2 + e.damping[2] * w3;
        r2 -= e.damping[3] * w1 + e.damping[4] * w2 + e.damping[5] * w3;
        r3 -= e.damping[6] * w1 + e.damping[7] * w2 + e.damping[8] * w3;
    }
    if (n == 0) r1 += e.constant[0], r2 += e.constant[1], r3 += e.constant[2];
}

/// One order of the Euler recursion below for T = double, ω[n+1] from ω[0..n]:
///   ω_i[n+1] = ((A_j − A_k) P_jk[n] + a_i) · (J_i⁻¹/(n + 1)),
/// a_i the affine terms (affine_euler_terms, added when `with_affine`), with the six
/// multiplications of a pair (m, r = n − m) of the Cauchy products in three
/// 2-wide vectors (one SSE2 register each; scalar code issues one product per instruction): with
/// X = (ω2, ω3), Y = (ω3, ω1), Z = (ω1, ω2), S = (ω2, ω1) per coefficient,
///   X[m]·Y[r] = (ω2[m] ω3[r], ω3[m] ω1[r])   terms of (P23, P31),
///   X[r]·Y[m] = (ω2[r] ω3[m], ω3[r] ω1[m])   the partner terms of (P23, P31),
///   Z[m]·S[r] = (ω1[m] ω2[r], ω2[m] ω1[r])   both terms of P12 (its lanes summed at the end),
/// and ω1, ω2 of the new order scaled as one vector too (scalar scaling there undoes most of the
/// gain). 6 … 11 % faster than the scalar loop at orders 20 … 23, slower below (in the
/// integrator's chain of steps, ns per recursion: order 13: 120 against 103; 18: 164 against 158;
/// 20: 181 against 192; 23: 217 against 245), so euler_taylor_recursion uses it from order 20 on.
template <int order>
struct PackedEulerOrders {
    typedef double Pair __attribute__((vector_size(16)));
    Pair X[order + 1], Y[order + 1], Z[order + 1], S[order + 1];

    void push(int n, double a, double b, double c) {
        X[n] = Pair{b, c}, Y[n] = Pair{c, a}, Z[n] = Pair{a, b}, S[n] = Pair{b, a};
    }
    void next(int n, const AffineEuler<double>& e, bool with_affine, const double (&affine)[3], double& a, double& b,
              double& c) const {
        Pair p = {0.0, 0.0}, q = p, z = p;
#pragma GCC unroll 16
        for (int m = (n + 1) / 2 - 1; m >= 0; --m) {
            const int r = n - m;
            p += X[m] * Y[r];
            q += X[r] * Y[m];
            z += Z[m] * S[r];
        }
        double middle12 = 0.0;
        if (n % 2 == 0) {  // the middle term m = n/2 (once for P12)
            const int m = n / 2;
            p += X[m] * Y[m];
            middle12 = Z[m][0] * Z[m][1];
        }
        const double inv = 1.0 / (n + 1);
        Pair ab = Pair{e.differences[0], e.differences[1]} * (p + q);
        double r3 = e.differences[2] * (z[0] + (z[1] + middle12));
        if (with_affine) ab += Pair{affine[0], affine[1]}, r3 += affine[2];
        ab *= Pair{e.inverse_moments[0], e.inverse_moments[1]} * inv;
        a = ab[0], b = ab[1], c = r3 * (e.inverse_moments[2] * inv);
    }
};

/// Order n + 1 of the attitude in the Euler recursion below:
///   q[n+1] = ½ Σ_{m≤n} q[m] ⊗ (0, ω[n−m]) / (n + 1).
template <class T, class Coefficient>
void attitude_order(int n, Coefficient& c) {
    T s0 = lanes::splat<T>(0.0), s1 = s0, s2 = s0, s3 = s0;
    for (int m = 0; m <= n; ++m) {
        const T &qw = c(m, 3), &qx = c(m, 4), &qy = c(m, 5), &qz = c(m, 6);
        const T &p = c(n - m, 0), &q = c(n - m, 1), &r = c(n - m, 2);
        s0 -= qx * p + qy * q + qz * r;
        s1 += qw * p + qy * r - qz * q;
        s2 += qw * q + qz * p - qx * r;
        s3 += qw * r + qx * q - qy * p;
    }
    const double half = 0.5 / (n + 1);
    c(n + 1, 3) = half * s0;
    c(n + 1, 4) = half * s1;
    c(n + 1, 5) = half * s2;
    c(n + 1, 6) = half * s3;
}

/// Taylor coefficients c(n, ·), n = 1..order, of the affine Euler equations (and the attitude)
/// from c(0, ·) = y: y(t + h) = Σ c(n, ·) hⁿ. The right-hand side is quadratic, so each order is
/// a Cauchy product of earlier ones; with P_jk[n] = Σ_{m≤n} ω_j[m] ω_k[n−m]:
///   ω_i[n+1] = J_i⁻¹ ((A_j − A_k) P_jk[n] − (ω[n] × k)_i − (D ω[n])_i + M0_i δ_{n0}) / (n + 1),
///   q[n+1] = ½ Σ_{m≤n} q[m] ⊗ (0, ω[n−m]) / (n + 1).
/// `c(n, i)` returns a reference to coefficient n of component i. The order is a compile-time
/// constant, so the short nested loops unroll completely; T = double (from order 20 with the
/// products packed in pairs, PackedEulerOrders) or lanes::Lanes (one body per lane: no lane's
/// numbers depend on another's).
template <int order, bool WithAttitude, class T, class Coefficient>
void euler_taylor_recursion(const AffineEuler<T>& e, Coefficient&& c) {
    if constexpr (std::is_same_v<T, double> && order >= 20) {  // the products packed in pairs
        PackedEulerOrders<order> orders;
        T w1 = c(0, 0), w2 = c(0, 1), w3 = c(0, 2);  // ω[n] in locals (no store-forwarding stalls)
        orders.push(0, w1, w2, w3);
#pragma GCC unroll 32
        for (int n = 0; n < order; ++n) {
            T affine[3] = {0.0, 0.0, 0.0};
            const bool with_affine = e.has_rotor || e.damped || n == 0;
            if (with_affine) add_affine_euler_terms(e, n, w1, w2, w3, affine[0], affine[1], affine[2]);
            orders.next(n, e, with_affine, affine, w1, w2, w3);
            orders.push(n + 1, w1, w2, w3);
            c(n + 1, 0) = w1;
            c(n + 1, 1) = w2;
            c(n + 1, 2) = w3;
            if constexpr (WithAttitude) attitude_order<T>(n, c);
        }
        return;
    }
    T w1[order + 1], w2[order + 1], w3[order + 1];
    w1[0] = c(0, 0), w2[0] = c(0, 1), w3[0] = c(0, 2);
#pragma GCC unroll 32
    for (int n = 0; n < order; ++n) {
        // Products j·k summed in pairs from both ends (terms m and n − m share their factors'
        // loads), with two partial sums to shorten the chain of dependent additions; m runs down
        // so that the newest coefficient (m = 0, r = n) is added last: the step is a chain of
        // dependent operations, and the older terms' sums can then start early.
        T p23 = lanes::splat<T>(0.0), p31 = p23, p12 = p23, q23 = p23, q31 = p23, q12 = p23;
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
        // Plain locals, not Eigen 3-vectors: temporaries here cost store-forwarding stalls.
        T r1 = e.differences[0] * p23, r2 = e.differences[1] * p31, r3 = e.differences[2] * p12;
        add_affine_euler_terms(e, n, w1[n], w2[n], w3[n], r1, r2, r3);
        const double inv = 1.0 / (n + 1);  // J⁻¹/(n + 1) first: one multiplication after the sum
        w1[n + 1] = r1 * (e.inverse_moments[0] * inv);
        w2[n + 1] = r2 * (e.inverse_moments[1] * inv);
        w3[n + 1] = r3 * (e.inverse_moments[2] * inv);
        c(n + 1, 0) = w1[n + 1];
        c(n + 1, 1) = w2[n + 1];
        c(n + 1, 2) = w3[n + 1];
        if constexpr (WithAttitude) attitude_order<T>(n, c);
    }
}

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

    Gyrostat(Body body, TorqueSet torques)
        : body_(std::move(body)), torques_(std::move(torques)), affine_(AffineEuler<double>::of(body_, torques_)) {}

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

    /// Taylor coefficients y[0..order] of the solution through y(t): y(t + h) = Σ y[n] hⁿ, from
    /// the recursion euler_taylor_recursion (above) for constant and linear torques.
    static constexpr int max_taylor_order = 30;

    template <int order>
    void taylor_coefficients(double /*t*/, const State& y, State* coefficients) const {
        for (int i = 0; i < dim; ++i) coefficients[0][i] = y[i];
        euler_taylor_recursion<order, WithAttitude>(affine_, [&](int n, int i) -> double& { return coefficients[n][i]; });
    }

    /// The affine Euler equations' coefficients (constant and linear torques folded).
    const AffineEuler<double>& affine_euler() const { return affine_; }

    // --- Splitting (integrate/splitting.hpp) ---------------------------------------------------
    // f = f_free + f_pert with
    //   f_free = (J⁻¹ (Jω + k) × ω,  ½ q ⊗ (0, ω))   the free gyrostat: its exact flow FreeBodyFlow,
    //   f_pert = (J⁻¹ ΣM(t, ω),      0)              the torques with t frozen (t advances in the
    //                                                 free part), q unchanged.
    // Constant and linear torques alone (M = M0 − D ω) have the exact perturbation flow
    // (integrate::AffineRateFlow). Any other torque (cavity, damper, medium) is not exact: the
    // perturbation sub-flow is then one step of the 8th-order Dormand–Prince method
    // (integrate::dop853_substep).

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

    /// |G| = |Jω| is a first integral the splitting projects on (a rigid body, and every torque
    /// keeps it: none, or the cavity).
    bool keeps_momentum_norm() const { return body_.rotor().squaredNorm() == 0.0 && torques_.keeps_momentum_norm(); }

    /// The perturbation's flow over h, prepared once per sub-step size.
    using Perturbation = integrate::TorqueSubflow;
    Perturbation perturbation(double h) const { return Perturbation::over(h, body_, torques_); }
    /// y ← the perturbation's flow over p.h at frozen time t.
    void perturb(const Perturbation& p, double t, State& y) const {
        if (torques_.empty()) return;
        y.template head<3>() = p.advance(body_, torques_, t, y.template head<3>(), Vec3::Zero());
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
    AffineEuler<double> affine_;  // the constant and linear torques' part, for the Taylor recursion
};

}  // namespace gyrostat::model
