// The full model of a gyrostat under perturbation torques: Euler's dynamic equations, with the
// attitude quaternion integrated only when asked for.
#pragma once

#include <algorithm>
#include <array>
#include <string>
#include <variant>
#include <vector>
#include <utility>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <type_traits>

#include "gyrostat/attitude.hpp"
#include "gyrostat/body.hpp"
#include "gyrostat/numeric/lanes.hpp"
#include "gyrostat/model/affine_euler.hpp"
#include "gyrostat/model/affine_euler_avx2.hpp"
#include "gyrostat/model/system.hpp"
#include "gyrostat/model/torque_free.hpp"
#include "gyrostat/torque/set.hpp"

namespace gyrostat::model {

template <bool WithAttitude>
struct GyrostatLanes;

/// Gyrostat (body + constant rotor momentum k) under a set of torques.
///
///   J ω̇ + ω × (J ω + k) = Σ M_i(t, ω),     J = diag(A1, A2, A3),        (Euler)
///   q̇ = ½ q ⊗ (0, ω)                                                    (attitude, optional)
///
/// q is the unit quaternion (w, x, y, z) that rotates body axes into inertial axes:
/// x_inertial = q x_body q*. State layout: y = (p, q, r) or (p, q, r, q_w, q_x, q_y, q_z).
///
/// Outputs recorded along a trajectory:
///   |G| = |J ω + k|  (conserved without torques; the inertial vector G is conserved too),
///   T = ½ ω·J ω      (conserved without torques; dT/dt = ω·ΣM),
///   with the attitude: the z-x-z Euler angles ψ, θ, φ.
template <bool WithAttitude>
class Gyrostat : public RateAttitude<Gyrostat<WithAttitude>, WithAttitude ? 7 : 3, WithAttitude> {
public:
    static constexpr int dim = WithAttitude ? 7 : 3;
    static constexpr const char* model_name = "Gyrostat";
    using State = Eigen::Matrix<double, dim, 1>;
    using Jacobian = Eigen::Matrix<double, dim, dim>;
    static constexpr const char* family = "gyrostat";
    static constexpr auto states = rate_states<WithAttitude>();

    Gyrostat(Body body, TorqueSet torques)
        : body_(std::move(body)), torques_(torques.in_principal_axes(body)), affine_(AffineEuler<double>::of(body_, torques_)) {
        if constexpr (!WithAttitude) torques_.require_no_attitude("Model(attitude=False)");
    }

    const Body& body() const { return body_; }
    /// The Taylor recursion covers constant and linear torques (a quadratic right-hand side).
    bool supports_taylor() const { return torques_.is_affine(); }
    const TorqueSet& torques() const { return torques_; }

    /// ω̇ = J⁻¹ (ΣM − ω × (Jω + k));  q̇ = ½ q ⊗ (0, ω).
    void rhs(double t, const State& y, State& dy) const {
        const Vec3 omega = y.template head<3>();
        const Vec3 momentum = body_.moments().cwiseProduct(omega) + body_.rotor();
        Eigen::Vector4d q;
        const Vec3 torque = torques_.total(t, omega, body_.moments(), system::attitude_of<Gyrostat>(y, q));
        dy.template head<3>() = body_.inverse_moments().cwiseProduct(torque - omega.cross(momentum));
        if constexpr (WithAttitude) {
            dy.template segment<4>(3) = quaternion_rate(y.template segment<4>(3), omega);
        }
    }

