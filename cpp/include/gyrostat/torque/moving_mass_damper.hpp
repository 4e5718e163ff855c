// The moving mass on a viscoelastic damper, in Chernousko's quasi-static (reduced) form.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cmath>
#include <limits>
#include <vector>
#include <stdexcept>

#include "gyrostat/body.hpp"
#include "gyrostat/torque/parameter.hpp"

namespace gyrostat::torque {

/// A point mass on an isotropic spring (Ω² = c/μ) with a viscous damper (λ = δ/μ), attached on
/// the body's z principal axis at distance ρ; μ is the (reduced) mass. When the mass follows
/// the body quasi-statically (Ω² ≫ λ|ν| and Ω² ≫ |ω|², ν = (C − A) r / A the body-frame
/// precession rate), it exerts the torque M = T_L + T_S with kL = μρ²/Ω², kS = μρ²λ/Ω⁴.
///
/// Symmetric body (A = B), paper 001 eqs. (2)–(3):
///   L = kL C (A² p² + A² q² + C² r²)/A³,  S = kS C³ (A − C)/A⁴,
///   T_L = (L q r, −L p r, 0),  T_S = (S p r⁴, S q r⁴, −(A/C) S r³ (p² + q²)).
/// A, B, C are the whole system's moments with the mass at rest. For a triaxial body the exact
/// expansion of the same reduction is used (docs/papers/001_moving_mass.md §B(i-b); it reduces
/// to the above at B = A). T_L is conservative; T_S keeps |G| (symmetric body) and dissipates.
///
/// Averaged over the symmetric Euler–Poinsot motion: ȧ = S r⁴ a / A, ṙ = −(A/C²) S r³ a²
/// (T_L only shifts the phase). The sign of S is that of A − C: the damper destabilises rotation
/// about the axis of least inertia.
///
/// Assumptions (reported by the validity check): λ|ν|/Ω² ≪ 1 and |G|²/(A²Ω²) ≪ 1 (the
/// reduction's error grows like these, docs/papers/001_moving_mass.md §E); the paper's own
/// condition (4), Ω² ≫ λ|ω| ≫ |ω|², is reported as printed.
struct MovingMassDamper {
    static constexpr const char* name = "moving_mass_damper";
    static constexpr const char* python_name = "MovingMassDamper";
    static constexpr const char* description = "Chernousko's quasi-static moving-mass damper";
    static constexpr std::array<Parameter, 4> parameters{{
        {"mass", "mass m", Shape::Scalar, "kg", "mass m", Constraint::Positive},
        {"arm", "arm rho", Shape::Scalar, "m", "distance rho of the mass on the z axis", Constraint::NonNegative},
        {"frequency", "frequency Omega", Shape::Scalar, "rad/s", "Omega = sqrt(c/m)", Constraint::Positive},
        {"damping", "damping lambda", Shape::Scalar, "1/s", "lambda = delta/m", Constraint::NonNegative},
    }};

    double mass = 0.0;       ///< μ (reduced mass; m when the carrier is much heavier)
    double arm = 0.0;        ///< ρ, distance of the attachment point along z
    double frequency = 0.0;  ///< Ω, natural frequency of the spring (Ω² = c/μ)
    double damping = 0.0;    ///< λ = δ/μ

    MovingMassDamper(double m, double rho, double omega, double lambda)
        : mass(m), arm(rho), frequency(omega), damping(lambda) {
        require(python_name, parameters[0], m);
        require(python_name, parameters[1], rho);
        require(python_name, parameters[2], omega);
        require(python_name, parameters[3], lambda);
    }
    static MovingMassDamper from(const Values& v) {
        return MovingMassDamper(v.scalar("mass"), v.scalar("arm"), v.scalar("frequency"), v.scalar("damping"));
    }
    Values values() const {
        Values v;
        v.set("mass", mass), v.set("arm", arm), v.set("frequency", frequency), v.set("damping", damping);
        return v;
    }
    double kL() const { return mass * arm * arm / (frequency * frequency); }
    /// S of paper 001 eq. (3) for a symmetric body (A, A, C).
    double S(double A, double C) const {
        const double omega2 = frequency * frequency;
        return mass * arm * arm * damping / (omega2 * omega2) * C * C * C * (A - C) / (A * A * A * A);
    }

