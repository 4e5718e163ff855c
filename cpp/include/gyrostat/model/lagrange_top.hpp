// Paper 003: a heavy dynamically symmetric top about a fixed point on its axis (Lagrange case)
// under small perturbation torques; its classical unperturbed solution in Jacobi sn.
#pragma once

#include <algorithm>
#include <array>
#include <iterator>
#include <cmath>
#include <stdexcept>
#include <utility>

#include "gyrostat/attitude.hpp"
#include "gyrostat/body.hpp"
#include "gyrostat/numeric/elliptic.hpp"
#include "gyrostat/model/system.hpp"
#include "gyrostat/model/torque_free.hpp"
#include "gyrostat/torque/set.hpp"

namespace gyrostat::model {

/// The nutation of the unperturbed top in terms of its first integrals (G_z, H, r).
///
///   f(u) = A (2H − C r² − 2μu)(1 − u²) − (G_z − C r u)² = 2μA (u − u1)(u − u2)(u − u3),
///   −1 ≤ u1 ≤ u2 ≤ 1 ≤ u3,   u = cos θ ∈ [u1, u2],
///   u(t) = u1 + (u2 − u1) sn²(α t + β | m),  m = k² = (u2 − u1)/(u3 − u1),  α = √(μ(u3 − u1)/(2A)),
///   period of u:  T = 2K(m)/α  (the paper prints K/α after (1.3): see docs/papers/003),
///   ⟨u⟩ = v = u1 + (u2 − u1) W(m) = u3 − (u3 − u1) E/K.
struct Nutation {
    double u1 = 0.0, u2 = 0.0, u3 = 0.0;
    double m = 0.0;       ///< k², clamped to [0, 1]
    double alpha = 0.0;   ///< rate of the sn argument
    double v = 0.0;       ///< ⟨cos θ⟩ over the nutation
    double period = 0.0;  ///< 2K(m)/α (+∞ at the separatrix m = 1 or at the triple root α = 0)
};

/// Roots of the cubic, k², α, v from (G_z, H, r): u3 by Newton's iteration from 2 + max|s_i|
/// down onto the last sign change on [1, 2 + max|s_i|] of the factored f (f(1) = −(G_z − C r)² ≤ 0
/// exactly), closed by regula falsi onto adjacent doubles, then deflation u1 + u2 = s1 − u3,
/// u1 u2 = s3/u3 (u3 ≥ 1). Throws std::invalid_argument for non-finite input or no root.
Nutation nutation(double A, double C, double mu, double Gz, double H, double r);

/// The derivatives of v = ⟨cos θ⟩ (Nutation) with respect to G_z, H, r and μ, at fixed A and C.
///
/// Each root moves as ∂u_i/∂θ = g_θ(u_i)/∏_{j≠i}(u_i − u_j), g_θ = −(∂f/∂θ)/(2μA) a polynomial in u:
///   g_H = (u² − 1)/μ,  g_Gz = (G_z − C r u)/(μA),  g_r = (A C r − C G_z u + C r (C − A) u²)/(μA),
///   g_μ = (u − u³)/μ.
/// With v = u1 + (u2 − u1) W(m), W = (K − E)/(m K), m = (u2 − u1)/D, D = u3 − u1, the weights
/// w_i = ∂v/∂u_i are w1 = 1 − W − m(1 − m)W', w2 = W + m W', w3 = −m² W', where
/// W' = (Z + W²)/(2(1 − m)) and Z = (1 − 2W)/m (its Taylor series below m = 0.05). As u2 → u1
/// (regular precession, m → 0) ∂u1/∂θ and ∂u2/∂θ grow as 1/(u2 − u1) with opposite signs; written
/// with a = (w1 + w2)/2 = (1 + m² W')/2 and (w1 − w2)/m = Z − (2 − m)W', the sum
///   ∂v/∂θ = a (g[u1, u2, u3] − t3) − (Z − (2 − m)W')/(2D) (g(u1)/(u1 − u3) + g(u2)/(u2 − u3)) + w3 t3,
///   t3 = g(u3)/((u3 − u1)(u3 − u2)),  g[u1, u2, u3] = c2 + c3 (u1 + u2 + u3) (g's second divided difference),
/// has no division by u2 − u1 and is exact at m = 0. At the separatrix (m → 1) W' grows as v's
/// slope does (log-singular). Checked against mpmath in tests/test_lagrange_sensitivity_slopes.py.
struct NutationSlopes {
    double Gz = 0.0, H = 0.0, r = 0.0, mu = 0.0;
};
NutationSlopes nutation_slopes(double A, double C, double mu, double Gz, double H, double r, const Nutation& n);

/// Throws std::invalid_argument naming (G_z, H, r) when no motion of the top has them: when
/// f(u) < 0 for every u = cos θ in [−1, 1] (then p² + q² < 0).
void check_reachable(double A, double C, double mu, double Gz, double H, double r);

/// The unperturbed top from an initial state (ω, γ) at t0 (γ: upward vertical in body axes):
/// u(t) = cos θ(t) in closed form, β = ±F(arcsin √((u0 − u1)/(u2 − u1)) | m), sign of u̇0 = γ1 q − γ2 p.
class LagrangeUnperturbed {
public:
    LagrangeUnperturbed(double A, double C, double mu, const Vec3& omega, const Vec3& gamma, double t0 = 0.0);
    double u(double t) const;
    const Nutation& nutation() const { return n_; }
    double Gz() const { return Gz_; }
    double H() const { return H_; }
    double r() const { return r_; }
    double beta() const { return beta_; }

private:
    Nutation n_;
    double Gz_ = 0.0, H_ = 0.0, r_ = 0.0, beta_ = 0.0, t0_ = 0.0;
};

/// Upward vertical in body axes from the body→space quaternion (w, x, y, z): third row of R(Q).
inline Vec3 vertical_in_body(double w, double x, double y, double z) {
    return {2.0 * (x * z - w * y), 2.0 * (y * z + w * x), 1.0 - 2.0 * (x * x + y * y)};
}

/// Heavy symmetric top (A1 = A2 = A, A3 = C) about a fixed point O on its axis, centre of mass
/// at distance l on +z, μ = m g l > 0, plus the torques of a TorqueSet.
///
/// State y = (p, q, r, Q_w, Q_x, Q_y, Q_z): ω in body axes and the unit quaternion Q rotating
/// body axes into space axes (z up). No Euler angles: nothing is singular at θ = 0 or π.
/// γ = upward vertical in body axes = third row of R(Q) (vertical_in_body). Gravity torque
/// about O: l e_z × (−m g γ) = μ (γ2, −γ1, 0).
///
///   A ṗ = (A − C) q r + μ γ2 + M1(t, ω)
///   A q̇ = (C − A) p r − μ γ1 + M2(t, ω)
///   C ṙ =                      M3(t, ω)
///   Q̇  = ½ Q ⊗ (0, ω)
///
/// With γ = (sin θ sin φ, sin θ cos φ, cos θ) (z-x-z Euler angles) this is the paper's (1.1).
/// Paper 003's torque (3.1) M = ε(−a(τ)p, −a(τ)q, −b(τ)r), τ = εt, is a ResistiveMedium with
/// D_0 = ε diag(a0, a0, b0), D_1 = ε² diag(a1, a1, b1).
///
/// Outputs recorded (the first integrals of the unperturbed top, paper (1.2), then what the
/// nutation cubic gives at them, then the attitude):
///   G_z = A (p γ1 + q γ2) + C r γ3        (vertical angular momentum; dG_z/dt = M·γ),
///   H   = ½ (A (p² + q²) + C r²) + μ γ3    (energy; dH/dt = M·ω),
///   kinetic_energy = ½ (A (p² + q²) + C r²),
///   u1 ≤ u2 ≤ u3, k² = m, v = ⟨cos θ⟩, T_nut = 2K(m)/α at (G_z, H, r) (Nutation),
///   cos_theta = γ3 and its rate d(cos θ)/dt = γ̇3 = γ1 q − γ2 p (γ̇ = γ × ω; zero at the turning
///   points of the nutation), and the z-x-z Euler angles ψ, θ, φ of Q.
/// (r, the axial spin, C dr/dt = M3, is a state.)
class LagrangeTop {
public:
    static constexpr int dim = 7;
    using State = Eigen::Matrix<double, 7, 1>;
    static constexpr const char* family = "lagrange_top";
    static constexpr auto states = rate_states<true>();
    static constexpr bool carries_attitude = true;
    /// Its own numbers (as gyrostat.sensitivity names them) whose ∂f/∂p it gives in closed form
    /// (system::has_parameter_rate, parameter_rate below): μ.
    static constexpr std::array<const char*, 1> analytic_in{{"mu"}};

