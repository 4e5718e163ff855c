#include "gyrostat/model/torque_free.hpp"

#include "gyrostat/model/elliptic.hpp"
#include "gyrostat/attitude.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>

namespace gyrostat::model {


TorqueFreeSolution::TorqueFreeSolution(const Body& body, const Vec3& omega0, double t0) : omega0_(omega0), t0_(t0) {
    constant_ = false;
    if (body.rotor().squaredNorm() != 0.0)
        throw std::invalid_argument("TorqueFreeSolution: the closed form is for a rigid body (rotor k = 0); "
                                    "this body has |k| = " + std::to_string(body.rotor().norm()) +
                                    ": integrate the full model instead");
    require_finite(omega0, "TorqueFreeSolution: omega0");
    if (!std::isfinite(t0)) throw std::invalid_argument("TorqueFreeSolution: t0 is not finite");

    const Vec3& J = body.moments();
    int order[3] = {0, 1, 2};
    std::sort(order, order + 3, [&](int i, int j) { return J[i] < J[j]; });
    const double tiny = 64.0 * std::numeric_limits<double>::epsilon();
    if (omega0.squaredNorm() == 0.0 || J[order[2]] - J[order[0]] <= tiny * J[order[2]]) {
        constant_ = true;  // at rest, or a spherical body
        return;
    }
    // The ordering of 2T D = G² against 2T B (B the middle moment), from the components:
    // G² − 2TB = Σ J_i (J_i − B) ω_i², no cancellation of the two large invariants.
    const auto w2 = [&](int i) { return omega0[i] * omega0[i]; };
    const double Jmin = J[order[0]], Jmid = J[order[1]], Jmax = J[order[2]];
    const double versus_middle = Jmin * (Jmin - Jmid) * w2(order[0]) + Jmax * (Jmax - Jmid) * w2(order[2]);
    const bool about_largest = versus_middle >= 0.0;
    if (about_largest) {
        axis_[0] = order[0], axis_[1] = order[1], axis_[2] = order[2];
    } else {
        axis_[0] = order[2], axis_[1] = order[1], axis_[2] = order[0];
    }
    const double A = J[axis_[0]], B = J[axis_[1]], C = J[axis_[2]];
    const double w1 = omega0[axis_[0]], w2v = omega0[axis_[1]], w3 = omega0[axis_[2]];
    // 2TC − G² = A (C − A) ω1² + B (C − B) ω2² and G² − 2TA = B (B − A) ω2² + C (C − A) ω3², both
    // of the sign of C − A, from the components (no cancellation near a permanent rotation).
    const double across = A * (C - A) * w1 * w1 + B * (C - B) * w2v * w2v;
    const double along = B * (B - A) * w2v * w2v + C * (C - A) * w3 * w3;
    // Permanent rotation about axis 3' (or about the intermediate axis): ω stays constant.
    if (across == 0.0 || (w1 == 0.0 && w3 == 0.0)) {
        constant_ = true;
        return;
    }
    a_ = std::sqrt(across / (A * (C - A)));
    b_ = B == C ? 0.0 : std::sqrt(across / (B * (C - B)));
    c_ = std::sqrt(along / (C * (C - A)));
    m_ = std::clamp((B - A) * across / ((C - B) * along), 0.0, 1.0);
    if (!std::isfinite(m_)) m_ = 1.0;
    sign3_ = w3 >= 0.0 ? 1.0 : -1.0;
    // Parity of the relabelling (1', 2', 3'): a cyclic order keeps Euler's equations, an odd
    // one reverses the sign of their right-hand sides.
    const bool cyclic = (axis_[1] - axis_[0] + 3) % 3 == 1;
    const double parity = cyclic ? 1.0 : -1.0;
    nu_ = parity * sign3_ * (C - B) * b_ * c_ / (A * a_);
    const double phi0 = std::atan2(b_ > 0.0 ? w2v / b_ : 0.0, w1 / a_);
    u0_ = elliptic_F(phi0, m_);
    K_ = elliptic_K(m_);
}

TorqueFreeSolution::Reduced TorqueFreeSolution::reduced(double t) const {
    const double u = nu_ * (t - t0_) + u0_;
    double j = 0.0, r = u;
    if (std::isfinite(K_)) {
        j = std::round(u / (2.0 * K_));
        r = u - 2.0 * K_ * j;
        // |r| ≤ K up to rounding: clamp so that cn r ≥ 0
        r = std::clamp(r, -K_, K_);
    }
    const auto [sn, cn, dn] = jacobi_sn_cn_dn(r, m_);
    return {j, sn, std::max(cn, 0.0), dn};
}

Vec3 TorqueFreeSolution::omega(double t) const {
    if (constant_) return omega0_;
    const Reduced z = reduced(t);
    const double sign = std::fmod(std::abs(z.j), 2.0) == 1.0 ? -1.0 : 1.0;
    Vec3 w;
    w[axis_[0]] = a_ * sign * z.cn;
    w[axis_[1]] = b_ * sign * z.sn;
    w[axis_[2]] = sign3_ * c_ * z.dn;
    return w;
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
    if (constant_) return std::numeric_limits<double>::infinity();
    if (m_ >= 1.0) return std::numeric_limits<double>::infinity();
    return 4.0 * K_ / std::abs(nu_);
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

FreeBodyFlow::FreeBodyFlow(const Body& body, const Vec3& omega0, const Eigen::Vector4d& q0, double t0, bool attitude)
    : t0_(t0), omega0_(omega0), q0_(attitude ? unit_quaternion(q0) : Eigen::Vector4d(1, 0, 0, 0)) {
    require_closed_form(body, "FreeBodyFlow");
    require_finite(omega0, "FreeBodyFlow: omega0");
    if (!std::isfinite(t0)) throw std::invalid_argument("FreeBodyFlow: t0 = " + format_value(t0) + " is not finite");
    const Vec3& J = body.moments();
    const Vec3& k = body.rotor();
    const int axis = symmetry_axis(J);
    const Vec3 Gb = body.angular_momentum(omega0);
    if (axis >= 0) {  // symmetric or spherical, any axial rotor
        kind_ = Kind::Symmetric;
        const int transverse = axis == 3 ? 0 : (axis + 1) % 3;
        const double A = J[transverse];
        if (axis == 3) {
            lambda_ = k / A;
        } else {
            const double C = J[axis];
            lambda_ = Vec3::Zero();
            lambda_[axis] = ((C - A) * omega0[axis] + k[axis]) / A;
        }
        if (lambda_.squaredNorm() == 0.0) kind_ = Kind::Constant;
        precession_ = attitude ? Vec3(rotation_matrix(q0_) * Gb / A) : Vec3::Zero();
        return;
    }
    // Scale invariance of the free rigid body: ω(t; s ω̂0) = s ω(s t; ω̂0), and the attitude is a
    // function of s t. Working with ω̂0 = ω0/s, s = max|ω0_i|, keeps every square in the formulas
    // away from underflow (a decayed ω of 1e-160 would otherwise lose all its digits in ω²).
    scale_ = omega0.cwiseAbs().maxCoeff();
    if (scale_ == 0.0) {  // at rest
        kind_ = Kind::Constant;
        return;
    }
    const Vec3 unit = omega0 / scale_;
    elliptic_ = TorqueFreeSolution(body, unit, 0.0);
    if (elliptic_.is_constant()) {
        kind_ = Kind::Constant;
        return;
    }
    kind_ = Kind::Elliptic;
    const int* ax = elliptic_.axes();
    A_ = J[ax[0]], B_ = J[ax[1]], C_ = J[ax[2]];
    G_ = J.cwiseProduct(unit).norm();
    const double m = elliptic_.modulus_squared();
    N_ = -C_ * (B_ - A_) / (A_ * (C_ - B_));
    if (!std::isfinite(N_)) N_ = 0.0;  // B = C cannot reach here (symmetric)
    const bool cyclic = (ax[1] - ax[0] + 3) % 3 == 1;
    s_ = cyclic ? 1.0 : -1.0;
    S_.setZero();
    S_(0, ax[0]) = 1.0, S_(1, ax[1]) = s_, S_(2, ax[2]) = 1.0;
    if (!attitude) return;
    rate_ = G_ / C_;
    coeff_ = G_ * (C_ - A_) / (C_ * A_ * elliptic_.frequency());
    Pi_complete_ = m < 1.0 ? elliptic_Pi(N_, m) : 0.0;
    const TorqueFreeSolution::Reduced z0 = elliptic_.reduced(0.0);
    Pi0_ = 2.0 * z0.j * Pi_complete_ + elliptic_Pi_jacobi(z0.sn, z0.cn, z0.dn, N_, m);
    q_s_ = quaternion_from_matrix(S_);
    // q_in = q0 ⊗ q_S* ⊗ (q_x(θ0) ⊗ q_z(ψ0))*
    const Vec3 g = S_ * J.cwiseProduct(unit) / G_;
    const double sin_theta = std::hypot(g[0], g[1]);
    const double theta0 = std::atan2(sin_theta, g[2]);
    const double psi0 = std::atan2(A_ * elliptic_.a() * z0.cn, s_ * B_ * elliptic_.b() * z0.sn) - s_ * z0.j * M_PI;
    const Eigen::Vector4d qw0 = quaternion_product(q_x(theta0), q_z(psi0));
    q_in_ = quaternion_product(quaternion_product(q0_, conjugate(q_s_)), conjugate(qw0));
}

Vec3 FreeBodyFlow::omega(double t) const {
    switch (kind_) {
        case Kind::Constant: return omega0_;
        case Kind::Symmetric: return rotation_matrix(rotation_quaternion(lambda_ * (t - t0_))) * omega0_;
        case Kind::Elliptic: break;
    }
    return scale_ * elliptic_.omega(scale_ * (t - t0_));
}

Eigen::Vector4d FreeBodyFlow::quaternion(double t) const {
    const double dt = t - t0_;
    switch (kind_) {
        case Kind::Constant: return quaternion_product(q0_, rotation_quaternion(omega0_ * dt));
        case Kind::Symmetric:
            return quaternion_product(quaternion_product(rotation_quaternion(precession_ * dt), q0_),
                                      rotation_quaternion(-lambda_ * dt));
        case Kind::Elliptic: break;
    }
    const double m = elliptic_.modulus_squared();
    const TorqueFreeSolution::Reduced z = elliptic_.reduced(scale_ * dt);
    const double Pi = 2.0 * z.j * Pi_complete_ + elliptic_Pi_jacobi(z.sn, z.cn, z.dn, N_, m);
    const double dphi = rate_ * (scale_ * dt) + coeff_ * (Pi - Pi0_);
    // θ and ψ from ω(t) in primed axes (the same reduced sn, cn, dn)
    const double sign = std::fmod(std::abs(z.j), 2.0) == 1.0 ? -1.0 : 1.0;
    const double w1 = elliptic_.a() * sign * z.cn, w2 = s_ * elliptic_.b() * sign * z.sn;
    const double w3 = elliptic_.sign3() * elliptic_.c() * z.dn;
    const double sin_theta = std::hypot(A_ * w1, B_ * w2) / G_;
    const double theta = std::atan2(sin_theta, C_ * w3 / G_);
    const double psi = std::atan2(A_ * elliptic_.a() * z.cn, s_ * B_ * elliptic_.b() * z.sn) - s_ * z.j * M_PI;
    Eigen::Vector4d q = quaternion_product(q_in_, q_z(dphi));
    q = quaternion_product(q, q_x(theta));
    q = quaternion_product(q, q_z(psi));
    return quaternion_product(q, q_s_);
}

FreeBodyFlow::State FreeBodyFlow::at(double t) const {
    State y;
    y.head<3>() = omega(t);
    y.tail<4>() = quaternion(t);
    return y;
}

double FreeBodyFlow::period() const {
    switch (kind_) {
        case Kind::Constant: return std::numeric_limits<double>::infinity();
        case Kind::Symmetric: return 2.0 * M_PI / std::max(lambda_.norm(), precession_.norm());
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