    /// The coefficients of the torque's monomials in (p, q, r) for the moments J = (A, B, C) (kL and
    /// kS included): M_x = q r (l0·(p², q², r²)) + p s0·(q²r², p²q², p²r², r⁴, q⁴),
    /// M_y = p r (l1·(p², q², r²)) + q s1·(p²r², p²q², q²r², r⁴, p⁴), M_z = r s2·(p²r², q²r²).
    struct Coefficients {
        Vec3 moments{0.0, 0.0, 0.0};  ///< the J they are for (0: none)
        std::array<double, 3> l0{}, l1{};
        std::array<double, 5> s0{}, s1{};
        std::array<double, 2> s2{};
    };
    Coefficients coefficients(const Vec3& J) const {
        const double A = J[0], B = J[1], C = J[2];
        const double A2 = A * A, A3 = A2 * A, A4 = A3 * A, B2 = B * B, B3 = B2 * B, B4 = B3 * B;
        const double C2 = C * C, C3 = C2 * C, C4 = C3 * C;
        const double mass_arm2 = mass * arm * arm, omega2 = frequency * frequency;
        auto sq = [](double x) { return x * x; };
        const double kL = mass_arm2 / omega2;
        const double kS = mass_arm2 * damping / (omega2 * omega2);
        Coefficients c;
        c.moments = J;
        // T_L,x = kL q r (p² (…)/(ABC) − (q² (…) + r² (…))/(A²BC))
        c.l0 = {kL * (7*A3 - 14*A2*B + 2*A2*C + 7*A*B2 + 8*A*B*C - 9*A*C2 - 10*B2*C + 10*B*C2) / (A*B*C),
                -kL * (A2*B2 - 2*A2*B*C - 2*A*B3 + 4*A*B2*C - 2*A*B*C2 + B4 - 2*B3*C + B2*C2) / (A2*B*C),
                -kL * (-4*A2*B*C + 3*A2*C2 + 4*A*B2*C - 2*A*B*C2 - 2*A*C3 - B2*C2 + 2*B*C3 - C4) / (A2*B*C)};
        // T_L,y = kL p r (−q² (…)/(ABC) + (p² (…) + r² (…))/(AB²C))
        c.l1 = {kL * (A4 - 2*A3*B - 2*A3*C + A2*B2 + 4*A2*B*C + A2*C2 - 2*A*B2*C - 2*A*B*C2) / (A*B2*C),
                -kL * (7*A2*B - 10*A2*C - 14*A*B2 + 8*A*B*C + 10*A*C2 + 7*B3 + 2*B2*C - 9*B*C2) / (A*B*C),
                kL * (4*A2*B*C - A2*C2 - 4*A*B2*C - 2*A*B*C2 + 2*A*C3 + 3*B2*C2 - 2*B*C3 - C4) / (A*B2*C)};
        // T_S,x = kS p (−2q²r²(A−B)(…)/(A²BC) − p²q²(A−B)(…)/(ABC²) + 2p²r²(A−B)(A−C)(…)/(AB²C)
        //              + r⁴(A−C)(…)/(A²B²) + q⁴B(A−B)(A−B+C)²/(A²C²))
        c.s0 = {-kS * 2*(A - B)*(12*A2*B - 13*A2*C - 12*A*B2 + 10*A*B*C + 2*A*C2 + 11*B2*C - 22*B*C2 + 11*C3) / (A2*B*C),
                -kS * (A - B)*(5*A3 - 10*A2*B + 4*A2*C + 5*A*B2 + 4*A*B*C - 9*A*C2 - 8*B2*C + 8*B*C2) / (A*B*C2),
                kS * 2*(A - B)*(A - C)*(3*A2 - 3*A*B + A*C + 4*B*C - 4*C2) / (A*B2*C),
                kS * (A - C)*(4*A2*B - 3*A2*C - 4*A*B2 + 2*A*B*C + 2*A*C2 + B2*C - 2*B*C2 + C3) / (A2*B2),
                kS * B*(A - B)*sq(A - B + C) / (A2*C2)};
        // T_S,y = kS q (−2p²r²(A−B)(…)/(AB²C) + p²q²(A−B)(…)/(ABC²) + 2q²r²(A−B)(B−C)(…)/(A²BC)
        //              − r⁴(B−C)(…)/(A²B²) − p⁴A(A−B)(A−B−C)²/(B²C²))
        c.s1 = {-kS * 2*(A - B)*(12*A2*B - 11*A2*C - 12*A*B2 - 10*A*B*C + 22*A*C2 + 13*B2*C - 2*B*C2 - 11*C3) / (A*B2*C),
                kS * (A - B)*(5*A2*B - 8*A2*C - 10*A*B2 + 4*A*B*C + 8*A*C2 + 5*B3 + 4*B2*C - 9*B*C2) / (A*B*C2),
                kS * 2*(A - B)*(B - C)*(3*A*B - 4*A*C - 3*B2 - B*C + 4*C2) / (A2*B*C),
                -kS * (B - C)*(4*A2*B - A2*C - 4*A*B2 - 2*A*B*C + 2*A*C2 + 3*B2*C - 2*B*C2 - C3) / (A2*B2),
                -kS * A*(A - B)*sq(A - B - C) / (B2*C2)};
        // T_S,z = kS r (A−B−C)(A−B+C) (p²r²(A−C)/(AB²) + q²r²(B−C)/(A²B))
        const double common = kS * (A - B - C) * (A - B + C);
        c.s2 = {common * (A - C) / (A*B2), common * (B - C) / (A2*B)};
        return c;
    }
    /// The coefficients for the moments of the model it acts in, made once (TorqueSet::in_principal_axes:
    /// a torque with `prepared` is given the body's moments there); the torque is evaluated at
    /// other moments too (from Python, say), then from coefficients made on the call.
    MovingMassDamper prepared(const Vec3& J) const {
        MovingMassDamper ready = *this;
        ready.prepared_ = coefficients(J);
        return ready;
    }