    /// ∂ω̇/∂ω = J⁻¹ (ΣM_ω − skew(ω) J + skew(J ω + k)),  ∂ω̇/∂q = J⁻¹ ΣM_q (the attitude torques';
    /// TorqueSet::add_attitude_jacobian);  ∂q̇/∂ω, ∂q̇/∂q from the product ½ q ⊗ (0, ω).
    void jacobian(double t, const State& y, Jacobian& jac) const {
        jac.setZero();
        const Vec3 omega = y.template head<3>();
        const Vec3 momentum = body_.moments().cwiseProduct(omega) + body_.rotor();
        Eigen::Vector4d q;
        const Mat3 d_torque = torques_.jacobian(t, omega, body_.moments(), system::attitude_of<Gyrostat>(y, q));
        const Mat3 d_omega = body_.inverse_moments().asDiagonal() *
                             (d_torque - skew(omega) * body_.moments().asDiagonal() +
                              skew(momentum));
        jac.template topLeftCorner<3, 3>() = d_omega;
        if constexpr (WithAttitude) {
            quaternion_rate_jacobian(jac, 3, y.template segment<4>(3), omega);
            Eigen::Matrix<double, 3, 4> d_attitude = Eigen::Matrix<double, 3, 4>::Zero();
            if (torques_.add_attitude_jacobian(t, omega, body_.moments(), q, d_attitude))
                jac.template block<3, 4>(0, 3) = body_.inverse_moments().asDiagonal() * d_attitude;
        }
    }

    /// ∂f/∂p of a parameter of the torques folded into M = M0 − D ω (constant and linear torques),
    /// from this model moved by `step` in it (system::has_linear_rate_change): with the same body
    /// and no other torques, f_moved − f = J⁻¹ (ΔM0 − ΔD ω), so
    ///   ∂f/∂p = b + a y,   b_ω = J⁻¹ ΔM0 / step,   a_ωω = −J⁻¹ ΔD / step   (q̇ does not change),
    /// exact up to the coefficients' rounding; false where the bodies differ or a torque is not folded.
    bool linear_rate_change(const Gyrostat& moved, double step, State& b, Jacobian& a) const {
        const Body& other = moved.body();
        if (!torques_.is_affine() || !moved.torques().is_affine() || body_.moments() != other.moments() ||
            body_.rotor() != other.rotor() || body_.principal_axes() != other.principal_axes())
            return false;
        b.setZero();
        a.setZero();
        const Vec3 to_rate = body_.inverse_moments() / step;
        b.template head<3>() = to_rate.cwiseProduct(moved.torques().constant_part() - torques_.constant_part());
        a.template topLeftCorner<3, 3>() = -(to_rate.asDiagonal() * (moved.torques().damping_part() - torques_.damping_part()));
        return true;
    }

    /// f and ∂f/∂y · s_j for every column s_j at once (system::has_rate_with_products: the
    /// variational equations, model/variational.hpp): the torques, their ∂M/∂ω and the attitude
    /// torques' ∂M/∂q once, then each column's product from the same derivatives,
    ///   ∂ω̇ · s = J⁻¹ (ΣM_ω s_ω + ΣM_q s_q − s_ω × (Jω + k) − ω × (J s_ω)),
    ///   ∂q̇ · s = ½ (s_q ⊗ (0, ω) + q ⊗ (0, s_ω))      (q̇ is bilinear in q and ω),
    /// without the whole 7×7 Jacobian; f by rhs's own operations.
    bool rate_with_products(double t, const State& y, const double* columns, std::size_t count, State& f,
                            double* products) const {
        const Vec3 omega = y.template head<3>();
        const Vec3 momentum = body_.moments().cwiseProduct(omega) + body_.rotor();
        Eigen::Vector4d q;
        const auto* attitude = system::attitude_of<Gyrostat>(y, q);
        // the folded torques alone (constant and linear): M = M0 − D ω and ∂M/∂ω = −D, inline
        const bool folded = torques_.is_affine();
        const Vec3 torque = folded ? torques_.folded_total(omega) : torques_.total(t, omega, body_.moments(), attitude);
        f.template head<3>() = body_.inverse_moments().cwiseProduct(torque - omega.cross(momentum));
        if constexpr (WithAttitude) f.template segment<4>(3) = quaternion_rate(y.template segment<4>(3), omega);
        const Mat3 d_torque = folded ? Mat3(-torques_.damping_part()) : torques_.jacobian(t, omega, body_.moments(), attitude);
        [[maybe_unused]] Eigen::Matrix<double, 3, 4> d_attitude = Eigen::Matrix<double, 3, 4>::Zero();
        [[maybe_unused]] bool reads_attitude = false;
        if constexpr (WithAttitude) reads_attitude = torques_.add_attitude_jacobian(t, omega, body_.moments(), q, d_attitude);
        for (std::size_t j = 0; j < count; ++j) {
            const Eigen::Map<const State> s(columns + j * dim);
            Eigen::Map<State> product(products + j * dim);
            const Vec3 s_omega = s.template head<3>();
            Vec3 d_moment = d_torque * s_omega;
            if constexpr (WithAttitude)
                if (reads_attitude) d_moment += d_attitude * s.template segment<4>(3);
            product.template head<3>() = body_.inverse_moments().cwiseProduct(
                d_moment - s_omega.cross(momentum) - omega.cross(body_.moments().cwiseProduct(s_omega)));
            if constexpr (WithAttitude)
                product.template segment<4>(3) = quaternion_rate(s.template segment<4>(3), omega) + quaternion_rate(q, s_omega);
        }
        return true;
    }

