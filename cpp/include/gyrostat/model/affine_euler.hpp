// The affine Euler equations (the gyrostat under constant and linear torques) in the form the
// Taylor recursion and the SIMD batches use: their coefficients, right-hand side and Taylor
// recursion, for one body (T = double) or one body per SIMD lane (T = lanes::Lanes). The one-body
// recursion has a second form, compiled for AVX2 + FMA and chosen at run time
// (affine_euler_avx2.hpp).
#pragma once

#include <type_traits>

#include "gyrostat/body.hpp"
#include "gyrostat/numeric/lanes.hpp"
#include "gyrostat/numeric/double_double.hpp"
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
/// `extra`: a further torque M_i added to M0_i (the user's vectorised torques, model/gyrostat.hpp),
/// or nullptr.
template <bool WithAttitude, class T>
void affine_euler_rhs(const AffineEuler<T>& e, const T* y, T* dy, const T* extra = nullptr) {
    T r[3] = {e.differences[0] * y[1] * y[2], e.differences[1] * y[2] * y[0], e.differences[2] * y[0] * y[1]};
    if (e.has_rotor) {
        r[0] -= y[1] * e.rotor[2] - y[2] * e.rotor[1];
        r[1] -= y[2] * e.rotor[0] - y[0] * e.rotor[2];
        r[2] -= y[0] * e.rotor[1] - y[1] * e.rotor[0];
    }
    if (e.damped)
        for (int i = 0; i < 3; ++i) r[i] -= e.damping[3 * i] * y[0] + e.damping[3 * i + 1] * y[1] + e.damping[3 * i + 2] * y[2];
    if (extra)
        for (int i = 0; i < 3; ++i) dy[i] = (r[i] + (e.constant[i] + extra[i])) * e.inverse_moments[i];
    else
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

/// The linear part of the affine Euler rate, a_i(ω) = −(ω × k)_i − (D ω)_i = Σ_l A_il ω_l:
///   A = −D + skew-part of the rotor, A_ij += −k_k, A_ik += k_j   ((i, j, k) cyclic).
inline void affine_euler_linear_part(const AffineEuler<double>& e, double (&a)[3][3]) {
    for (int i = 0; i < 3; ++i)
        for (int l = 0; l < 3; ++l) a[i][l] = e.damped ? -e.damping[3 * i + l] : 0.0;
    if (e.has_rotor)
        for (int i = 0; i < 3; ++i) {
            const int j = (i + 1) % 3, k = (i + 2) % 3;
            a[i][j] -= e.rotor[k];
            a[i][k] += e.rotor[j];
        }
}

/// f(ω + ω_low) − c1 beyond double precision (System::taylor_rate_error, model/system.hpp), for
/// the affine Euler rate f_i(ω) = J_i⁻¹ ((A_j − A_k) ω_j ω_k + Σ_l A_il ω_l + M0_i): c1 = fl(f(ω))
/// is the first Taylor coefficient as computed (~1 ulp of rounding), ω_low the compensated state's
/// low part (~½ ulp of ω). To first order in ω_low,
///   f(ω + ω_low) − c1 = (f(ω) − c1) + ∂f/∂ω ω_low,
///   ∂f_i/∂ω ω_low = J_i⁻¹ ((A_j − A_k)(ω_low,j ω_k + ω_j ω_low,k) + Σ_l A_il ω_low,l),
/// with f(ω) as hi + lo from error-free products (dekker_product_error: no FMA needed) and sums
/// (two_sum), so that f_hi − c1 is exact and the result good to ~2⁻¹⁰⁰ of f plus O(ω_low²).
/// The Taylor integrator adds (f(ω + ω_low) − c1)·h to the state's low part: the largest rounding
/// of a step's change left in a long compensated run (integrate/taylor.hpp).
inline void affine_euler_rate_error(const AffineEuler<double>& e, const double* w, const double* low, const double* c1,
                                    double* error) {
    double a[3][3];
    affine_euler_linear_part(e, a);
    const bool affine = e.damped || e.has_rotor;  // (else A = 0: its terms skipped)
    for (int i = 0; i < 3; ++i) {
        const int j = (i + 1) % 3, k = (i + 2) % 3;
        const double product = w[j] * w[k];
        const double product_low = dekker_product_error(w[j], w[k], product);
        const double quadratic = e.differences[i] * product;
        double sum_low = dekker_product_error(e.differences[i], product, quadratic) + e.differences[i] * product_low;
        double sum = quadratic;
        for (int l = 0; l < 3 && affine; ++l) {
            const double term = a[i][l] * w[l];
            const DoubleDouble s = dd_detail::two_sum(sum, term);
            sum = s.hi;
            sum_low += s.lo + dekker_product_error(a[i][l], w[l], term);
        }
        const DoubleDouble s = dd_detail::two_sum(sum, e.constant[i]);
        sum = s.hi;
        sum_low += s.lo;
        const double f = e.inverse_moments[i] * sum;
        const double f_low = dekker_product_error(e.inverse_moments[i], sum, f) + e.inverse_moments[i] * sum_low;
        const double linear = e.differences[i] * (low[j] * w[k] + w[j] * low[k]) +
                              (affine ? a[i][0] * low[0] + a[i][1] * low[1] + a[i][2] * low[2] : 0.0);
        error[i] = (f - c1[i]) + (f_low + e.inverse_moments[i] * linear);
    }
}

/// s += Σ_{m≤n} q[m] ⊗ (0, w[n−m]), the n-th coefficient of the product q ⊗ (0, w) of two series
/// (q(m, ·): the quaternion's coefficient m, w(m, ·): the vector's).
template <class T, class Quaternion, class Vector>
__attribute__((always_inline)) inline void add_quaternion_product(int n, Quaternion&& q, Vector&& w, T (&s)[4]) {
    for (int m = 0; m <= n; ++m) {
        const T &qw = q(m, 0), &qx = q(m, 1), &qy = q(m, 2), &qz = q(m, 3);
        const T &p = w(n - m, 0), &v = w(n - m, 1), &r = w(n - m, 2);
        s[0] -= qx * p + qy * v + qz * r;
        s[1] += qw * p + qy * r - qz * v;
        s[2] += qw * v + qz * p - qx * r;
        s[3] += qw * r + qx * v - qy * p;
    }
}

/// Order n + 1 of the attitude in the Euler recursion below:
///   q[n+1] = ½ Σ_{m≤n} q[m] ⊗ (0, ω[n−m]) / (n + 1).
template <class T, class Coefficient>
void attitude_order(int n, Coefficient& c) {
    T s[4] = {lanes::splat<T>(0.0), lanes::splat<T>(0.0), lanes::splat<T>(0.0), lanes::splat<T>(0.0)};
    add_quaternion_product<T>(n, [&](int m, int i) -> const T& { return c(m, 3 + i); },
                              [&](int m, int i) -> const T& { return c(m, i); }, s);
    const double half = 0.5 / (n + 1);
    for (int i = 0; i < 4; ++i) c(n + 1, 3 + i) = half * s[i];
}

/// Taylor coefficients c(n, ·), n = 1..order, of the affine Euler equations (and the attitude)
/// from c(0, ·) = y: y(t + h) = Σ c(n, ·) hⁿ. The right-hand side is quadratic, so each order is
/// a Cauchy product of earlier ones; with P_jk[n] = Σ_{m≤n} ω_j[m] ω_k[n−m]:
///   ω_i[n+1] = J_i⁻¹ ((A_j − A_k) P_jk[n] − (ω[n] × k)_i − (D ω[n])_i + M0_i δ_{n0}) / (n + 1),
///   q[n+1] = ½ Σ_{m≤n} q[m] ⊗ (0, ω[n−m]) / (n + 1).
/// `c(n, i)` returns a reference to coefficient n of component i. The order is a compile-time
/// constant, so the short nested loops unroll completely; T = double (the portable form: the
/// Gyrostat uses affine_euler_rate_orders_avx2 instead where the CPU has AVX2 and FMA) or
/// lanes::Lanes (one body per lane: no lane's numbers depend on another's).
template <int order, bool WithAttitude, class T, class Coefficient>
void euler_taylor_recursion(const AffineEuler<T>& e, Coefficient&& c) {
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

/// The affine Euler rate component by component, f_i(ω) = Q_i ω_j ω_k + Σ_l L_il ω_l + C_i
/// ((i, j, k) cyclic), with Q_i = J_i⁻¹ (A_j − A_k), L = J⁻¹ A (A: affine_euler_linear_part) and
/// C_i = J_i⁻¹ M0_i: the form the variational equations' Taylor recursion (affine_euler_tangent_order)
/// reads. f is linear in these coefficients, so its derivative with respect to a parameter of the
/// model is the same form with the coefficients' derivatives (`derivative`).
struct AffineEulerRate {
    double quadratic[3] = {0.0, 0.0, 0.0};
    double linear[3][3] = {{0.0, 0.0, 0.0}, {0.0, 0.0, 0.0}, {0.0, 0.0, 0.0}};
    double constant[3] = {0.0, 0.0, 0.0};

    static AffineEulerRate of(const AffineEuler<double>& e) {
        AffineEulerRate f;
        affine_euler_linear_part(e, f.linear);
        for (int i = 0; i < 3; ++i) {
            f.quadratic[i] = e.inverse_moments[i] * e.differences[i];
            f.constant[i] = e.inverse_moments[i] * e.constant[i];
            for (int l = 0; l < 3; ++l) f.linear[i][l] *= e.inverse_moments[i];
        }
        return f;
    }
    /// ∂f/∂p as the central difference (f_plus − f_minus)/(2 step) of the rates of the models built
    /// with p moved by ±step: the difference of their coefficients (the same number as the
    /// difference of the two rates wherever they are evaluated, up to rounding).
    static AffineEulerRate derivative(const AffineEuler<double>& plus, const AffineEuler<double>& minus, double step) {
        const AffineEulerRate a = of(plus), b = of(minus);
        AffineEulerRate d;
        const double scale = 1.0 / (2.0 * step);
        for (int i = 0; i < 3; ++i) {
            d.quadratic[i] = (a.quadratic[i] - b.quadratic[i]) * scale;
            d.constant[i] = (a.constant[i] - b.constant[i]) * scale;
            for (int l = 0; l < 3; ++l) d.linear[i][l] = (a.linear[i][l] - b.linear[i][l]) * scale;
        }
        return d;
    }
};

/// P_i[n] = Σ_{m≤n} ω_j[m] ω_k[n−m] ((i, j, k) cyclic): the n-th coefficient of ω_j ω_k along the
/// solution (y(m, ·): its coefficient m), what the parameter terms of affine_euler_tangent_order read.
template <class Solution>
void affine_euler_products(int n, Solution&& y, double (&products)[3]) {
    for (int i = 0; i < 3; ++i) {
        const int j = (i + 1) % 3, k = (i + 2) % 3;
        double sum = 0.0;
        for (int m = 0; m <= n; ++m) sum += y(m, j) * y(n - m, k);
        products[i] = sum;
    }
}

/// Order n + 1 of a sensitivity S = ∂y/∂p along the solution y of the affine Euler equations (and
/// the attitude), from the orders ≤ n of both: S' = ∂f/∂y(y) S + ∂f/∂p(y) is bilinear in (y, S)
/// plus quadratic in y, so its coefficient n is a sum of Cauchy products of their coefficients:
///   S_ω,i[n+1] = (Q_i Σ_{m≤n} (ω_j[m] S_k[n−m] + S_j[m] ω_k[n−m]) + Σ_l L_il S_l[n]
///                 + Q'_i P_i[n] + Σ_l L'_il ω_l[n] + C'_i δ_{n0}) / (n + 1),
///   S_q[n+1]   = ½ Σ_{m≤n} (q[m] ⊗ (0, S_ω[n−m]) + S_q[m] ⊗ (0, ω[n−m])) / (n + 1),
/// with f's coefficients Q, L (AffineEulerRate `rate`), their derivatives Q', L', C' (`parameter`;
/// nullptr for a column of the initial state, which has no ∂f/∂p) and P_i[n] (affine_euler_products,
/// read only with a `parameter`). y(m, i), s(m, i): coefficient m of component i.
template <bool WithAttitude, class Solution, class Sensitivity>
void affine_euler_tangent_order(const AffineEulerRate& rate, const AffineEulerRate* parameter, const double (&products)[3],
                                int n, Solution&& y, Sensitivity&& s) {
    const double inv = 1.0 / (n + 1);
    double next[3];
    for (int i = 0; i < 3; ++i) {
        const int j = (i + 1) % 3, k = (i + 2) % 3;
        double bilinear = 0.0;
        for (int m = 0; m <= n; ++m) bilinear += y(m, j) * s(n - m, k) + s(m, j) * y(n - m, k);
        double r = rate.quadratic[i] * bilinear + (rate.linear[i][0] * s(n, 0) + rate.linear[i][1] * s(n, 1) +
                                                   rate.linear[i][2] * s(n, 2));
        if (parameter) {
            r += parameter->quadratic[i] * products[i] + (parameter->linear[i][0] * y(n, 0) +
                                                          parameter->linear[i][1] * y(n, 1) +
                                                          parameter->linear[i][2] * y(n, 2));
            if (n == 0) r += parameter->constant[i];
        }
        next[i] = r * inv;
    }
    for (int i = 0; i < 3; ++i) s(n + 1, i) = next[i];
    if constexpr (WithAttitude) {
        double q[4] = {0.0, 0.0, 0.0, 0.0};
        auto solution_q = [&](int m, int i) -> double { return y(m, 3 + i); };
        auto sensitivity_q = [&](int m, int i) -> double { return s(m, 3 + i); };
        add_quaternion_product<double>(n, solution_q, [&](int m, int i) -> double { return s(m, i); }, q);
        add_quaternion_product<double>(n, sensitivity_q, [&](int m, int i) -> double { return y(m, i); }, q);
        const double half = 0.5 * inv;
        for (int i = 0; i < 4; ++i) s(n + 1, 3 + i) = half * q[i];
    }
}

}  // namespace gyrostat::model