    LagrangeTop(Body body, double mu, TorqueSet torques) : body_(std::move(body)), torques_(torques.in_principal_axes(body)), mu_(mu) {
        const Vec3& J = body_.moments();
        if (J[0] != J[1])
            throw std::invalid_argument("LagrangeTop: the top must be dynamically symmetric (A1 = A2); got A1 = " +
                                        format_value(J[0]) + ", A2 = " + format_value(J[1]));
        if (!body_.principal())
            throw std::invalid_argument(
                "LagrangeTop: give the top by its principal moments (A, A, C): its centre of mass lies on its "
                "symmetry axis z, which a body given by an inertia tensor with products of inertia does not place");
        if (body_.rotor().squaredNorm() != 0.0)
            throw std::invalid_argument("LagrangeTop: a rigid top has no rotor; got |k| = " +
                                        format_value(body_.rotor().norm()));
        if (!(mu > 0.0) || !std::isfinite(mu))
            throw std::invalid_argument("LagrangeTop: mu = m g l must be positive and finite; got mu = " +
                                        format_value(mu));
        A_ = J[0];
        C_ = J[2];
    }

    const Body& body() const { return body_; }
    const TorqueSet& torques() const { return torques_; }
    double A() const { return A_; }
    double C() const { return C_; }
    double mu() const { return mu_; }
    bool supports_taylor() const { return false; }