    /// Taylor coefficients y[0..order] of the solution through y(t): y(t + h) = Σ y[n] hⁿ, from
    /// the recursion euler_taylor_recursion (above) for constant and linear torques.
    static constexpr int max_taylor_order = 30;

    template <int order>
    void taylor_coefficients(double /*t*/, const State& y, State* coefficients) const {
        for (int i = 0; i < dim; ++i) coefficients[0][i] = y[i];
        auto c = [&](int n, int i) -> double& { return coefficients[n][i]; };
#ifdef GYROSTAT_HAS_AVX2_KERNEL
        if (affine_euler_avx2_available()) {  // the same recursion in 4-wide vectors (affine_euler_avx2.hpp)
            static_assert(sizeof(State) == dim * sizeof(double), "coefficients[n] are dim contiguous doubles");
            affine_euler_rate_orders_avx2<order>(affine_, coefficients[0].data(), dim);
            if constexpr (WithAttitude)
                for (int n = 0; n < order; ++n) attitude_order<double>(n, c);
            return;
        }
#endif
        euler_taylor_recursion<order, WithAttitude>(affine_, c);
    }

    /// f(y + y_low) − c1 beyond double precision, for the Taylor method's compensated state
    /// (model/system.hpp; affine_euler_rate_error): the rate components; the attitude's are 0
    /// (its first coefficient keeps its rounding).
    State taylor_rate_error(const State& y, const State& y_low, const State& c1) const {
        State error = State::Zero();
#ifdef GYROSTAT_HAS_AVX2_KERNEL
        if (affine_euler_avx2_available()) {
            affine_euler_rate_error_avx2(affine_, y.data(), y_low.data(), c1.data(), error.data());
            return error;
        }
#endif
        affine_euler_rate_error(affine_, y.data(), y_low.data(), c1.data(), error.data());
        return error;
    }

    /// The affine Euler equations' coefficients (constant and linear torques folded).
    const AffineEuler<double>& affine_euler() const { return affine_; }

    /// W gyrostats in SIMD lanes (below), for the ensembles' batches (integrate/batch.hpp).
    using LaneModel = GyrostatLanes<WithAttitude>;

    // --- Splitting (integrate/splitting.hpp) ---------------------------------------------------
    // f = f_free + f_pert with
    //   f_free = (J⁻¹ (Jω + k) × ω,  ½ q ⊗ (0, ω))   the free gyrostat: its exact flow FreeBodyFlow,
    //   f_pert = (J⁻¹ ΣM(t, ω),      0)              the torques with t frozen (t advances in the
    //                                                 free part), q unchanged.
    // Constant and linear torques alone (M = M0 − D ω) have the exact perturbation flow
    // (integrate::AffineRateFlow). Any other torque (cavity, damper, medium) is not exact: the
    // perturbation sub-flow is then one step of the 8th-order Dormand–Prince method
    // (integrate::dop853_substep). The perturbation is body() and torques() (model/system.hpp).

