// The torque-free rigid body in closed form (Euler–Poinsot motion): Jacobi elliptic functions,
// no integration at all. The cheapest answer for a scene with no torque and no rotor.
#pragma once

#include <Eigen/Geometry>
#include <array>
#include <vector>

#include "gyrostat/body.hpp"
#include "gyrostat/model/system.hpp"

namespace gyrostat::model {

/// ω(t) of a free rigid body (rotor k = 0) from ω(t0) = ω0.
///
/// With the axes relabelled (1', 2', 3') so that the polhode encircles axis 3' (the axis of the
/// largest moment when D = G²/2T > A2, of the smallest otherwise), and A, B, C the moments on
/// those axes:
///   ω1' = a cn(u, m),  ω2' = b sn(u, m),  ω3' = ±c dn(u, m),  u = ν (t − t0) + u0,
///   a² = (2TC − G²)/(A(C − A)),  b² = (2TC − G²)/(B(C − B)),  c² = (G² − 2TA)/(C(C − A)),
///   m = k² = (B − A)(2TC − G²)/((C − B)(G² − 2TA)),  ν = σ (C − B) b c/(A a),
/// with σ = ±1 from the sign of ω3' and the parity of the relabelling, and u0 = F(φ0, k),
/// φ0 = atan2(ω2'(t0)/b, ω1'(t0)/a) (Landau & Lifshitz, Mechanics §37).
/// Permanent rotations (a = b = 0) and the spherical body give a constant ω.
/// Attitude is not given in closed form (it needs the incomplete integral of the third kind):
/// integrate when attitude is needed.
class TorqueFreeSolution {
public:
    /// Throws std::invalid_argument when the body has a rotor (k ≠ 0: the Zhukovsky–Volterra
    /// gyrostat has no such closed form here) or ω0 is not finite.
    TorqueFreeSolution(const Body& body, const Vec3& omega0, double t0 = 0.0);

    Vec3 omega(double t) const;
    Vec3 at(double t) const { return omega(t); }                          ///< the flow's state at t
    std::vector<double> omega(const std::vector<double>& times) const;  ///< n×3, row-major

    double modulus_squared() const { return m_; }            ///< m = k² (0 for permanent rotation)
    double frequency() const { return nu_; }                  ///< ν (rad/s of the argument u)
    double period() const;                                     ///< of ω(t): 4K(m)/|ν| (∞ when constant)
    /// The longest piece over which an event search may assume at most one crossing of a smooth
    /// function of ω: 1/32 of the period (∞ when ω is constant).
    double event_step() const { return period() / 32.0; }
    bool is_constant() const { return constant_; }

private:
    Vec3 omega0_;
    double t0_;
    bool constant_ = false;
    int axis_[3] = {0, 1, 2};   // body axis index of 1', 2', 3'
    double a_ = 0, b_ = 0, c_ = 0, m_ = 0, nu_ = 0, u0_ = 0, sign3_ = 1;
};

/// The torque-free rigid body as a model that needs no integration (model/system.hpp, `flow`):
/// state ω, outputs |G| and T (conserved exactly: the closed form keeps them to rounding).
class TorqueFree {
public:
    static constexpr int dim = 3;
    using State = Eigen::Vector3d;
    static constexpr std::array<const char*, dim> state_names{"p", "q", "r"};

    /// Throws std::invalid_argument for a gyrostat (k ≠ 0): no closed form here.
    explicit TorqueFree(Body body);
    const Body& body() const { return body_; }

    TorqueFreeSolution flow(double t0, const State& y0) const { return TorqueFreeSolution(body_, y0, t0); }
    /// ω̇ = J⁻¹ (Jω × ω), for checks and stiffness diagnostics (the solve never integrates it).
    void rhs(double, const State& y, State& dy) const {
        dy = body_.inverse_moments().cwiseProduct(body_.moments().cwiseProduct(y).cross(y));
    }

    static constexpr std::array<OutputInfo, 2> outputs_info{{{"angular_momentum_norm", true}, {"kinetic_energy", true}}};
    void outputs(double, const State& y, double* out) const {
        out[0] = body_.angular_momentum(y).norm();
        out[1] = body_.kinetic_energy(y);
    }

private:
    Body body_;
};

}  // namespace gyrostat::model
