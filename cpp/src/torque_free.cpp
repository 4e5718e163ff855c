#include "gyrostat/model/torque_free.hpp"

#include "gyrostat/numeric/elliptic.hpp"
#include "gyrostat/attitude.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>

namespace gyrostat::model {


namespace {

// The closed form's constants (the formulas of TorqueFreeSolution's and FreeBodyFlow's comments)
// in the scalar Real (DoubleDouble or double) from the exact double inputs J and ω. The ordering
// G² − 2TB = Σ J_i (J_i − B) ω_i², 2TC − G² = A (C − A) ω1² + B (C − B) ω2² and
// G² − 2TA = B (B − A) ω2² + C (C − A) ω3² are formed from the components (no cancellation of the
// two large invariants near a permanent rotation or the separatrix). K = R_F(0, 1 − m, 1),
// Π(N | m) = K + (N/3) R_J(0, 1 − m, 1, 1 − N) (DLMF 19.25.1–2), Carlson's duplication in Real.
template <class Real>
void compute_constants(const Vec3& J, const Vec3& w, bool precession, FreeBodyConstants& k) {
    using std::sqrt;
    int order[3] = {0, 1, 2};
    std::sort(order, order + 3, [&](int i, int j) { return J[i] < J[j]; });
    const auto sq = [&](int i) { return Real(w[i]) * Real(w[i]); };
    const Real Jmin(J[order[0]]), Jmid(J[order[1]]), Jmax(J[order[2]]);
    const Real versus_middle = Jmin * (Jmin - Jmid) * sq(order[0]) + Jmax * (Jmax - Jmid) * sq(order[2]);
    const bool about_largest = versus_middle >= Real(0.0);
    for (int i = 0; i < 3; ++i) k.axis[i] = about_largest ? order[i] : order[2 - i];
    const Real A(J[k.axis[0]]), B(J[k.axis[1]]), C(J[k.axis[2]]);
    const double w1 = w[k.axis[0]], w3 = w[k.axis[2]];
    const Real across = A * (C - A) * sq(k.axis[0]) + B * (C - B) * sq(k.axis[1]);
    const Real along = B * (B - A) * sq(k.axis[1]) + C * (C - A) * sq(k.axis[2]);
    // Permanent rotation about axis 3' (or about the intermediate axis): ω stays constant.
    if (across == Real(0.0) || (w1 == 0.0 && w3 == 0.0)) return;
    k.constant = false;
    const Real a = sqrt(across / (A * (C - A)));
    const Real b = B == C ? Real(0.0) : sqrt(across / (B * (C - B)));
    const Real c = sqrt(along / (C * (C - A)));
    // 1 − m = ((C − B) along − (B − A) across)/((C − B) along) = (C − A) versus_middle/((C − B) along):
    // the complement from the component sum (no cancellation next to the separatrix, where
    // m = 1 − 1e-30 is not a double), and m from it.
    const Real m_denominator = (C - B) * along;
    Real one_minus_m = m_denominator == Real(0.0) ? Real(0.0) : (C - A) * versus_middle / m_denominator;
    if (!(one_minus_m >= Real(0.0))) one_minus_m = Real(0.0);
    if (!(one_minus_m <= Real(1.0))) one_minus_m = Real(1.0);
    const Real m = Real(1.0) - one_minus_m;
    k.sign3 = w3 >= 0.0 ? 1.0 : -1.0;
    // Parity of the relabelling (1', 2', 3'): a cyclic order keeps Euler's equations, an odd
    // one reverses the sign of their right-hand sides.
    const double parity = (k.axis[1] - k.axis[0] + 3) % 3 == 1 ? 1.0 : -1.0;
    const Real nu = Real(parity * k.sign3) * (C - B) * b * c / (A * a);
    const bool bounded = one_minus_m > Real(0.0);
    const Real K = bounded ? carlson_RF(Real(0.0), one_minus_m, Real(1.0)) : Real(std::numeric_limits<double>::infinity());
    k.a = double(a), k.b = double(b), k.c = double(c), k.m = double(m), k.m1 = double(one_minus_m);
    k.nu = DoubleDouble(nu), k.K = DoubleDouble(K);
    if (!precession) return;
    Real G2(0.0);
    for (int i = 0; i < 3; ++i) G2 += (Real(J[i]) * Real(w[i])) * (Real(J[i]) * Real(w[i]));
    const Real G = sqrt(G2);
    const Real N = B == C ? Real(0.0) : -(C * (B - A)) / (A * (C - B));
    k.G = DoubleDouble(G);
    k.rate = DoubleDouble(G / C);
    k.coeff = DoubleDouble(G * (C - A) / (C * A * nu));
    k.N = double(N);
    k.Pi_complete = DoubleDouble(
        bounded ? K + N / Real(3.0) * carlson_RJ(Real(0.0), one_minus_m, Real(1.0), Real(1.0) - N) : Real(0.0));
}

}  // namespace

TorqueFreeSolution::TorqueFreeSolution(const Body& body, const Vec3& omega0, double t0, Phases phases, bool precession)
    : omega0_(omega0), t0_(t0) {
    if (body.rotor().squaredNorm() != 0.0)
        throw std::invalid_argument("TorqueFreeSolution: the closed form is for a rigid body (rotor k = 0); "
                                    "this body has |k| = " + std::to_string(body.rotor().norm()) +
                                    ": integrate the full model instead");
    require_finite(omega0, "TorqueFreeSolution: omega0");
    if (!std::isfinite(t0)) throw std::invalid_argument("TorqueFreeSolution: t0 is not finite");
    const Vec3& J = body.moments();
    const double tiny = 64.0 * std::numeric_limits<double>::epsilon();
    if (omega0.squaredNorm() == 0.0 || J.maxCoeff() - J.minCoeff() <= tiny * J.maxCoeff()) return;  // rest, sphere
    if (phases == Phases::Extended)
        compute_constants<DoubleDouble>(J, omega0, precession, k_);
    else
        compute_constants<double>(J, omega0, precession, k_);
    if (k_.constant) return;
    // u0 from sn u0 = ω2'/b, cn u0 = ω1'/a, dn u0 = ±ω3'/c (jacobi_argument): next to the
    // separatrix cn and dn are both tiny, and only the components themselves carry their digits.
    const double w1 = omega0[k_.axis[0]], w2 = omega0[k_.axis[1]], w3 = omega0[k_.axis[2]];
    const double sn0 = k_.b > 0.0 ? w2 / k_.b : 0.0, cn0 = w1 / k_.a;
    const double norm = std::hypot(sn0, cn0);  // 1 to rounding
    // On the separatrix (K = ∞) the orbit with ω1' < 0 is the mirror (−a sech, −b tanh, ±c sech)
    // of the one with ω1' > 0: "u + 2K" with K = ∞, so it is carried as the fixed parity j = 1
    // (sn, cn change sign with j: TorqueFreeSolution::omega) and u0 taken on the other branch.
    branch_ = isfinite(k_.K) || cn0 >= 0.0 ? 0.0 : 1.0;
    const double flip = branch_ == 0.0 ? 1.0 : -1.0;
    u0_ = jacobi_argument(flip * sn0 / norm, flip * cn0 / norm, std::abs(w3) / k_.c, k_.m1);
}

// u = ν τ + u0 in double-double, j = nearest integer of u/2K, r = u − 2jK (|r| ≤ K up to
// rounding: clamped so that cn r ≥ 0), then sn, cn, dn of r in double.
TorqueFreeSolution::Reduced TorqueFreeSolution::reduced_since(const DoubleDouble& tau) const {
    const DoubleDouble u = k_.nu * tau + DoubleDouble(u0_);
    double j = branch_, r = double(u);
    if (isfinite(k_.K)) {
        const Reduction reduction = reduce(u, k_.K + k_.K);
        j = reduction.n;
        const double K = double(k_.K);
        r = std::clamp(double(reduction.r), -K, K);
    }
    const auto [sn, cn, dn] = jacobi_sn_cn_dn_complementary(r, k_.m1);
    return {j, sn, std::max(cn, 0.0), dn};
}

// ω1' = a cn u, ω2' = b sn u, ω3' = ±c dn u with sn, cn of u = 2jK + r equal to (−1)^j those of r.
Vec3 TorqueFreeSolution::omega(const Reduced& z) const {
    const double sign = std::fmod(std::abs(z.j), 2.0) == 1.0 ? -1.0 : 1.0;
    Vec3 w;
    w[k_.axis[0]] = k_.a * sign * z.cn;
    w[k_.axis[1]] = k_.b * sign * z.sn;
    w[k_.axis[2]] = k_.sign3 * k_.c * z.dn;
    return w;
}

Vec3 TorqueFreeSolution::omega(double t) const {
    if (k_.constant) return omega0_;
    return omega(reduced(t));
}

std::vector<double> TorqueFreeSolution::omega(const std::vector<double>& times) const {
    std::vector<double> out(3 * times.size());
    for (std::size_t i = 0; i < times.size(); ++i) {
        const Vec3 w = omega(times[i]);
        std::copy(w.data(), w.data() + 3, out.begin() + 3 * i);
    }
    return out;
}

double TorqueFreeSolution::period() const {
    if (k_.constant || !isfinite(k_.K)) return std::numeric_limits<double>::infinity();
    return 4.0 * double(k_.K) / std::abs(double(k_.nu));
}

// ---------------------------------------------------------------------------------------------
// FreeBodyFlow (the derivation is in model/torque_free.hpp)
// ---------------------------------------------------------------------------------------------

Eigen::Vector4d rotation_quaternion(const Vec3& v) {
    const double angle = v.norm();
    if (angle == 0.0) return {1.0, 0.0, 0.0, 0.0};
    const double s = std::sin(0.5 * angle) / angle;
    return {std::cos(0.5 * angle), s * v[0], s * v[1], s * v[2]};
}

namespace {

const double kTiny = 64.0 * std::numeric_limits<double>::epsilon();

/// The symmetry axis of a body with two equal moments (−1: none; 3: spherical).
int symmetry_axis(const Vec3& J) {
    const double scale = J.maxCoeff();
    const bool e01 = std::abs(J[0] - J[1]) <= kTiny * scale, e12 = std::abs(J[1] - J[2]) <= kTiny * scale,
               e02 = std::abs(J[0] - J[2]) <= kTiny * scale;
    if (e01 && e12) return 3;
    if (e01) return 2;
    if (e12) return 0;
    if (e02) return 1;
    return -1;
}

Eigen::Vector4d conjugate(const Eigen::Vector4d& q) { return {q[0], -q[1], -q[2], -q[3]}; }
Eigen::Vector4d q_x(double angle) { return {std::cos(0.5 * angle), std::sin(0.5 * angle), 0.0, 0.0}; }
Eigen::Vector4d q_z(double angle) { return {std::cos(0.5 * angle), 0.0, 0.0, std::sin(0.5 * angle)}; }

}  // namespace

void FreeBodyFlow::require_closed_form(const Body& body, const char* who) {
    const Vec3& k = body.rotor();
    if (k.squaredNorm() == 0.0) return;
    const int axis = symmetry_axis(body.moments());
    if (axis == 3) return;
    if (axis >= 0) {
        bool axial = true;
        for (int i = 0; i < 3; ++i)
            if (i != axis && std::abs(k[i]) > kTiny * k.norm()) axial = false;
        if (axial) return;
    }
    throw std::invalid_argument(
        std::string(who) + ": the free flow of a gyrostat has a closed form here only for a rigid body (k = 0), a "
        "symmetric body with the rotor along its symmetry axis, or a spherical body; this body has moments (" +
        format_value(body.moments()[0]) + ", " + format_value(body.moments()[1]) + ", " + format_value(body.moments()[2]) +
        ") and rotor k = (" + format_value(k[0]) + ", " + format_value(k[1]) + ", " + format_value(k[2]) +
        ") (the Zhukovsky–Volterra gyrostat is not implemented): integrate the full Model instead");
}

namespace {

/// |v| in double-double, taken of v / 2^e with 2^e ≤ max|v_i| < 2^(e+1) (exact): the squares
/// neither overflow (|v_i| > 1e154) nor underflow (every |v_i| < 1e-154), and in between the
/// result is the unscaled one, bit for bit.
DoubleDouble norm_dd(const std::array<DoubleDouble, 3>& v) {
    const double largest = std::max({std::abs(v[0].hi), std::abs(v[1].hi), std::abs(v[2].hi)});
    if (!(largest > 0.0)) return DoubleDouble(0.0);
    int exponent = 0;
    std::frexp(largest, &exponent);
    const double scale = std::ldexp(1.0, exponent - 1);
    DoubleDouble sum;
    for (const DoubleDouble& x : v) {
        const DoubleDouble scaled(x.hi / scale, x.lo / scale);
        sum += scaled * scaled;
    }
    return sqrt(sum) * DoubleDouble(scale);
}
/// |v| in double-double from the exact components.
DoubleDouble norm_dd(const Vec3& v) { return norm_dd({DoubleDouble(v[0]), DoubleDouble(v[1]), DoubleDouble(v[2])}); }

const DoubleDouble four_pi_dd(2.0 * two_pi_dd.hi, 2.0 * two_pi_dd.lo);

}  // namespace

// q_rot(θ a) = (cos θ/2, sin θ/2 a), θ = rate τ − 4πn formed in double-double.
Eigen::Vector4d FreeBodyFlow::Spin::quaternion(const DoubleDouble& tau) const {
    if (rate == DoubleDouble(0.0)) return {1.0, 0.0, 0.0, 0.0};
    const double angle = double(reduce(rate * tau, four_pi_dd).r);
    const double s = std::sin(0.5 * angle);
    return {std::cos(0.5 * angle), s * axis[0], s * axis[1], s * axis[2]};
}

FreeBodyFlow::FreeBodyFlow(const Body& body, const Vec3& omega0, const Eigen::Vector4d& q0, double t0, bool attitude,
                           Phases phases)
    : t0_(t0), omega0_(omega0), q0_(attitude ? unit_quaternion(q0) : Eigen::Vector4d(1, 0, 0, 0)) {
    require_closed_form(body, "FreeBodyFlow");
    require_finite(omega0, "FreeBodyFlow: omega0");
    if (!std::isfinite(t0)) throw std::invalid_argument("FreeBodyFlow: t0 = " + format_value(t0) + " is not finite");
    const Vec3& J = body.moments();
    const Vec3& k = body.rotor();
    const int axis = symmetry_axis(J);
    // Constant ω (at rest, a permanent rotation): R(t) = R0 exp(Δt [ω0]×).
    const DoubleDouble w_norm = norm_dd(omega0);
    if (w_norm.hi > 0.0) spin_ = {omega0 / w_norm.hi, w_norm};
    if (axis >= 0) {  // symmetric or spherical, any axial rotor
        kind_ = Kind::Symmetric;
        const int transverse = axis == 3 ? 0 : (axis + 1) % 3;
        const DoubleDouble A(J[transverse]);
        // λ = k/A (sphere) or ((C − A) ω·e + k·e)/A e
        Spin lambda;
        if (axis == 3) {
            const DoubleDouble k_norm = norm_dd(k);
            if (k_norm.hi > 0.0) lambda = {k / k_norm.hi, k_norm / A};
        } else {
            const DoubleDouble C(J[axis]);
            const DoubleDouble along = ((C - A) * DoubleDouble(omega0[axis]) + DoubleDouble(k[axis])) / A;
            lambda.axis = Vec3::Unit(axis) * (along.hi < 0.0 ? -1.0 : 1.0);
            lambda.rate = abs(along);
        }
        if (lambda.rate == DoubleDouble(0.0)) {
            kind_ = Kind::Constant;
            return;
        }
        spin_ = lambda;
        if (attitude) {  // about G_in = R(q0) G_b at |G|/A, G_b = J ω0 + k
            std::array<DoubleDouble, 3> G;
            for (int i = 0; i < 3; ++i) G[i] = DoubleDouble(J[i]) * DoubleDouble(omega0[i]) + DoubleDouble(k[i]);
            const DoubleDouble G_norm = norm_dd(G);
            Vec3 G_in = rotation_matrix(q0_) * body.angular_momentum(omega0);
            normalize_in_place(G_in);  // (|G| may overflow or underflow in double: numeric/unit_vector.hpp)
            if (G_norm.hi > 0.0) precession_ = {G_in, G_norm / A};
        }
        return;
    }
    // Scale invariance of the free rigid body: ω(t; s ω̂0) = s ω(s t; ω̂0), and the attitude is a
    // function of s t. Working with ω̂0 = ω0/s, s the power of two at or above max|ω0_i| (so that
    // ω0/s and s t are exact), keeps every square in the formulas away from underflow (a decayed
    // ω of 1e-160 would otherwise lose all its digits in ω²).
    const double largest = omega0.cwiseAbs().maxCoeff();
    if (largest == 0.0) {  // at rest
        kind_ = Kind::Constant;
        return;
    }
    int exponent = 0;
    std::frexp(largest, &exponent);
    scale_ = std::ldexp(1.0, exponent);
    const Vec3 unit = omega0 / scale_;
    elliptic_ = TorqueFreeSolution(body, unit, 0.0, phases, attitude);
    if (elliptic_.is_constant()) {
        kind_ = Kind::Constant;
        return;
    }
    kind_ = Kind::Elliptic;
    const FreeBodyConstants& c = elliptic_.constants();
    const int* ax = c.axis;
    A_ = J[ax[0]], B_ = J[ax[1]], C_ = J[ax[2]];
    G_ = J.cwiseProduct(unit).norm();
    const bool cyclic = (ax[1] - ax[0] + 3) % 3 == 1;
    s_ = cyclic ? 1.0 : -1.0;
    S_.setZero();
    S_(0, ax[0]) = 1.0, S_(1, ax[1]) = s_, S_(2, ax[2]) = 1.0;
    if (!attitude) return;
    rate_ = c.rate;
    coeff_ = double(c.coeff);
    drift_ = DoubleDouble(2.0) * c.coeff * c.Pi_complete;
    const TorqueFreeSolution::Reduced z0 = elliptic_.reduced_since(DoubleDouble(0.0));
    j0_ = z0.j;
    Pi_r0_ = elliptic_Pi_jacobi(z0.sn, z0.cn, z0.dn, c.N, c.m);
    q_s_ = quaternion_from_matrix(S_);
    // q_in = q0 ⊗ q_S* ⊗ (q_x(θ0) ⊗ q_z(ψ0))*
    const Vec3 g = S_ * J.cwiseProduct(unit) / G_;
    const double sin_theta = std::hypot(g[0], g[1]);
    const double theta0 = std::atan2(sin_theta, g[2]);
    const double psi0 = std::atan2(A_ * c.a * z0.cn, s_ * B_ * c.b * z0.sn) - s_ * std::fmod(z0.j, 4.0) * M_PI;
    const Eigen::Vector4d qw0 = quaternion_product(q_x(theta0), q_z(psi0));
    q_in_ = quaternion_product(quaternion_product(q0_, conjugate(q_s_)), conjugate(qw0));
}

Vec3 FreeBodyFlow::omega(double t) const {
    const DoubleDouble dt = two_diff(t, t0_);
    switch (kind_) {
        case Kind::Constant: return omega0_;
        case Kind::Symmetric: return rotation_matrix(spin_.quaternion(dt)) * omega0_;
        case Kind::Elliptic: break;
    }
    return scale_ * elliptic_.omega(elliptic_.reduced_since(dt * DoubleDouble(scale_)));
}

// φ(τ) − φ(0) = rate τ + drift (j − j0) [double-double, reduced modulo 4π] + coeff (Π̃(r) − Π̃(r0)),
// θ and ψ from ω(τ) in primed axes (the same reduced sn, cn, dn), ψ's shift j π taken modulo 4π.
Eigen::Vector4d FreeBodyFlow::elliptic_quaternion(const DoubleDouble& tau, const TorqueFreeSolution::Reduced& z) const {
    const FreeBodyConstants& c = elliptic_.constants();
    const DoubleDouble secular = rate_ * tau + drift_ * DoubleDouble(z.j - j0_);
    const double Pi_r = elliptic_Pi_jacobi(z.sn, z.cn, z.dn, c.N, c.m);
    const double dphi = double(reduce(secular, four_pi_dd).r) + coeff_ * (Pi_r - Pi_r0_);
    const double sign = std::fmod(std::abs(z.j), 2.0) == 1.0 ? -1.0 : 1.0;
    const double w1 = c.a * sign * z.cn, w2 = s_ * c.b * sign * z.sn;
    const double w3 = c.sign3 * c.c * z.dn;
    const double sin_theta = std::hypot(A_ * w1, B_ * w2) / G_;
    const double theta = std::atan2(sin_theta, C_ * w3 / G_);
    const double psi = std::atan2(A_ * c.a * z.cn, s_ * B_ * c.b * z.sn) - s_ * std::fmod(z.j, 4.0) * M_PI;
    Eigen::Vector4d q = quaternion_product(q_in_, q_z(dphi));
    q = quaternion_product(q, q_x(theta));
    q = quaternion_product(q, q_z(psi));
    return quaternion_product(q, q_s_);
}

Eigen::Vector4d FreeBodyFlow::quaternion(double t) const {
    const DoubleDouble dt = two_diff(t, t0_);
    switch (kind_) {
        case Kind::Constant: return quaternion_product(q0_, spin_.quaternion(dt));
        case Kind::Symmetric:
            return quaternion_product(quaternion_product(precession_.quaternion(dt), q0_), conjugate(spin_.quaternion(dt)));
        case Kind::Elliptic: break;
    }
    const DoubleDouble tau = dt * DoubleDouble(scale_);
    return elliptic_quaternion(tau, elliptic_.reduced_since(tau));
}

FreeBodyFlow::State FreeBodyFlow::at(double t) const {
    State y;
    if (kind_ == Kind::Elliptic) {  // one reduction for ω and q
        const DoubleDouble tau = two_diff(t, t0_) * DoubleDouble(scale_);
        const TorqueFreeSolution::Reduced z = elliptic_.reduced_since(tau);
        y.head<3>() = scale_ * elliptic_.omega(z);
        y.tail<4>() = elliptic_quaternion(tau, z);
        return y;
    }
    y.head<3>() = omega(t);
    y.tail<4>() = quaternion(t);
    return y;
}

double FreeBodyFlow::period() const {
    switch (kind_) {
        case Kind::Constant: return std::numeric_limits<double>::infinity();
        case Kind::Symmetric: return 2.0 * M_PI / std::max(double(spin_.rate), double(precession_.rate));
        case Kind::Elliptic: break;
    }
    return elliptic_.period() / scale_;
}

double FreeBodyFlow::event_step() const {
    // the attitude turns about G at |G|/C as well: 1/32 of the shorter of the two periods
    double p = period();
    if (kind_ == Kind::Elliptic) p = std::min(p, 2.0 * M_PI * std::min(C_, A_) / (G_ * scale_));
    if (kind_ == Kind::Constant && omega0_.norm() > 0.0) p = 2.0 * M_PI / omega0_.norm();
    return p / 32.0;
}

}  // namespace gyrostat::model