    /// The equations in the block comment above the class.
    void rhs(double t, const State& y, State& dy) const {
        const double p = y[0], q = y[1], r = y[2];
        const double w = y[3], x = y[4], yy = y[5], z = y[6];
        const Vec3 g = vertical_in_body(w, x, yy, z);
        const Eigen::Vector4d attitude(w, x, yy, z);
        const Vec3 M = torques_.empty() ? Vec3::Zero() : torques_.total(t, Vec3(p, q, r), body_.moments(), &attitude);
        dy[0] = ((A_ - C_) * q * r + mu_ * g[1] + M[0]) / A_;
        dy[1] = ((C_ - A_) * p * r - mu_ * g[0] + M[1]) / A_;
        dy[2] = M[2] / C_;
        dy.template segment<4>(3) = quaternion_rate(y.template segment<4>(3), Vec3(p, q, r));
    }

    /// ∂f/∂μ (k = 0, the one number of analytic_in): gravity's moment over μ, (γ2, −γ1, 0)/A in the
    /// Euler rows; the quaternion's rows do not hold μ.
    void parameter_rate(std::size_t /*k*/, double /*t*/, const State& y, State& rate) const {
        const Vec3 g = vertical_in_body(y[3], y[4], y[5], y[6]);
        rate.setZero();
        rate[0] = g[1] / A_;
        rate[1] = -g[0] / A_;
    }

    /// ∂f/∂y of the equations above: the Euler rows through (A − C) q r / A, the gravity torque
    /// through γ(Q) (∂γ1/∂(w, x, y, z) = 2(−y, z, −w, x), ∂γ2/∂(w, x, y, z) = 2(x, w, z, y)) and the
    /// torques through their own ∂M/∂ω and, those that read the attitude, ∂M/∂Q
    /// (TorqueSet::add_attitude_jacobian); the quaternion rows as in quaternion_rate_jacobian.
    using Jacobian = Eigen::Matrix<double, 7, 7>;
    void jacobian(double t, const State& y, Jacobian& jac) const {
        const double p = y[0], q = y[1], r = y[2];
        const double w = y[3], x = y[4], yy = y[5], z = y[6];
        jac.setZero();
        if (!torques_.empty()) {
            const Eigen::Vector4d attitude(w, x, yy, z);
            const Mat3 dM = torques_.jacobian(t, Vec3(p, q, r), body_.moments(), &attitude);
            jac.template block<2, 3>(0, 0) = dM.template topRows<2>() / A_;
            jac.template block<1, 3>(2, 0) = dM.row(2) / C_;
        }
        jac(0, 1) += (A_ - C_) * r / A_;
        jac(0, 2) += (A_ - C_) * q / A_;
        jac(1, 0) += (C_ - A_) * r / A_;
        jac(1, 2) += (C_ - A_) * p / A_;
        const double k = 2.0 * mu_ / A_;
        jac.template block<1, 4>(0, 3) << k * x, k * w, k * z, k * yy;          //  μ ∂γ2/∂Q / A
        jac.template block<1, 4>(1, 3) << k * yy, -k * z, k * w, -k * x;        // −μ ∂γ1/∂Q / A
        Eigen::Matrix<double, 3, 4> dM_dQ = Eigen::Matrix<double, 3, 4>::Zero();
        if (torques_.add_attitude_jacobian(t, Vec3(p, q, r), body_.moments(), Eigen::Vector4d(w, x, yy, z), dM_dQ)) {
            jac.template block<2, 4>(0, 3) += dM_dQ.template topRows<2>() / A_;
            jac.template block<1, 4>(2, 3) += dM_dQ.row(2) / C_;
        }
        quaternion_rate_jacobian(jac, 3, y.template segment<4>(3), Vec3(p, q, r));
    }

