// Paper 003: the heavy symmetric top averaged over the nutation, in the slow variables (G_z, H, r).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "gyrostat/model/lagrange_top.hpp"

namespace gyrostat::model {

/// Heavy symmetric top (A, A, C; μ = m g l) under torques of the paper's class (2.3),
/// M1 = f p, M2 = f q, M3 = M3*, averaged over the nutation phase of the unperturbed top.
///
/// Slow variables x = (G_z, H, r): the unperturbed first integrals. They are smooth and need no
/// sign bookkeeping (the paper's roots u1, u2, u3 do: docs/papers/003_lagrange_top.md §3–4).
/// Exactly, dG_z/dt = M·γ, dH/dt = M·ω, C dr/dt = M3, and with p γ1 + q γ2 = (G_z − C r u)/A,
/// p² + q² = (2H − C r² − 2μu)/A, averaging over u = cos θ (⟨u⟩ = v(G_z, H, r), see Nutation):
///
///   dG_z/dt = f(t) (G_z − C r v)/A + M3*(t, r) v
///   dH/dt   = f(t) (2H − C r² − 2μ v)/A + M3*(t, r) r
///   dr/dt   = M3*(t, r)/C
///
/// Torques accepted (the class (2.3) with coefficients that may depend on t):
///   ResistiveMedium and LinearDamping with D = diag(d, d, d3) at every order (f = −d(t),
///   M3* contains −d3(t) r); Constant with M = (0, 0, c) (M3* contains c).
/// Any other torque throws std::invalid_argument naming it: its nutation average is not
/// implemented, use the full LagrangeTop. For the paper's (3.1), f = −ε a(εt), M3* = −ε b(εt) r,
/// and r(t) = r0 exp(−(b0 τ + b1 τ²/2)/C) exactly (paper (3.3)).
///
/// Validity: the nutation period T = 2K(m)/α must be short against the time scale of the slow
/// variables (N = rate() · T ≪ 1, recorded as the output `adiabaticity`); near the separatrix
/// (1 − m → 0) and the triple root (α → 0) T grows and the averaging degrades. At m → 0
/// (regular precession) the right-hand side stays smooth (only the individual roots u1, u2 do not).
///
/// Outputs recorded: u1 ≤ u2 ≤ u3 (the roots of the nutation cubic), m = k², v = ⟨cos θ⟩,
/// T_nut and the adiabaticity number N = rate · T_nut.
/// A full top state (ω, Q) given as the initial state is mapped to its (G_z, H, r).
class LagrangeAveraged {
public:
    static constexpr int dim = 3;
    using State = Eigen::Vector3d;
    static constexpr const char* family = "lagrange_averaged";
    static constexpr std::array<Quantity, dim> states{{{"G_z", "kg m^2/s", "the angular momentum about the vertical"}, {"H", "J", "the top's energy, rotation plus gravity"}, {"r", "rad/s", "angular velocity about body z"}}};

    const Body& body() const { return top_.body(); }

    LagrangeAveraged(Body body, double mu, TorqueSet torques)
        : top_(body, mu, torques), torques_(torques.in_principal_axes(body)) {
        // the torques' affine forms (torque/affine.hpp: M = M0 − Σ t^k D_k ω) are of the paper's
        // class when M0 = (0, 0, c) and every D_k = diag(d_k, d_k, d3_k)
        for (const auto& part : torques_.parts())
            std::visit([&](const auto& x) {
                using T = std::decay_t<decltype(x)>;
                if constexpr (gyrostat::has_affine_form<T>::value) {
                    const torque::AffineForm form = x.affine_form();
                    const Vec3& m0 = form.constant;
                    if (m0.x() != 0.0 || m0.y() != 0.0)
                        throw std::invalid_argument(
                            std::string("LagrangeAveraged: ") + T::python_name + "'s constant torque must be axial, "
                            "M = (0, 0, c), to be of the paper's class (2.3); got M1 = " + format_value(m0.x()) +
                            ", M2 = " + format_value(m0.y()) + ": use the full LagrangeTop");
                    axial_constant_ += m0.z();
                    for (std::size_t k = 0; k < form.damping.size(); ++k)
                        add_linear(form.damping[k], k, std::string(T::python_name) +
                                                           (form.damping.size() == 1 ? std::string(" matrix")
                                                                                     : " coefficient D_" + std::to_string(k)));
                } else {
                    throw std::invalid_argument(std::string("LagrangeAveraged: the nutation average of torque '") +
                                                T::name + "' is not implemented: use the full LagrangeTop");
                }
            }, part);
    }

    const LagrangeTop& top() const { return top_; }
    double A() const { return top_.A(); }
    double C() const { return top_.C(); }
    double mu() const { return top_.mu(); }