    Vec3 operator()(double /*t*/, const Vec3& w, const Vec3& J) const {
        if (J == prepared_.moments) return torque(w, prepared_);
        return torque(w, coefficients(J));
    }
    /// ∂M/∂ω by central differences (the polynomial is long; the step is relative, ~1e-6·|ω|).
    void add_jacobian(double t, const Vec3& w, const Vec3& J, Mat3& d) const {
        const double h = 1e-6 * std::max(1.0, w.cwiseAbs().maxCoeff());
        for (int j = 0; j < 3; ++j) {
            Vec3 plus = w, minus = w;
            plus[j] += h;
            minus[j] -= h;
            d.col(j) += ((*this)(t, plus, J) - (*this)(t, minus, J)) / (2.0 * h);
        }
    }
    Eigen::Vector2d averaged(double /*t*/, double a, double r, double A, double C) const {
        const double s = S(A, C), r3 = r * r * r;
        return {s * r3 * r * a / A, -(A / (C * C)) * s * r3 * a * a};
    }
    /// Commutes with rotations about body z (the mass sits on the z axis, the spring is isotropic).
    bool axisymmetric() const { return true; }

    /// The quasi-static reduction's conditions λ|ν|/Ω² ≪ 1 and |G|²/(A²Ω²) ≪ 1, and paper 001's
    /// condition (4) as printed (Ω² ≫ λ|ω| ≫ |ω|², not needed for (a, r)).
    std::vector<Assumption> assumptions(const Motion& motion) const {
        const double omega2 = frequency * frequency, A = motion.moments[0];
        const double lag = damping * motion.axial_frequency / omega2;
        const double inertial = motion.momentum * motion.momentum / (A * A * omega2);
        const double inf = std::numeric_limits<double>::infinity();
        const double first = damping * motion.speed > 0 ? omega2 / (damping * motion.speed) : inf;
        const double second = motion.speed > 0 ? damping / motion.speed : inf;
        const char* printed = "as printed; not needed for (a, r)";
        return {{"moving-mass damper", "λ|ν|/Ω² ≪ 1 (quasi-static lag, ν = (C−A)r/A)", lag, kSmall, lag <= kSmall, ""},
                {"moving-mass damper", "|G|²/(A²Ω²) ≪ 1 (inertial corrections)", inertial, kSmall, inertial <= kSmall, ""},
                {"moving-mass damper", "paper 001 condition (4): Ω²/(λ|ω|) ≫ 1", first, kLarge, first >= kLarge, printed},
                {"moving-mass damper", "paper 001 condition (4): λ|ω|/|ω|² ≫ 1", second, kLarge, second >= kLarge, printed}};
    }

private:
    static Vec3 torque(const Vec3& w, const Coefficients& c) {
        const double p = w[0], q = w[1], r = w[2];
        const double p2 = p * p, q2 = q * q, r2 = r * r;
        const double q2r2 = q2 * r2, p2q2 = p2 * q2, p2r2 = p2 * r2;
        const double TL0 = q * r * (c.l0[0] * p2 + c.l0[1] * q2 + c.l0[2] * r2);
        const double TL1 = p * r * (c.l1[0] * p2 + c.l1[1] * q2 + c.l1[2] * r2);
        const double TS0 = p * (c.s0[0] * q2r2 + c.s0[1] * p2q2 + c.s0[2] * p2r2 + c.s0[3] * r2 * r2 + c.s0[4] * q2 * q2);
        const double TS1 = q * (c.s1[0] * p2r2 + c.s1[1] * p2q2 + c.s1[2] * q2r2 + c.s1[3] * r2 * r2 + c.s1[4] * p2 * p2);
        const double TS2 = r * (c.s2[0] * p2r2 + c.s2[1] * q2r2);
        return {TL0 + TS0, TL1 + TS1, TS2};
    }

    Coefficients prepared_;  ///< for prepared_.moments (none: 0)
};

}  // namespace gyrostat::torque