    /// Throws std::invalid_argument naming the body when the free gyrostat has no exact flow here.
    void require_splitting() const { FreeBodyFlow::require_closed_form(body_, "splitting"); }

    /// y ← the exact free flow over h (t is not needed: the free gyrostat is autonomous). The
    /// constants in double (Phases::Double): over one sub-step |ω| h ~ 1, so their rounding
    /// costs ~1e-16 per step, as any step's; the double-double constants would cost 6× (12 µs
    /// instead of 2 µs per flow with attitude, measured).
    void free_flow(double h, State& y) const {
        if constexpr (WithAttitude) {
            const FreeBodyFlow flow(body_, y.template head<3>(), y.template segment<4>(3), 0.0, true, Phases::Double);
            y = flow.at(h);
        } else {
            const FreeBodyFlow flow(body_, y, Eigen::Vector4d(1, 0, 0, 0), 0.0, false, Phases::Double);
            y = flow.omega(h);
        }
    }

    /// |G| = |Jω| is a first integral the splitting projects on (a rigid body, and every torque
    /// keeps it: none, or the cavity).
    bool keeps_momentum_norm() const { return body_.rotor().squaredNorm() == 0.0 && torques_.keeps_momentum_norm(); }

    static constexpr std::array<OutputInfo, 3> own_outputs{{{"angular_momentum_norm", "kg m^2/s", "|G| = |J omega + k|, the norm of the angular momentum", true, true}, {"kinetic_energy", "J", "T = omega . J omega / 2, the kinetic energy of the rotation", true, true}, nutation_angle_info}};
    static constexpr auto outputs_info = with_euler_outputs<WithAttitude>(own_outputs);
    /// |G|, T, the nutation angle ϑ between body z and G = Jω + k (model/system.hpp:
    /// nutation_angle), then ψ, θ, φ with the attitude.
    void outputs(double /*t*/, const State& y, double* out) const {
        const Vec3 omega = y.template head<3>();
        const Vec3 G = body_.angular_momentum(omega);
        out[0] = G.norm();
        out[1] = body_.kinetic_energy(omega);
        out[2] = nutation_angle(G);
        this->attitude_outputs(y, out + 3);
    }
    /// The free rigid body's separatrix at ω (Body::separatrix; NaN with a rotor).
    double separatrix(const State& y) const { return body_.separatrix(y.template head<3>()); }
    /// Without torques |G| and T are first integrals; a torque with Jω·M ≡ 0 (the cavity) keeps
    /// |G| of a rigid body; any torque changes T.
    bool keeps(std::size_t output) const {
        return torques_.empty() || (output == 0 && keeps_momentum_norm());
    }

private:
    Body body_;
    TorqueSet torques_;
    AffineEuler<double> affine_;  // the constant and linear torques' part, for the Taylor recursion
};

/// W gyrostats side by side in SIMD lanes (numeric/lanes.hpp): Euler's affine equations
/// (affine_euler.hpp), each lane with its member's moments, rotor and constant and linear torques,
/// plus the user's compiled vectorised torques (torque/custom.hpp), called once per right-hand
/// side for the W lanes. A lane model (model/system.hpp) gives the right-hand side, the projection
/// and the Taylor recursion of W members at once.
template <bool WithAttitude>
struct GyrostatLanes {
    using System = Gyrostat<WithAttitude>;
    using Lanes = lanes::Lanes;
    static constexpr int W = lanes::width;
    static constexpr int dim = System::dim;
    static constexpr int max_taylor_order = System::max_taylor_order;
    AffineEuler<Lanes> euler;

