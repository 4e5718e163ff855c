// The perturbation sub-flows of the splitting integrators (integrate/splitting.hpp): the exact
// flow of an affine rate equation, and one 8th-order step for any other. A model that splits
// declares its perturbation (model/system.hpp: torques on ω with an optional frozen moment, or a
// rate on part of its state); PerturbationFlow builds the sub-flow from it.
#pragma once

#include <Eigen/Core>
#include <cmath>

#include "gyrostat/body.hpp"
#include "gyrostat/numeric/dop853_tableau.hpp"
#include "gyrostat/model/system.hpp"
#include "gyrostat/torque/set.hpp"

namespace gyrostat::integrate {

/// The exact flow over h of the affine rate equation with body and torques frozen
///   ω̇ = J⁻¹ (M − D ω),   M constant over the sub-step:
///   ω(h) = exp(−h J⁻¹D) ω(0) + [∫₀ʰ exp(−s J⁻¹D) ds] J⁻¹ M = propagator ω(0) + forcing M.
/// Both matrices are blocks of the exponential of the 6×6 matrix
///   X = [[−h J⁻¹D, h J⁻¹], [0, 0]],  exp(X) = [[propagator, forcing], [0, I]],
/// computed by scaling X to |X|∞ ≤ 1/2, 20 Taylor terms (remainder < 2⁻²⁰/20! ≈ 4e-25) and
/// squaring back: to rounding. Prepared once per sub-step size h; M may change at every use
/// (the heavy top's gravity depends on the frozen attitude).
struct AffineRateFlow {
    Mat3 propagator = Mat3::Identity();
    Mat3 forcing = Mat3::Zero();

    static AffineRateFlow over(double h, const Vec3& inverse_moments, const Mat3& damping) {
        using Mat6 = Eigen::Matrix<double, 6, 6>;
        Mat6 X = Mat6::Zero();
        X.topLeftCorner<3, 3>() = -(inverse_moments.asDiagonal() * damping) * h;
        X.topRightCorner<3, 3>() = (inverse_moments * h).asDiagonal();
        const double norm = X.cwiseAbs().rowwise().sum().maxCoeff();
        int squarings = 0;
        if (norm > 0.5) squarings = static_cast<int>(std::ceil(std::log2(norm / 0.5)));
        const Mat6 Y = X / std::ldexp(1.0, squarings);
        Mat6 E = Mat6::Identity(), term = Mat6::Identity();
        for (int n = 1; n <= 20; ++n) {
            term = term * Y / n;
            E += term;
        }
        for (int i = 0; i < squarings; ++i) E = E * E;
        AffineRateFlow flow;
        flow.propagator = E.topLeftCorner<3, 3>();
        flow.forcing = E.topRightCorner<3, 3>();
        return flow;
    }
    /// ω(h) from ω(0) under the constant moment M.
    Vec3 apply(const Vec3& omega, const Vec3& moment) const { return propagator * omega + forcing * moment; }
};

/// x ← one step of size h of the 8th-order Dormand–Prince method (DOP853's 12 stages, no error
/// estimate) for the autonomous x' = rate(x), time frozen by the caller. The splitting uses it
/// for the perturbations without an exact flow: 8th order is above that of every composition
/// offered (≤ 6), so the composition keeps its order (tests/test_splitting.py measures it).
template <class Vector, class Rate>
void dop853_substep(double h, Vector& x, const Rate& rate) {
    namespace tab = dop853_tableau;
    Vector k[tab::n_stages];
    for (int s = 0; s < tab::n_stages; ++s) {
        Vector stage = x;
        for (int j = 0; j < s; ++j)
            if (tab::a[s][j] != 0.0) stage += (h * tab::a[s][j]) * k[j];
        k[s] = rate(stage);
    }
    Vector increment = Vector::Zero();
    for (int s = 0; s < tab::n_stages; ++s)
        if (tab::b[s] != 0.0) increment += tab::b[s] * k[s];
    x += h * increment;
}

/// The perturbation sub-flow of a body under its torques and an extra moment frozen with t
/// (the heavy top's gravity at frozen attitude; zero for the gyrostat):
///   J ω̇ = extra + ΣM(t, ω).
/// Exact (AffineRateFlow) when every torque is constant or linear, one dop853_substep otherwise.
/// Prepared once per sub-step size h.
struct TorqueSubflow {
    double h = 0.0;
    bool exact = true;
    AffineRateFlow flow;

    static TorqueSubflow over(double h, const Body& body, const TorqueSet& torques) {
        TorqueSubflow p;
        p.h = h;
        p.exact = torques.is_affine();
        if (p.exact) p.flow = AffineRateFlow::over(h, body.inverse_moments(), torques.damping_part());
        return p;
    }
    /// `attitude`: the quaternion, frozen over the sub-step, for the torques that need it.
    Vec3 advance(const Body& body, const TorqueSet& torques, double t, Vec3 omega, const Vec3& extra,
                 const Eigen::Vector4d* attitude) const {
        if (exact) return flow.apply(omega, extra + torques.constant_part());
        const Vec3& J = body.moments();
        dop853_substep(h, omega, [&](const Vec3& w) -> Vec3 {
            return body.inverse_moments().cwiseProduct(extra + torques.total(t, w, J, attitude));
        });
        return omega;
    }
};

/// The perturbation's flow over h of a model that splits (model/system.hpp), prepared once per
/// sub-step size h and applied at frozen time t:
///   a rate on part of the state (perturbation_rate): one dop853_substep on that part;
///   else the model's torques on ω (body(), torques()) with the moment frozen_moment(y) (the
///   heavy top's gravity at frozen attitude; none: zero, and no torque leaves y as it is):
///   TorqueSubflow, exact for constant and linear torques.
template <class System>
class PerturbationFlow {
public:
    using State = typename System::State;
    static PerturbationFlow over(const System& system, double h) {
        PerturbationFlow p;
        if constexpr (model::system::has_perturbation_rate<System>::value) {
            (void)system;
            p.h_ = h;
        } else {
            p.torques_ = TorqueSubflow::over(h, system.body(), system.torques());
        }
        return p;
    }
    /// y ← the perturbation's flow over h at frozen time t.
    void apply(const System& system, double t, State& y) const {
        if constexpr (model::system::has_perturbation_rate<System>::value) {
            auto x = system.perturbed_part(y);
            dop853_substep(h_, x, [&](const decltype(x)& part) { return system.perturbation_rate(t, part); });
            system.set_perturbed_part(y, x);
        } else {
            Eigen::Vector4d q;  // frozen with t over the sub-step (the perturbation leaves q as it is)
            const Eigen::Vector4d* attitude = model::system::attitude_of<System>(y, q);
            if constexpr (model::system::has_frozen_moment<System>::value) {
                y.template head<3>() = torques_.advance(system.body(), system.torques(), t, y.template head<3>(),
                                                        system.frozen_moment(y), attitude);
            } else {
                if (system.torques().empty()) return;
                y.template head<3>() =
                    torques_.advance(system.body(), system.torques(), t, y.template head<3>(), Vec3::Zero(), attitude);
            }
        }
    }

private:
    double h_ = 0.0;
    TorqueSubflow torques_;
};

}  // namespace gyrostat::integrate
