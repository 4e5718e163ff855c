#include "gyrostat/model/torque_free.hpp"

#include "gyrostat/model/elliptic.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>

namespace gyrostat::model {


TorqueFreeSolution::TorqueFreeSolution(const Body& body, const Vec3& omega0, double t0) : omega0_(omega0), t0_(t0) {
    if (body.rotor().squaredNorm() != 0.0)
        throw std::invalid_argument("TorqueFreeSolution: the closed form is for a rigid body (rotor k = 0); "
                                    "this body has |k| = " + std::to_string(body.rotor().norm()) +
                                    ": integrate the full model instead");
    require_finite(omega0, "TorqueFreeSolution: omega0");
    if (!std::isfinite(t0)) throw std::invalid_argument("TorqueFreeSolution: t0 is not finite");

    const Vec3& J = body.moments();
    const double G2 = J.cwiseProduct(omega0).squaredNorm();
    const double T2 = omega0.dot(J.cwiseProduct(omega0));  // 2T
    int order[3] = {0, 1, 2};
    std::sort(order, order + 3, [&](int i, int j) { return J[i] < J[j]; });
    const double tiny = 64.0 * std::numeric_limits<double>::epsilon();
    if (T2 == 0.0 || J[order[2]] - J[order[0]] <= tiny * J[order[2]]) {
        constant_ = true;  // at rest, or a spherical body
        return;
    }
    const double D = G2 / T2;  // lies in [A_min, A_max]
    const bool about_largest = D >= J[order[1]];
    if (about_largest) {
        axis_[0] = order[0], axis_[1] = order[1], axis_[2] = order[2];
    } else {
        axis_[0] = order[2], axis_[1] = order[1], axis_[2] = order[0];
    }
    const double A = J[axis_[0]], B = J[axis_[1]], C = J[axis_[2]];
    const double w1 = omega0[axis_[0]], w2 = omega0[axis_[1]], w3 = omega0[axis_[2]];
    const double across = T2 * C - G2;  // 2TC − G², same sign as C − A
    const double along = G2 - T2 * A;   // G² − 2TA, same sign as C − A
    // Permanent rotation about axis 3' (or about the intermediate axis): ω stays constant.
    if (std::abs(across) <= tiny * G2 || std::abs(w1) + std::abs(w2) == 0.0 ||
        (std::abs(w1) + std::abs(w3) == 0.0)) {
        constant_ = true;
        return;
    }
    a_ = std::sqrt(across / (A * (C - A)));
    b_ = std::sqrt(across / (B * (C - B)));
    c_ = std::sqrt(along / (C * (C - A)));
    m_ = std::clamp((B - A) * across / ((C - B) * along), 0.0, 1.0);
    sign3_ = w3 >= 0.0 ? 1.0 : -1.0;
    // Parity of the relabelling (1', 2', 3'): a cyclic order keeps Euler's equations, an odd
    // one reverses the sign of their right-hand sides.
    const bool cyclic = (axis_[1] - axis_[0] + 3) % 3 == 1;
    const double parity = cyclic ? 1.0 : -1.0;
    nu_ = parity * sign3_ * (C - B) * b_ * c_ / (A * a_);
    const double phi0 = std::atan2(w2 / b_, w1 / a_);
    u0_ = elliptic_F(phi0, m_);
}

Vec3 TorqueFreeSolution::omega(double t) const {
    if (constant_) return omega0_;
    const auto [sn, cn, dn] = jacobi_sn_cn_dn(nu_ * (t - t0_) + u0_, m_);
    Vec3 w;
    w[axis_[0]] = a_ * cn;
    w[axis_[1]] = b_ * sn;
    w[axis_[2]] = sign3_ * c_ * dn;
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
    return 4.0 * elliptic_K(m_) / std::abs(nu_);
}


TorqueFree::TorqueFree(Body body) : body_(std::move(body)) {
    if (body_.rotor().squaredNorm() != 0.0)
        throw std::invalid_argument("TorqueFree: the closed form is for a rigid body (rotor k = 0); this body has |k| = " +
                                    format_value(body_.rotor().norm()) + ": use the full Model (it integrates)");
}

}  // namespace gyrostat::model
