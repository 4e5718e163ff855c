// A cavity filled with a highly viscous fluid (Chernousko's small-Reynolds-number theory).
#pragma once

#include <Eigen/Core>
#include <array>
#include <cmath>
#include <cstdio>
#include <vector>
#include <stdexcept>

#include "gyrostat/body.hpp"
#include "gyrostat/euler_poinsot.hpp"
#include "gyrostat/torque/parameter.hpp"

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
    static constexpr const char* name = "viscous_cavity";
    static constexpr const char* python_name = "ViscousCavity";
    static constexpr const char* description = "a cavity filled with a highly viscous fluid";
    static constexpr std::array<Parameter, 4> parameters{{
        {"density", "density ρ", Shape::Scalar, "kg/m^3", "rho", Constraint::Positive},
        {"viscosity", "kinematic viscosity ν", Shape::Scalar, "m^2/s", "kinematic viscosity nu", Constraint::Positive},
        {"p0", "cavity coefficient P0", Shape::Scalar, "m^5", "P0 of the cavity tensor P = P0 I", Constraint::Positive, 1},
        {"radius", "cavity radius b", Shape::Scalar, "m", "radius of a spherical cavity", Constraint::Positive, 1, false},
    }};
    /// M is affine in these (a sensitivity's ∂f/∂p is then a one-sided difference, exact).
    static constexpr std::array<const char*, 2> affine_in{{"density", "p0"}};
    /// M ∝ 1/ν (κ = ρ P0/ν): a sensitivity's ∂f/∂ν is a one-sided difference too, scaled (torque/set.hpp).
    static constexpr std::array<const char*, 1> inverse_in{{"viscosity"}};

    double density = 0.0;    ///< ρ
    double viscosity = 0.0;  ///< ν (kinematic)
    double p0 = 0.0;         ///< P0 of P = P0·I

    ViscousCavity(double rho, double nu, double p) : density(rho), viscosity(nu), p0(p) {
        require(python_name, parameters[0], rho);
        require(python_name, parameters[1], nu);
        require(python_name, parameters[2], p);
    }
    /// A spherical cavity of radius b: P0 = 8π b⁷ / 525.
    static ViscousCavity sphere(double rho, double nu, double radius) {
        require(python_name, parameters[3], radius);
        return ViscousCavity(rho, nu, 8.0 * M_PI * std::pow(radius, 7) / 525.0);
    }
    static ViscousCavity from(const Values& v) {
        if (v.has("radius")) return sphere(v.scalar("density"), v.scalar("viscosity"), v.scalar("radius"));
        return ViscousCavity(v.scalar("density"), v.scalar("viscosity"), v.scalar("p0"));
    }
    Values values() const {
        Values v;
        v.set("density", density), v.set("viscosity", viscosity), v.set("p0", p0);
        return v;
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
    /// Its averaged power per axis ⟨ω_i M_i⟩ over the triaxial Euler–Poinsot motion (TorqueSet::
    /// averaged_power; docs/papers/triaxial_averaging.md §2(c)): with Q_ij = ⟨ω_i² ω_j²⟩
    /// (EulerPoinsot::mean_square_products, in K and E) and k = κ/(ABC),
    ///   ⟨p M_p⟩ = k (c0 Q_pr + c1 Q_pq),  ⟨q M_q⟩ = k (c2 Q_qp + c3 Q_qr),  ⟨r M_r⟩ = k (c4 Q_rq + c5 Q_rp);
    /// Σ J_i ⟨ω_i M_i⟩ = 0 (|G| kept) and Σ ⟨ω_i M_i⟩ ≤ 0.
    Vec3 averaged_power(double /*t*/, const EulerPoinsot& motion, const Vec3& J) const {
        const double k = kappa() / (J[0] * J[1] * J[2]);
        const Coefficients c = coefficients(J);
        const Mat3 Q = motion.mean_square_products();
        return {k * (c[0] * Q(0, 2) + c[1] * Q(0, 1)), k * (c[2] * Q(1, 0) + c[3] * Q(1, 2)),
                k * (c[4] * Q(2, 1) + c[5] * Q(2, 0))};
    }
    /// Commutes with rotations about body z (the cavity tensor is isotropic, P = P0 I).
    bool axisymmetric() const { return true; }
    /// Jω·M ≡ 0: |Jω| is kept (TorqueSet::keeps_momentum_norm; the splitting projects on it).
    static constexpr bool keeps_momentum_norm = true;

    /// Small Reynolds number Re = |ω| b²/ν (b: the sphere of the same P0) and a small
    /// perturbation κ|ω|/A_min, both against kSmall.
    std::vector<Assumption> assumptions(const Motion& motion) const {
        const double b = equivalent_radius();
        const double reynolds = motion.speed * b * b / viscosity;
        const double strength = kappa() * motion.speed / motion.moments.minCoeff();
        char note[64];
        std::snprintf(note, sizeof note, "b = %.4g (sphere of the same P0)", b);
        return {{"viscous cavity", "Reynolds number |ω| b²/ν ≪ 1", reynolds, kSmall, reynolds <= kSmall, note},
                {"viscous cavity", "cavity rate κ|ω|/A_min ≪ 1 (perturbation small)", strength, kSmall,
                 strength <= kSmall, ""}};
    }

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
};

}  // namespace gyrostat::torque