    /// f and ∂f/∂y · s_j for every column s_j at once (system::has_rate_with_products: the
    /// variational equations, model/variational.hpp), from the Jacobian's terms above without
    /// forming it: the torques, their ∂M/∂ω and the attitude torques' ∂M/∂Q once, then
    ///   A ∂ṗ · s = ΣM_ω s_ω + ΣM_Q s_Q + (A − C)(r s_q + q s_r) + 2μ (x s_w + w s_x + z s_y + y s_z),
    ///   A ∂q̇ · s = … + (C − A)(r s_p + p s_r) + 2μ (y s_w − z s_x + w s_y − x s_z),
    ///   C ∂ṙ · s = ΣM_ω s_ω + ΣM_Q s_Q,     ∂Q̇ · s = ½ (s_Q ⊗ (0, ω) + Q ⊗ (0, s_ω));  f by rhs's own operations.
    bool rate_with_products(double t, const State& y, const double* columns, std::size_t count, State& f,
                            double* products) const {
        const double p = y[0], q = y[1], r = y[2];
        const double w = y[3], x = y[4], yy = y[5], z = y[6];
        const Vec3 omega(p, q, r);
        const Vec3 g = vertical_in_body(w, x, yy, z);
        const Eigen::Vector4d attitude(w, x, yy, z);
        const Vec3 M = torques_.empty() ? Vec3::Zero() : torques_.total(t, omega, body_.moments(), &attitude);
        f[0] = ((A_ - C_) * q * r + mu_ * g[1] + M[0]) / A_;
        f[1] = ((C_ - A_) * p * r - mu_ * g[0] + M[1]) / A_;
        f[2] = M[2] / C_;
        f.template segment<4>(3) = quaternion_rate(attitude, omega);
        Mat3 dM = Mat3::Zero();
        Eigen::Matrix<double, 3, 4> dM_dQ = Eigen::Matrix<double, 3, 4>::Zero();
        bool reads_attitude = false;
        if (!torques_.empty()) {
            dM = torques_.jacobian(t, omega, body_.moments(), &attitude);
            reads_attitude = torques_.add_attitude_jacobian(t, omega, body_.moments(), attitude, dM_dQ);
        }
        for (std::size_t j = 0; j < count; ++j) {
            const Eigen::Map<const State> s(columns + j * dim);
            Eigen::Map<State> product(products + j * dim);
            const Vec3 s_omega = s.template head<3>();
            const Eigen::Vector4d s_attitude = s.template segment<4>(3);
            Vec3 d_moment = dM * s_omega;
            if (reads_attitude) d_moment += dM_dQ * s_attitude;
            const double k = 2.0 * mu_;
            product[0] = (d_moment[0] + (A_ - C_) * (r * s[1] + q * s[2]) +
                          k * (x * s[3] + w * s[4] + z * s[5] + yy * s[6])) / A_;
            product[1] = (d_moment[1] + (C_ - A_) * (r * s[0] + p * s[2]) +
                          k * (yy * s[3] - z * s[4] + w * s[5] - x * s[6])) / A_;
            product[2] = d_moment[2] / C_;
            product.template segment<4>(3) = quaternion_rate(s_attitude, omega) + quaternion_rate(attitude, s_omega);
        }
        return true;
    }

    // --- Splitting (integrate/splitting.hpp) ---------------------------------------------------
    // f = f_free + f_pert with
    //   f_free: A ṗ = (A − C) q r,  A q̇ = (C − A) p r,  C ṙ = 0,  Q̇ = ½ Q ⊗ (0, ω)
    //           the free symmetric top, exact (FreeBodyFlow, the symmetric closed form);
    //   f_pert: J ω̇ = μ (γ2, −γ1, 0) + ΣM(t, ω),  Q̇ = 0
    //           gravity and the torques with Q (so γ) and t frozen: gravity is a constant torque
    //           over the sub-step, so with constant and linear torques the flow is exact
    //           (integrate::AffineRateFlow); with any other torque it is one 8th-order step.
    // The classical splitting of the heavy top into the free top and the gravity kick. The free
    // flow keeps the inertial G and the kick changes it by a horizontal torque (e_z × γ-direction
    // in space), so without torques G_z and r are kept to rounding at any step size.