    /// A user's torque as the lanes call it.
    struct UserTorque {
        torque::VectorForm form;
        bool attitude;             ///< it takes the quaternion
        const std::string* label;  ///< its name (the member's torque outlives the batch)
        bool operator==(const UserTorque& o) const { return form == o.form && attitude == o.attitude; }
    };
    std::vector<UserTorque> user;                      ///< the same in every lane: one call each for the W lanes
    std::array<std::vector<UserTorque>, W> lane_user;  ///< when the lanes' differ: each lane's, called with n = 1
    bool mixed = false;                                ///< the lanes' user torques differ

    /// Whether every torque of `torques` outside the affine part has a compiled vectorised form
    /// (torque/set.hpp: has_vector_form; each appended to `found`).
    static bool vectorised(const TorqueSet& torques, std::vector<UserTorque>* found = nullptr) {
        for (const AnyTorque& part : torques.others()) {
            const bool taken = std::visit([&](const auto& x) {
                if constexpr (gyrostat::has_vector_form<std::decay_t<decltype(x)>>::value) {
                    const torque::VectorForm form = x.vector_form();
                    if (!form.function) return false;
                    if (found) found->push_back({form, gyrostat::uses_attitude(x), &x.label});
                    return true;
                } else {
                    return false;
                }
            }, part);
            if (!taken) return false;
        }
        return true;
    }

    /// Whether the batches take this member (else it runs alone): the Taylor recursion needs
    /// constant and linear torques; DOP853 takes the user's compiled vectorised torques besides.
    static bool accepts(const System& system, bool taylor) {
        if constexpr (!lanes::wide && !WithAttitude) {
            // The portable build's 4 lanes in SSE2 pairs lose to one body at a time where the
            // scalar Taylor recursion runs in AVX2 (affine_euler_avx2.hpp): ω alone, 512
            // torque-free members, t = 200, 1 thread: 10.8 against 14.9 ms at rtol 1e-8, 14.9
            // against 25.2 ms at 1e-12 (with the attitude the batch still wins: 31 against 42 ms).
            if (taylor && affine_euler_avx2_available()) return false;
        }
        return system.supports_taylor() || (!taylor && vectorised(system.torques()));
    }

