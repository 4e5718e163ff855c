// The one model concept: what every system the engine integrates must give, what it may give,
// and the defaults for what it does not (in one place, so that no model carries empty stubs).
#pragma once

#include <Eigen/Core>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "gyrostat/attitude.hpp"

namespace gyrostat::model {

/// A named component of a model's state: its name, SI unit ("1": dimensionless) and one line
/// saying what it is. The units in files, plots and docs come from here.
struct Quantity {
    const char* name;
    const char* unit;
    const char* description;
    /// The vector this component is part of ("omega", "quaternion", …; nullptr: a scalar). A run's
    /// error is measured on a vector as one norm (engine.hpp: measured_quantities).
    const char* vector = nullptr;
    /// A label, not a quantity (the triaxial averaged model's branch ±1): no error is measured on it.
    bool label = false;
};

/// A named quantity a model records at every output time (invariants and derived quantities).
struct OutputInfo {
    const char* name;
    const char* unit;         ///< SI unit ("1": dimensionless)
    const char* description;  ///< one line: what it is
    /// A first integral of the model without perturbation (|G|, T, G_z, H, …). Its relative
    /// change along a run measures the perturbation's work, or the integration error where
    /// nothing perturbs it. Derived quantities (angles, roots, rates) are not conserved.
    bool conserved;
    /// A run's error is measured on it (engine.hpp: measured_quantities): the invariants the
    /// papers plot (|G|, T, the moving mass's energy, the top's G_z and H).
    bool measured = false;
};

/// A System must give
///   static constexpr int dim;                                    state size
///   using State = Eigen::Matrix<double, dim, 1>;
///   static constexpr const char* family;                         the model family's name
///   static constexpr std::array<Quantity, dim> states;          name, unit, description per component
///   void rhs(double t, const State& y, State& dy) const;         the right-hand side
/// and may give (detected below; each line names the default when it is absent)
///   void jacobian(double t, const State& y, Jacobian& J) const;  analytic ∂f/∂y
///                                                                (default: difference quotients)
///   void project(State& y) const;                                back onto a manifold (|q| = 1)
///                                                                after each step (default: none)
///   static constexpr int max_taylor_order;                       Taylor coefficients by recursion,
///   template <int Order> void taylor_coefficients(double t, const State& y, State* c) const;
///   bool supports_taylor() const;                                (default: no Taylor method)
///   State taylor_rate_error(const State& y, const State& y_low, const State& c1) const;
///                                                                f(y + y_low) − c1 beyond double
///                                                                precision, c1 = fl(f(y)) the
///                                                                first Taylor coefficient; the
///                                                                Taylor method adds it below
///                                                                rtol 1e-12 (default: none)
///   static constexpr std::array<OutputInfo, n> outputs_info;     named outputs recorded at every
///   void outputs(double t, const State& y, double* out) const;   output time (default: none)
///   void measured_outputs(double t, const State& y, double* out) const;
///                                                                the outputs flagged measured
///                                                                alone, NaN in the others: what a
///                                                                window estimate's companion records
///                                                                (Options::only_measured_outputs)
///                                                                where the others cost more than a
///                                                                few operations (default: outputs)
///   bool keeps(std::size_t output) const;                        whether the output `output`,
///                                                                flagged conserved, stays a first
///                                                                integral with this model's
///                                                                torques (default: yes; a forced
///                                                                energy is not)
///   double separatrix(const State& y) const;                     the signed distance to a separatrix of
///                                                                the unperturbed motion: a change of sign
///                                                                along a run is a crossing, where the
///                                                                run's error grows faster than before it
///                                                                (the accuracy contract's window estimate
///                                                                then measures the whole span; NaN: none
///                                                                here) (default: none)
///   void check_state(const State& y) const;                      throws std::invalid_argument for
///                                                                a state the model cannot reach
///                                                                (default: finite is enough)
///   State initial_state(const Eigen::VectorXd& given) const;     completes a shorter initial state
///                                                                (ω alone → ω, identity quaternion)
///                                                                (default: the size must be dim)
///   Eigen::VectorXd full_state(const State& slow, double phase) const;
///                                                                an averaged model: a state of the
///                                                                model it averages with these slow
///                                                                variables, at the fast phase given
///                                                                (the model ladder's switch up)
///   static constexpr std::array<int, n> quadratures;             components whose rate depends on the
///                                                                others and that feed back into none
///                                                                (a fast phase carried along): the
///                                                                first step's heuristic and DOP853's
///                                                                error test leave them out, as CVODES
///                                                                leaves its quadrature variables out
///                                                                by default (default: none)
///   static constexpr std::array<int, n> body_vectors;            the state's vectors in body axes
///                                                                (model/frame.hpp: a body given by
///                                                                its inertia tensor; default: only
///                                                                bodies given in principal axes)
///   using LaneModel = …;                                         W members side by side in SIMD
///                                                                lanes (numeric/lanes.hpp), for the
///                                                                ensembles' batches (integrate/
///                                                                batch.hpp; default: no batches).
///                                                                A lane model gives
///     using System; static constexpr int dim;
///     explicit LaneModel(const System* const* members);         the W lanes' members
///     static bool accepts(const System&, bool taylor);          whether a batch takes this member
///     void rhs(const Lanes& t, const Lanes* y, Lanes* dy) const;
///     void project(Lanes* y) const;                             (or nothing)
///   and for the Taylor method
///     static constexpr int max_taylor_order;
///     template <int Order> void taylor(Lanes (*c)[dim]) const;  c[0] given, c[1..Order] computed
/// A system that splits (integrate/splitting.hpp) gives its free part and its perturbation:
///   static constexpr bool carries_attitude;                      the unit quaternion body → inertial
///                                                                is y[3..7) (the torques that need
///                                                                the attitude read it; default: no)
///   void require_splitting() const;                              throws when its free part has
///                                                                no exact flow
///   void free_flow(double h, State& y) const;                    the exact free flow over h
///   const Body& body() const; const TorqueSet& torques() const;  the perturbation: the torques on
///   Vec3 frozen_moment(const State& y) const;                    ω (y[0..2]) plus, optionally, a
///                                                                moment frozen over the sub-step
///   or instead a rate on part of the state, frozen in t:
///     Part perturbed_part(const State&) const;  void set_perturbed_part(State&, const Part&) const;
///     Part perturbation_rate(double t, const Part& x) const;
///   bool keeps_momentum_norm() const;                            |Jω| is kept by both sub-flows
/// A system that needs no integration gives instead of rhs
///   auto flow(double t0, const State& y0) const;                 an object with State at(double t)
namespace system {

template <class S>
using Jacobian = Eigen::Matrix<double, S::dim, S::dim>;

template <class S, class = void>
struct has_jacobian : std::false_type {};
template <class S>
struct has_jacobian<S, std::void_t<decltype(std::declval<const S&>().jacobian(
                           0.0, std::declval<const typename S::State&>(), std::declval<Jacobian<S>&>()))>>
    : std::true_type {};

/// A model that gives f and its products with several columns in one evaluation (`void
/// rate_with_products(double t, const State& y, const double* columns, std::size_t count, State& f,
/// double* products) const`, columns and products `count` blocks of dim; false where it does not
/// cover that many columns): what f and the products share evaluated once (the gyrostat's torques
/// and their derivatives; the moving mass's dual numbers with a direction per column, whose values
/// are f), without forming the whole Jacobian.
template <class S, class = void>
struct has_rate_with_products : std::false_type {};
template <class S>
struct has_rate_with_products<S, std::void_t<decltype(std::declval<const S&>().rate_with_products(
                                     0.0, std::declval<const typename S::State&>(), std::declval<const double*>(),
                                     std::size_t{}, std::declval<typename S::State&>(), std::declval<double*>()))>>
    : std::true_type {};

/// A model that gives ∂f/∂p of some of its own numbers in closed form (the variational equations'
/// parameter columns then take it instead of a difference quotient between moved models): its
/// `static constexpr std::array<const char*, K> analytic_in` (the names gyrostat.sensitivity
/// gives them) and `void parameter_rate(std::size_t k, double t, const State& y, State& rate) const`
/// (∂f/∂p_k at (t, y)).
template <class S, class = void>
struct has_parameter_rate : std::false_type {};
template <class S>
struct has_parameter_rate<S, std::void_t<decltype(S::analytic_in), decltype(std::declval<const S&>().parameter_rate(
                                                                       std::size_t{}, 0.0, std::declval<const typename S::State&>(),
                                                                       std::declval<typename S::State&>()))>>
    : std::true_type {};

/// A model that gives ∂f/∂p from itself moved in p, where f's change is linear in the state
/// (`bool linear_rate_change(const S& moved, double step, State& b, Jacobian& a) const`:
/// f_moved − f = step · (b + a y) exactly, as the gyrostat's under torques constant and linear
/// in ω, whose parameters move only those coefficients; false where it is not so): the
/// variational equations' parameter column then takes b + a y, without a moved right-hand side.
template <class S, class = void>
struct has_linear_rate_change : std::false_type {};
template <class S>
struct has_linear_rate_change<S, std::void_t<decltype(std::declval<const S&>().linear_rate_change(
                                     std::declval<const S&>(), 0.0, std::declval<typename S::State&>(),
                                     std::declval<Jacobian<S>&>()))>>
    : std::true_type {};

/// The names of has_parameter_rate's numbers (none for a model without them).
template <class S>
std::vector<std::string> analytic_in() {
    if constexpr (has_parameter_rate<S>::value)
        return std::vector<std::string>(S::analytic_in.begin(), S::analytic_in.end());
    else
        return {};
}

template <class S, class = void>
struct has_projection : std::false_type {};
template <class S>
struct has_projection<S, std::void_t<decltype(std::declval<const S&>().project(std::declval<typename S::State&>()))>>
    : std::true_type {};

template <class S, class = void>
struct has_taylor : std::false_type {};
template <class S>
struct has_taylor<S, std::void_t<decltype(S::max_taylor_order)>> : std::true_type {};

/// The gyrostat's affine Euler coefficients (model/affine_euler.hpp): the variational equations'
/// Taylor recursion (integrate/variational_taylor.hpp).
template <class S, class = void>
struct has_affine_euler : std::false_type {};
template <class S>
struct has_affine_euler<S, std::void_t<decltype(std::declval<const S&>().affine_euler())>> : std::true_type {};

template <class S, class = void>
struct has_taylor_rate_error : std::false_type {};
template <class S>
struct has_taylor_rate_error<
    S, std::void_t<decltype(std::declval<const S&>().taylor_rate_error(
           std::declval<const typename S::State&>(), std::declval<const typename S::State&>(),
           std::declval<const typename S::State&>()))>> : std::true_type {};

template <class S, class = void>
struct has_outputs : std::false_type {};
template <class S>
struct has_outputs<S, std::void_t<decltype(S::outputs_info)>> : std::true_type {};

template <class S, class = void>
struct has_measured_outputs : std::false_type {};
template <class S>
struct has_measured_outputs<S, std::void_t<decltype(std::declval<const S&>().measured_outputs(
                                   0.0, std::declval<const typename S::State&>(), std::declval<double*>()))>>
    : std::true_type {};

template <class S, class = void>
struct has_separatrix : std::false_type {};
template <class S>
struct has_separatrix<S, std::void_t<decltype(std::declval<const S&>().separatrix(std::declval<const typename S::State&>()))>>
    : std::true_type {};

template <class S, class = void>
struct has_keeps : std::false_type {};
template <class S>
struct has_keeps<S, std::void_t<decltype(std::declval<const S&>().keeps(std::size_t{0}))>> : std::true_type {};

template <class S, class = void>
struct has_state_check : std::false_type {};
template <class S>
struct has_state_check<S, std::void_t<decltype(std::declval<const S&>().check_state(
                              std::declval<const typename S::State&>()))>> : std::true_type {};

template <class S, class = void>
struct has_initial_state : std::false_type {};
template <class S>
struct has_initial_state<S, std::void_t<decltype(std::declval<const S&>().initial_state(
                                std::declval<const Eigen::VectorXd&>()))>> : std::true_type {};

template <class S, class = void>
struct has_full_state : std::false_type {};
template <class S>
struct has_full_state<S, std::void_t<decltype(std::declval<const S&>().full_state(
                             std::declval<const typename S::State&>(), 0.0))>> : std::true_type {};

template <class S, class = void>
struct has_perturbation_rate : std::false_type {};
template <class S>
struct has_perturbation_rate<S, std::void_t<decltype(std::declval<const S&>().perturbation_rate(
                                    0.0, std::declval<const S&>().perturbed_part(std::declval<const typename S::State&>())))>>
    : std::true_type {};

template <class S, class = void>
struct has_quadratures : std::false_type {};
template <class S>
struct has_quadratures<S, std::void_t<decltype(S::quadratures)>> : std::true_type {};

/// The model's quadrature components (none by default).
template <class S>
constexpr auto quadratures() {
    if constexpr (has_quadratures<S>::value)
        return S::quadratures;
    else
        return std::array<int, 0>{};
}

template <class S, class = void>
struct carries_attitude : std::false_type {};
template <class S>
struct carries_attitude<S, std::enable_if_t<S::carries_attitude>> : std::true_type {};

/// The attitude quaternion of y (y[3..7)) where the model carries it, else nullptr; `q` holds it.
template <class S>
const Eigen::Vector4d* attitude_of(const typename S::State& y, Eigen::Vector4d& q) {
    if constexpr (carries_attitude<S>::value) {
        q = y.template segment<4>(3);
        return &q;
    } else {
        (void)y, (void)q;
        return nullptr;
    }
}

template <class S, class = void>
struct has_frozen_moment : std::false_type {};
template <class S>
struct has_frozen_moment<S, std::void_t<decltype(std::declval<const S&>().frozen_moment(
                                std::declval<const typename S::State&>()))>> : std::true_type {};

template <class S, class = void>
struct has_lanes : std::false_type {};
template <class S>
struct has_lanes<S, std::void_t<typename S::LaneModel>> : std::true_type {};

template <class S, class = void>
struct is_closed_form : std::false_type {};
template <class S>
struct is_closed_form<S, std::void_t<decltype(std::declval<const S&>().flow(
                             0.0, std::declval<const typename S::State&>()))>> : std::true_type {};

template <class S>
constexpr int n_outputs() {
    if constexpr (has_outputs<S>::value)
        return static_cast<int>(S::outputs_info.size());
    else
        return 0;
}

template <class S>
void project(const S& s, typename S::State& y) {
    if constexpr (has_projection<S>::value) s.project(y);
}

template <class S>
bool supports_taylor(const S& s) {
    if constexpr (has_taylor<S>::value)
        return s.supports_taylor();
    else
        return false;
}

/// Writes the named outputs at (t, y). A model's output that cannot be evaluated there (a
/// root that does not exist, a state outside its domain) is NaN, never an exception: outputs
/// are recorded during the run and must not abort it.
template <class S>
void outputs(const S& s, double t, const typename S::State& y, double* out) {
    if constexpr (has_outputs<S>::value) {
        try {
            s.outputs(t, y, out);
        } catch (const std::exception&) {
            for (int i = 0; i < n_outputs<S>(); ++i) out[i] = std::numeric_limits<double>::quiet_NaN();
        }
    }
}

/// The outputs a run's error is measured on (OutputInfo::measured) at (t, y), the others NaN where
/// the model says so (measured_outputs), else all of them (outputs).
template <class S>
void measured_outputs(const S& s, double t, const typename S::State& y, double* out) {
    if constexpr (has_measured_outputs<S>::value) {
        try {
            s.measured_outputs(t, y, out);
        } catch (const std::exception&) {
            for (int i = 0; i < n_outputs<S>(); ++i) out[i] = std::numeric_limits<double>::quiet_NaN();
        }
    } else {
        outputs(s, t, y, out);
    }
}

template <class S>
void check_state(const S& s, const typename S::State& y) {
    if constexpr (has_state_check<S>::value) s.check_state(y);
}

/// "p, q, r": the names of quantities, for messages.
template <class Q, std::size_t N>
std::string join_names(const std::array<Q, N>& quantities) {
    std::string joined;
    for (std::size_t i = 0; i < N; ++i) joined += std::string(i ? ", " : "") + quantities[i].name;
    return joined;
}

/// The full initial state from what the user gave: the model's own completion, or the state itself.
template <class S>
typename S::State initial_state(const S& s, const Eigen::VectorXd& given) {
    if constexpr (has_initial_state<S>::value) {
        if (given.size() != S::dim) return s.initial_state(given);
    }
    if (given.size() != S::dim)
        throw std::invalid_argument("initial state has " + std::to_string(given.size()) + " components; this model needs " +
                                    std::to_string(S::dim) + " (" + join_names(S::states) + ")");
    return given;
}

}  // namespace system

/// An attitude quaternion must be finite and not zero (it is normalised before use). Throws
/// std::invalid_argument naming the value and the model.
void check_quaternion(const Eigen::Vector4d& q, const char* model);


/// The z-x-z Euler angles (ψ, θ, φ) recorded by every model that integrates the attitude. θ is
/// the angle between body z and the z axis of the inertial frame the attitude starts from (the
/// identity quaternion): not the nutation angle to G (nutation_angle below), unless G happens to
/// lie along that inertial z.
inline constexpr std::array<OutputInfo, 3> euler_outputs_info{{{"psi", "rad", "the z-x-z Euler angle psi: precession about the inertial z axis", false}, {"theta", "rad", "the z-x-z Euler angle theta: between body z and the start frame's inertial z (not the nutation angle to G: nutation_angle)", false}, {"phi", "rad", "the z-x-z Euler angle phi: proper rotation about body z", false}}};

/// The nutation angle proper ϑ: the angle between the body's z axis e = (0, 0, 1) (the symmetry
/// axis of the papers' bodies) and the angular momentum G (G = Jω + k for the gyrostat, the
/// system's K for the moving mass), both in body axes:
///   cos ϑ = e·G/|G| = G_z/|G|,   ϑ = atan2(√(G_x² + G_y²), G_z) ∈ [0, π]
/// (atan2: full precision near 0 and π, where acos loses √ε; ϑ = 0 at G = 0). It needs ω alone,
/// not the attitude, and is the angle paper 004 calls the nutation (the polar angle of G in the
/// body). Torque-free, G is fixed in space, so ϑ is also the angle between body z and the
/// inertial direction of G.
inline constexpr OutputInfo nutation_angle_info{"nutation_angle", "rad", "the nutation angle: between body z (the symmetry axis) and the angular momentum G, from omega alone", false};
inline double nutation_angle(const Vec3& G) { return std::atan2(std::hypot(G[0], G[1]), G[2]); }
inline void euler_outputs(const Eigen::Vector4d& q, double* out) {
    const Vec3 angles = euler_angles(q, EulerConvention::ZXZ);
    out[0] = angles[0], out[1] = angles[1], out[2] = angles[2];
}

/// `first` followed by `second` (to append the Euler angles to a model's own outputs, the
/// quaternion to ω).
template <class T, std::size_t N, std::size_t M>
constexpr std::array<T, N + M> concat(const std::array<T, N>& first, const std::array<T, M>& second) {
    std::array<T, N + M> all{};
    for (std::size_t i = 0; i < N; ++i) all[i] = first[i];
    for (std::size_t i = 0; i < M; ++i) all[N + i] = second[i];
    return all;
}

/// The state of the models that may integrate the attitude: ω, then the quaternion.
inline constexpr std::array<Quantity, 3> omega_states{{{"p", "rad/s", "angular velocity about body x", "omega"}, {"q", "rad/s", "angular velocity about body y", "omega"}, {"r", "rad/s", "angular velocity about body z", "omega"}}};
inline constexpr std::array<Quantity, 4> quaternion_states{{{"q_w", "1", "attitude quaternion, scalar part (body to inertial)", "quaternion"}, {"q_x", "1", "attitude quaternion, x", "quaternion"}, {"q_y", "1", "attitude quaternion, y", "quaternion"}, {"q_z", "1", "attitude quaternion, z", "quaternion"}}};
template <bool WithAttitude>
constexpr auto rate_states() {
    if constexpr (WithAttitude)
        return concat(omega_states, quaternion_states);
    else
        return omega_states;
}

/// A model's own outputs, followed by the Euler angles when it integrates the attitude.
template <bool WithAttitude, std::size_t N>
constexpr auto with_euler_outputs(const std::array<OutputInfo, N>& own) {
    if constexpr (WithAttitude)
        return concat(own, euler_outputs_info);
    else
        return own;
}

/// The completion of a short initial state for the models whose state starts with ω (and the
/// quaternion when `attitude`): ω alone (3), or ω and the quaternion (7) when the state has more
/// after them. The quaternion defaults to the identity, what follows (e.g. τ(0)) to zero.
template <class State, std::size_t N>
State complete_rate_state(const Eigen::VectorXd& given, bool attitude, const std::array<Quantity, N>& names) {
    constexpr int dim = State::RowsAtCompileTime;
    State y = State::Zero();
    if (attitude) y[3] = 1.0;
    if (given.size() == 3 || (attitude && given.size() == 7 && dim > 7)) {
        y.head(given.size()) = given;
        return y;
    }
    throw std::invalid_argument("initial state has " + std::to_string(given.size()) + " components; this model needs " +
                                std::to_string(dim) + " (" + system::join_names(names) + ") or omega alone (3)" +
                                (attitude && dim > 7 ? " or omega and the quaternion (7)" : ""));
}

/// The attitude part of a state (ω, then the quaternion (w, x, y, z) when WithAttitude, then what
/// the model adds), written once for the models that integrate the attitude only when asked
/// (model/gyrostat.hpp, model/torque_free.hpp, model/orthogonal.hpp): the projection onto
/// |q| = 1 and the quaternion's check (only with the attitude: without it the model has neither),
/// the completion of ω alone (identity attitude, what follows zero) and the Euler angles among the
/// outputs. Derived gives `states` and `model_name` (named in the errors).
template <class Derived, int Dim, bool WithAttitude>
class RateAttitude {
public:
    using State = Eigen::Matrix<double, Dim, 1>;
    static constexpr bool carries_attitude = WithAttitude;
    /// ω is a vector in body axes (model/frame.hpp).
    static constexpr std::array<int, 1> body_vectors{{0}};

    /// Keeps |q| = 1 to rounding: called by the integrators after each accepted step (and on the
    /// initial state, which may come at any scale: normalize_in_place neither overflows nor
    /// underflows).
    template <bool A = WithAttitude, std::enable_if_t<A, int> = 0>
    void project(State& y) const {
        normalize_in_place(y.template segment<4>(3));
    }
    template <bool A = WithAttitude, std::enable_if_t<A, int> = 0>
    void check_state(const State& y) const {
        check_quaternion(y.template segment<4>(3), Derived::model_name);
    }
    /// ω alone (or ω and the quaternion, when more follows) starts from the identity attitude.
    State initial_state(const Eigen::VectorXd& given) const {
        return complete_rate_state<State>(given, WithAttitude, Derived::states);
    }

protected:
    /// The Euler angles ψ, θ, φ at out[0..3) (with the attitude; nothing without).
    static void attitude_outputs(const State& y, double* out) {
        if constexpr (WithAttitude) euler_outputs(y.template segment<4>(3), out);
        (void)y, (void)out;
    }
};

}  // namespace gyrostat::model
