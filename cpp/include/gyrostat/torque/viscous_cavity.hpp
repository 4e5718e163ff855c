// A cavity filled with a highly viscous fluid (Chernousko's small-Reynolds-number theory).
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <stdexcept>

#include "gyrostat/body.hpp"

namespace gyrostat::torque {

/// Torque of a cavity with fluid of density ρ and kinematic viscosity ν on the body, for a
/// cavity tensor P = P0·I (a sphere of radius b: P0 = 8π b⁷/525), κ = ρ P0 / ν
/// (paper 002 eq. (1), derived and checked in docs/papers/000_002_cavity_and_medium.md, T1):
///
///   M_p = κ/(ABC) · p · [ C(A−C)(A+C−B) r² + B(A−B)(A+B−C) q² ]
///   M_q = κ/(ABC) · q · [ A(B−A)(B+A−C) p² + C(B−C)(B+C−A) r² ]
///   M_r = κ/(ABC) · r · [ B(C−B)(C+B−A) q² + A(C−A)(C+A−B) p² ]
///
/// It conserves |Jω| (Jω·M ≡ 0) and dissipates energy. Averaged over the symmetric Euler–Poinsot
/// motion:  ȧ = κ C (A − C) r² a / A³,   ṙ = κ (C − A) a² r / (A C).
/// Assumptions: Reynolds number Re = |ω| b²/ν ≪ 1 (ν large, κ|ω|/A small); the validity check
/// reports Re with b the radius of the sphere of the same P0.
struct ViscousCavity {
    double density = 0.0;    ///< ρ
    double viscosity = 0.0;  ///< ν (kinematic)
    double p0 = 0.0;         ///< P0 of P = P0·I

    ViscousCavity(double rho, double nu, double p) : density(rho), viscosity(nu), p0(p) {
        check("density ρ", rho);
        check("kinematic viscosity ν", nu);
        check("cavity coefficient P0", p);
    }
    /// A spherical cavity of radius b: P0 = 8π b⁷ / 525.
    static ViscousCavity sphere(double rho, double nu, double radius) {
        check("cavity radius b", radius);
        return ViscousCavity(rho, nu, 8.0 * M_PI * std::pow(radius, 7) / 525.0);
    }
    /// Radius of the sphere with this P0.
    double equivalent_radius() const { return std::pow(525.0 * p0 / (8.0 * M_PI), 1.0 / 7.0); }
    double kappa() const { return density * p0 / viscosity; }

    Vec3 operator()(double /*t*/, const Vec3& w, const Vec3& J) const {
        const double A = J[0], B = J[1], C = J[2];
        const double k = kappa() / (A * B * C);
        const double p2 = w[0] * w[0], q2 = w[1] * w[1], r2 = w[2] * w[2];
        const Coefficients c = coefficients(J);
        return {k * w[0] * (c[0] * r2 + c[1] * q2), k * w[1] * (c[2] * p2 + c[3] * r2),
                k * w[2] * (c[4] * q2 + c[5] * p2)};
    }
    void add_jacobian(double /*t*/, const Vec3& w, const Vec3& J, Mat3& d) const {
        const double k = kappa() / (J[0] * J[1] * J[2]);
        const Coefficients c = coefficients(J);
        const double p = w[0], q = w[1], r = w[2];
        d(0, 0) += k * (c[0] * r * r + c[1] * q * q), d(0, 1) += k * 2 * c[1] * p * q, d(0, 2) += k * 2 * c[0] * p * r;
        d(1, 0) += k * 2 * c[2] * q * p, d(1, 1) += k * (c[2] * p * p + c[3] * r * r), d(1, 2) += k * 2 * c[3] * q * r;
        d(2, 0) += k * 2 * c[5] * r * p, d(2, 1) += k * 2 * c[4] * r * q, d(2, 2) += k * (c[4] * q * q + c[5] * p * p);
    }
    Eigen::Vector2d averaged(double /*t*/, double a, double r, double A, double C) const {
        const double k = kappa();
        return {k * C * (A - C) * r * r * a / (A * A * A), k * (C - A) * a * a * r / (A * C)};
    }
    static constexpr const char* name = "viscous_cavity";
    /// Jω·M ≡ 0: |Jω| is kept (TorqueSet::keeps_momentum_norm; the splitting projects on it).
    static constexpr bool keeps_momentum_norm = true;

private:
    using Coefficients = Eigen::Matrix<double, 6, 1>;
    /// (C(A−C)(A+C−B), B(A−B)(A+B−C), A(B−A)(B+A−C), C(B−C)(B+C−A), B(C−B)(C+B−A), A(C−A)(C+A−B)).
    static Coefficients coefficients(const Vec3& J) {
        const double A = J[0], B = J[1], C = J[2];
        Eigen::Matrix<double, 6, 1> c;
        c << C * (A - C) * (A + C - B), B * (A - B) * (A + B - C), A * (B - A) * (B + A - C), C * (B - C) * (B + C - A),
            B * (C - B) * (C + B - A), A * (C - A) * (C + A - B);
        return c;
    }
    static void check(const char* what, double value) {
        if (!std::isfinite(value) || !(value > 0.0))
            throw std::invalid_argument(std::string("ViscousCavity: ") + what + " = " + format_value(value) +
                                        " must be finite and positive");
    }
};

}  // namespace gyrostat::torque