    /// d(t): the equatorial damping coefficient (f = −d); d3(t): the axial one; c: axial constant.
    double equatorial_damping(double t) const { return horner(equatorial_, t); }
    double axial_damping(double t) const { return horner(axial_, t); }
    double axial_constant() const { return axial_constant_; }
    /// The rate at which the slow variables relax: max(|d(t)|/A, |d3(t)|/C). Times the nutation
    /// period it is the adiabaticity number N = rate · T that must be ≪ 1.
    double rate(double t) const {
        return std::max(std::abs(equatorial_damping(t)) / A(), std::abs(axial_damping(t)) / C());
    }

    /// The equations in the block comment above the class.
    void rhs(double t, const State& x, State& dx) const {
        const double A = top_.A(), C = top_.C(), mu = top_.mu();
        const double Gz = x[0], H = x[1], r = x[2];
        const double v = nutation(A, C, mu, Gz, H, r).v;
        const double f = -equatorial_damping(t);
        const double m3 = -axial_damping(t) * r + axial_constant_;
        dx[0] = f * (Gz - C * r * v) / A + m3 * v;
        dx[1] = f * (2.0 * H - C * r * r - 2.0 * mu * v) / A + m3 * r;
        dx[2] = m3 / C;
    }

    using Jacobian = Eigen::Matrix3d;
    /// ∂(dx)/∂x of the equations above, with v's slopes from nutation_slopes (lagrange_top.hpp):
    ///   ∂/∂G_z: (f (1 − C r v_G)/A + M3* v_G,  −2μ f v_G/A,  0)
    ///   ∂/∂H:   (−f C r v_H/A + M3* v_H,  f (2 − 2μ v_H)/A,  0)
    ///   ∂/∂r:   (−f C (v + r v_r)/A − d3 v + M3* v_r,  −f (2 C r + 2μ v_r)/A − d3 r + M3*,  −d3/C)
    /// one nutation solve where central differences along a direction take two (the sensitivities'
    /// J·S: two per column per stage; CVODE's Newton matrix).
    void jacobian(double t, const State& x, Jacobian& jac) const {
        const double A = top_.A(), C = top_.C(), mu = top_.mu();
        const double Gz = x[0], H = x[1], r = x[2];
        const Nutation n = nutation(A, C, mu, Gz, H, r);
        const NutationSlopes dv = nutation_slopes(A, C, mu, Gz, H, r, n);
        const double v = n.v, f = -equatorial_damping(t), d3 = axial_damping(t);
        const double m3 = -d3 * r + axial_constant_;
        jac << f * (1.0 - C * r * dv.Gz) / A + m3 * dv.Gz, -f * C * r * dv.H / A + m3 * dv.H,
            -f * C * (v + r * dv.r) / A - d3 * v + m3 * dv.r,
            -2.0 * mu * f * dv.Gz / A, f * (2.0 - 2.0 * mu * dv.H) / A, -f * (2.0 * C * r + 2.0 * mu * dv.r) / A - d3 * r + m3,
            0.0, 0.0, -d3 / C;
    }

    /// Its numbers whose ∂(dx)/∂p it gives in closed form (system::has_parameter_rate).
    static constexpr std::array<const char*, 1> analytic_in{{"mu"}};
    /// ∂(dx)/∂μ of the equations above (v's slope v_μ from nutation_slopes):
    ///   (−f C r v_μ/A + M3* v_μ,  −f (2v + 2μ v_μ)/A,  0)
    void parameter_rate(std::size_t /*k: μ, the only one*/, double t, const State& x, State& rate) const {
        const double A = top_.A(), C = top_.C(), mu = top_.mu();
        const double Gz = x[0], H = x[1], r = x[2];
        const Nutation n = nutation(A, C, mu, Gz, H, r);
        const double v_mu = nutation_slopes(A, C, mu, Gz, H, r, n).mu;
        const double f = -equatorial_damping(t), m3 = -axial_damping(t) * r + axial_constant_;
        rate << (-f * C * r / A + m3) * v_mu, -f * (2.0 * n.v + 2.0 * mu * v_mu) / A, 0.0;
    }

    /// (G_z, H, r) must be reachable by the top (lagrange_top.hpp: check_reachable).
    void check_state(const State& x) const { check_reachable(top_.A(), top_.C(), top_.mu(), x[0], x[1], x[2]); }

    /// (G_z, H, r) of a full top state (ω, Q); a state of size 3 is taken as it is.
    State initial_state(const Eigen::VectorXd& given) const {
        if (given.size() != LagrangeTop::dim)
            throw std::invalid_argument("initial state has " + std::to_string(given.size()) +
                                        " components; LagrangeAveraged needs (G_z, H, r) or a full top state "
                                        "(p, q, r, q_w, q_x, q_y, q_z)");
        LagrangeTop::State full = given;
        top_.check_state(full);
        normalize_in_place(full.segment<4>(3));
        return top_.first_integrals(full);
    }