    /// members[0..W): the lanes' models (lanes past the batch repeat a member).
    explicit GyrostatLanes(const System* const* members) {
        auto gather = [&](auto field) {
            Lanes v;
            for (int l = 0; l < W; ++l) v[l] = field(members[l]->affine_euler());
            return v;
        };
        for (int i = 0; i < 3; ++i) {
            euler.inverse_moments[i] = gather([i](const auto& e) { return e.inverse_moments[i]; });
            euler.differences[i] = gather([i](const auto& e) { return e.differences[i]; });
            euler.rotor[i] = gather([i](const auto& e) { return e.rotor[i]; });
            euler.constant[i] = gather([i](const auto& e) { return e.constant[i]; });
        }
        for (int i = 0; i < 9; ++i) euler.damping[i] = gather([i](const auto& e) { return e.damping[i]; });
        euler.has_rotor = euler.damped = false;
        for (int l = 0; l < W; ++l) {
            euler.has_rotor = euler.has_rotor || members[l]->affine_euler().has_rotor;
            euler.damped = euler.damped || members[l]->affine_euler().damped;
        }
        std::array<std::vector<UserTorque>, W> own;
        for (int l = 0; l < W; ++l) vectorised(members[l]->torques(), &own[l]);
        for (int l = 1; l < W; ++l) mixed = mixed || own[l] != own[0];
        if (mixed)
            lane_user = std::move(own);
        else
            user = std::move(own[0]);
    }
    /// ω̇ (and q̇) of the W lanes; the user's torques added to M0 (affine_euler_rhs).
    void rhs(const Lanes& t, const Lanes* y, Lanes* dy) const {
        if (user.empty() && !mixed) return affine_euler_rhs<WithAttitude>(euler, y, dy);
        Lanes m[3];
        user_torque(t, y, m);
        affine_euler_rhs<WithAttitude>(euler, y, dy, m);
    }
    /// Σ M of the user's torques in the W lanes: one call per torque with n = W on the lanes' own
    /// arrays, which are the vectorised signature's structure of arrays (ω_i of lane l is
    /// y[i][l] = (double*)y[0] [i W + l], q_i is y[3 + i][l]); when the lanes' torques differ, one
    /// call per lane and torque with n = 1. Either way a lane's M is the sum of its torques in
    /// order, the same numbers.
    void user_torque(const Lanes& t, const Lanes* y, Lanes* m) const {
        static_assert(sizeof(Lanes) == W * sizeof(double), "a lane vector is W contiguous doubles");
        for (int i = 0; i < 3; ++i) m[i].setZero();
        Lanes out[3];
        if (!mixed) {
            for (const UserTorque& u : user) {
                for (int i = 0; i < 3; ++i) out[i].setZero();
                call(u, W, t.data(), y[0].data(), attitude_of(u, y), out[0].data());
                for (int i = 0; i < 3; ++i) m[i] += out[i];
            }
            return;
        }
        for (int l = 0; l < W; ++l) {
            double w[3] = {y[0][l], y[1][l], y[2][l]}, q[4] = {1.0, 0.0, 0.0, 0.0};
            if constexpr (WithAttitude)
                for (int i = 0; i < 4; ++i) q[i] = y[3 + i][l];
            for (const UserTorque& u : lane_user[l]) {
                double moment[3] = {0.0, 0.0, 0.0};
                call(u, 1, &t[l], w, WithAttitude && u.attitude ? q : nullptr, moment);
                for (int i = 0; i < 3; ++i) m[i][l] += moment[i];
            }
        }
    }
    template <int Order>
    void taylor(Lanes (*c)[dim]) const {
        euler_taylor_recursion<Order, WithAttitude>(euler, [c](int n, int i) -> Lanes& { return c[n][i]; });
    }
    /// |q| = 1 in every lane; a lane whose |q|² overflows or underflows (a quaternion given at an
    /// extreme scale: the first projection) is normalised alone, as the scalar model does
    /// (normalize_in_place, numeric/unit_vector.hpp).
    void project(Lanes* y) const {
        if constexpr (WithAttitude) {
            const Lanes squares = y[3].square() + y[4].square() + y[5].square() + y[6].square();
            const auto normal = squares >= std::numeric_limits<double>::min() && squares <= std::numeric_limits<double>::max();
            const Lanes norm = normal.select(squares.sqrt(), Lanes::Ones());
            for (int i = 3; i < 7; ++i) y[i] /= norm;
            if (normal.all()) return;
            for (int l = 0; l < W; ++l) {
                if (normal[l]) continue;
                Eigen::Vector4d q(y[3][l], y[4][l], y[5][l], y[6][l]);
                normalize_in_place(q);
                for (int i = 0; i < 4; ++i) y[3 + i][l] = q[i];
            }
        }
    }

private:
    static const double* attitude_of(const UserTorque& u, const Lanes* y) {
        if constexpr (WithAttitude)
            return u.attitude ? y[3].data() : nullptr;
        else
            return (void)u, (void)y, nullptr;
    }
    /// The user's function on n members; throws naming the torque when it returns non-zero.
    static void call(const UserTorque& u, int n, const double* t, const double* omega, const double* q, double* moment) {
        const int status = u.form.function(n, t, omega, q, moment, u.form.user_data);
        if (status == 0) return;
        std::string where = "t = " + format_value(t[0]);
        if (n > 1) {
            const auto [low, high] = std::minmax_element(t, t + n);
            where = "one of " + std::to_string(n) + " members at t from " + format_value(*low) + " to " +
                    format_value(*high);
        }
        throw std::runtime_error(torque::compiled_failure(*u.label, "function", status, where));
    }
};

}  // namespace gyrostat::model