    /// The free top always has a closed form (symmetric, no rotor); the check names the body if not.
    void require_splitting() const { FreeBodyFlow::require_closed_form(body_, "splitting"); }
    /// y ← the exact flow of the free symmetric top over h (double constants, as for the gyrostat).
    void free_flow(double h, State& y) const {
        const FreeBodyFlow flow(body_, y.template head<3>(), y.template segment<4>(3), 0.0, true, Phases::Double);
        y = flow.at(h);
    }
    /// The perturbation (model/system.hpp): the torques, and gravity's moment μ (γ2, −γ1, 0) at
    /// the attitude frozen over the sub-step.
    Vec3 frozen_moment(const State& y) const {
        const Vec3 g = vertical_in_body(y[3], y[4], y[5], y[6]);
        return Vec3(mu_ * g[1], -mu_ * g[0], 0.0);
    }

    /// Keeps |Q| = 1 to rounding (so |γ| = 1).
    void project(State& y) const { normalize_in_place(y.template segment<4>(3)); }
    void check_state(const State& y) const { check_quaternion(y.template segment<4>(3), "LagrangeTop"); }

    /// (G_z, H, r) of a state: the slow variables of the averaged top.
    Vec3 first_integrals(const State& y) const {
        const Vec3 g = vertical_in_body(y[3], y[4], y[5], y[6]);
        return {A_ * (y[0] * g[0] + y[1] * g[1]) + C_ * y[2] * g[2],
                0.5 * (A_ * (y[0] * y[0] + y[1] * y[1]) + C_ * y[2] * y[2]) + mu_ * g[2], y[2]};
    }

    static constexpr std::array<OutputInfo, 12> own_outputs{{{"G_z", "kg m^2/s", "the angular momentum about the vertical", true, true},
                                                             {"H", "J", "the top's energy, rotation plus gravity", true, true},
                                                             {"kinetic_energy", "J", "T = omega . J omega / 2, the kinetic energy of the rotation", false, true},
                                                             {"u1", "1", "the smallest root of the nutation cubic (u = cos theta)", false},
                                                             {"u2", "1", "the middle root: the top of the nutation", false},
                                                             {"u3", "1", "the largest root", false},
                                                             {"m", "1", "the parameter of the nutation's sn", false},
                                                             {"v", "1", "the nutation's phase variable", false},
                                                             {"T_nut", "s", "the nutation period", false},
                                                             {"cos_theta", "1", "cos theta: theta the angle between the symmetry axis and the vertical (the heavy top's nutation)", false},
                                                             {"cos_theta_rate", "1/s", "d cos theta / dt", false},
                                                             nutation_angle_info}};
    static constexpr auto outputs_info = with_euler_outputs<true>(own_outputs);
    void outputs(double /*t*/, const State& y, double* out) const;
    /// G_z and H are first integrals of the top in gravity; any other torque changes them.
    bool keeps(std::size_t /*output*/) const { return torques_.empty(); }

private:
    Body body_;
    TorqueSet torques_;
    double mu_ = 0.0;
    double A_ = 0.0, C_ = 0.0;
};

inline void LagrangeTop::outputs(double /*t*/, const State& y, double* out) const {
    const Vec3 integrals = first_integrals(y);
    out[0] = integrals[0];
    out[1] = integrals[1];
    out[2] = 0.5 * (A_ * (y[0] * y[0] + y[1] * y[1]) + C_ * y[2] * y[2]);
    const Nutation n = nutation(A_, C_, mu_, integrals[0], integrals[1], integrals[2]);
    const double roots[] = {n.u1, n.u2, n.u3, n.m, n.v, n.period};
    std::copy(std::begin(roots), std::end(roots), out + 3);
    const Vec3 gamma = vertical_in_body(y[3], y[4], y[5], y[6]);
    out[9] = gamma[2];
    out[10] = gamma[0] * y[1] - gamma[1] * y[0];
    // the angle between the symmetry axis and G = Jω (model/system.hpp), not θ to the vertical
    out[11] = nutation_angle(body_.angular_momentum(y.template head<3>()));
    euler_outputs(y.template segment<4>(3), out + 12);
}

}  // namespace gyrostat::model