    /// A full top state (ω, Q) with these (G_z, H, r), at the top of the nutation u = cos θ = u2
    /// (a turning point: θ̇ = 0), precession angle ψ = 0 and proper rotation φ = `phase`.
    /// With the z-x-z angles, γ = (sin θ sin φ, sin θ cos φ, cos θ) in body axes and at θ̇ = 0
    ///   p = ψ̇ sin θ sin φ,  q = ψ̇ sin θ cos φ,  ψ̇ sin²θ = (G_z − C r u)/A,
    /// so that G_z = A(p γ1 + q γ2) + C r γ3; H = ½A(p² + q²) + ½C r² + μu holds because u2 is a
    /// root of the nutation cubic. Q = q_x(θ) ⊗ q_z(φ) = (c cφ, s cφ, −s sφ, c sφ), c = cos θ/2,
    /// s = sin θ/2, cφ = cos φ/2, sφ = sin φ/2. At sin θ = 0 (a sleeping top) p = q = 0.
    Eigen::VectorXd full_state(const State& x, double phase) const {
        check_state(x);
        const Nutation n = nutation(top_.A(), top_.C(), top_.mu(), x[0], x[1], x[2]);
        const double u = std::clamp(n.u2, -1.0, 1.0);
        const double theta = std::acos(u);
        const double sin_theta = std::sin(theta);
        const double transverse = sin_theta > 1e-12 ? (x[0] - top_.C() * x[2] * u) / (top_.A() * sin_theta) : 0.0;
        Eigen::VectorXd full(LagrangeTop::dim);
        full << transverse * std::sin(phase), transverse * std::cos(phase), x[2], std::cos(0.5 * theta) * std::cos(0.5 * phase),
            std::sin(0.5 * theta) * std::cos(0.5 * phase), -std::sin(0.5 * theta) * std::sin(0.5 * phase),
            std::cos(0.5 * theta) * std::sin(0.5 * phase);
        return full;
    }

    /// No nutation angle ϑ (body z to G) here: the slow variables (G_z, H, r) do not fix it, as it
    /// swings with the averaged-out nutation (the full LagrangeTop records it).
    static constexpr std::array<OutputInfo, 7> outputs_info{{{"u1", "1", "the smallest root of the nutation cubic (u = cos theta)", false},
                                                             {"u2", "1", "the middle root: the top of the nutation", false},
                                                             {"u3", "1", "the largest root", false},
                                                             {"m", "1", "the parameter of the nutation's sn", false},
                                                             {"v", "1", "the nutation's phase variable", false},
                                                             {"T_nut", "s", "the nutation period", false},
                                                             {"adiabaticity", "1", "the torque's relative rate times the nutation period (averaging needs it << 1)", false}}};
    void outputs(double t, const State& x, double* out) const {
        const Nutation n = nutation(top_.A(), top_.C(), top_.mu(), x[0], x[1], x[2]);
        const double values[] = {n.u1, n.u2, n.u3, n.m, n.v, n.period, rate(t) * n.period};
        std::copy(std::begin(values), std::end(values), out);
    }

private:
    void add_linear(const Mat3& D, std::size_t order, const std::string& what) {
        const bool diagonal = D(0, 1) == 0.0 && D(0, 2) == 0.0 && D(1, 0) == 0.0 && D(1, 2) == 0.0 &&
                              D(2, 0) == 0.0 && D(2, 1) == 0.0;
        if (!diagonal || D(0, 0) != D(1, 1))
            throw std::invalid_argument("LagrangeAveraged: " + what +
                                        " must be diag(d, d, d3) to be of the paper's class (2.3); got D11 = " +
                                        format_value(D(0, 0)) + ", D22 = " + format_value(D(1, 1)) +
                                        (diagonal ? std::string() : std::string(" and off-diagonal terms")) +
                                        ": use the full LagrangeTop");
        if (equatorial_.size() <= order) equatorial_.resize(order + 1, 0.0), axial_.resize(order + 1, 0.0);
        equatorial_[order] += D(0, 0);
        axial_[order] += D(2, 2);
    }
    static double horner(const std::vector<double>& c, double t) {
        double s = 0.0;
        for (std::size_t k = c.size(); k-- > 0;) s = s * t + c[k];
        return s;
    }

    LagrangeTop top_;
    TorqueSet torques_;
    std::vector<double> equatorial_, axial_;  ///< polynomial coefficients in t
    double axial_constant_ = 0.0;
};

}  // namespace gyrostat::model
