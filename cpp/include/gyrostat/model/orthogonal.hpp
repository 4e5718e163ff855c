// Paper 004: a gyrostat under a servo torque orthogonal to its angular momentum G and its angular
// velocity ω (Makeev). See docs/papers/004_orthogonal_torque.md.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "gyrostat/attitude.hpp"
#include "gyrostat/body.hpp"
#include "gyrostat/model/system.hpp"
#include "gyrostat/model/torque_free.hpp"
#include "gyrostat/torque/set.hpp"

namespace gyrostat::model {

/// The magnitude L(t) of the servo torque: a value type evaluated in C++ (no Python call per
/// right-hand side). L is signed: L < 0 means a torque along −Q.
///   constant:    L(t) = c0
///   polynomial:  L(t) = Σ_i c_i tⁱ                        (coefficients c0, c1, …)
///   harmonic:    L(t) = L0 + Σ_i A_i sin(w_i t + φ_i)
///   tabulated:   values L_i at strictly increasing times t_i; linear or cubic Hermite
///                interpolation (slopes by finite differences: centred inside, one-sided at the
///                ends); outside [t_0, t_n] the end value is held.
class MagnitudeLaw {
public:
    enum class Kind { Constant, Polynomial, Harmonic, Tabulated };

    static MagnitudeLaw constant(double value) {
        check_finite(value, "MagnitudeLaw.constant: value");
        MagnitudeLaw law;
        law.kind_ = Kind::Constant;
        law.a_ = {value};
        return law;
    }
    static MagnitudeLaw polynomial(std::vector<double> coefficients) {
        if (coefficients.empty()) throw std::invalid_argument("MagnitudeLaw.polynomial: no coefficients given");
        for (std::size_t i = 0; i < coefficients.size(); ++i)
            check_finite(coefficients[i], "MagnitudeLaw.polynomial: coefficient " + std::to_string(i));
        MagnitudeLaw law;
        law.kind_ = Kind::Polynomial;
        law.a_ = std::move(coefficients);
        return law;
    }
    static MagnitudeLaw harmonic(double mean, std::vector<double> amplitudes, std::vector<double> frequencies,
                                 std::vector<double> phases) {
        check_finite(mean, "MagnitudeLaw.harmonic: mean L0");
        if (phases.empty()) phases.assign(amplitudes.size(), 0.0);
        if (amplitudes.size() != frequencies.size() || amplitudes.size() != phases.size())
            throw std::invalid_argument("MagnitudeLaw.harmonic: " + std::to_string(amplitudes.size()) + " amplitudes, " +
                                        std::to_string(frequencies.size()) + " frequencies and " +
                                        std::to_string(phases.size()) + " phases: give one of each per term");
        for (std::size_t i = 0; i < amplitudes.size(); ++i) {
            check_finite(amplitudes[i], "MagnitudeLaw.harmonic: amplitude " + std::to_string(i));
            check_finite(frequencies[i], "MagnitudeLaw.harmonic: frequency " + std::to_string(i));
            check_finite(phases[i], "MagnitudeLaw.harmonic: phase " + std::to_string(i));
        }
        MagnitudeLaw law;
        law.kind_ = Kind::Harmonic;
        law.a_ = {mean};
        law.a_.insert(law.a_.end(), amplitudes.begin(), amplitudes.end());
        law.b_ = std::move(frequencies);
        law.c_ = std::move(phases);
        return law;
    }
    static MagnitudeLaw tabulated(std::vector<double> times, std::vector<double> values, bool cubic = false) {
        if (times.size() != values.size())
            throw std::invalid_argument("MagnitudeLaw.tabulated: " + std::to_string(times.size()) + " times but " +
                                        std::to_string(values.size()) + " values");
        if (times.size() < 2) throw std::invalid_argument("MagnitudeLaw.tabulated: needs at least 2 points");
        for (std::size_t i = 0; i < times.size(); ++i) {
            check_finite(times[i], "MagnitudeLaw.tabulated: time " + std::to_string(i));
            check_finite(values[i], "MagnitudeLaw.tabulated: value " + std::to_string(i));
            if (i > 0 && !(times[i] > times[i - 1]))
                throw std::invalid_argument("MagnitudeLaw.tabulated: times must increase strictly; time " +
                                            std::to_string(i) + " = " + format_value(times[i]) + " follows " +
                                            format_value(times[i - 1]) + " (spacing " +
                                            format_value(times[i] - times[i - 1]) + ")");
        }
        MagnitudeLaw law;
        law.kind_ = Kind::Tabulated;
        law.cubic_ = cubic;
        const std::size_t n = times.size();
        law.c_.assign(n, 0.0);  // slopes for the cubic Hermite form
        for (std::size_t i = 0; i < n; ++i) {
            const std::size_t lo = i == 0 ? 0 : i - 1, hi = i + 1 == n ? n - 1 : i + 1;
            // halves first: the differences of finite numbers may overflow, their halves do not
            law.c_[i] = (0.5 * values[hi] - 0.5 * values[lo]) / (0.5 * times[hi] - 0.5 * times[lo]);
        }
        law.a_ = std::move(times);
        law.b_ = std::move(values);
        return law;
    }

    Kind kind() const { return kind_; }
    bool cubic() const { return cubic_; }
    const std::vector<double>& a() const { return a_; }
    const std::vector<double>& b() const { return b_; }
    const std::vector<double>& c() const { return c_; }

    double operator()(double t) const {
        switch (kind_) {
            case Kind::Constant: return a_[0];
            case Kind::Polynomial: {
                double v = 0.0;
                for (std::size_t i = a_.size(); i-- > 0;) v = v * t + a_[i];
                return v;
            }
            case Kind::Harmonic: {
                double v = a_[0];
                for (std::size_t i = 0; i < b_.size(); ++i) v += a_[i + 1] * std::sin(b_[i] * t + c_[i]);
                return v;
            }
            case Kind::Tabulated: {
                const std::vector<double>& ts = a_;
                if (t <= ts.front()) return b_.front();
                if (t >= ts.back()) return b_.back();
                const std::size_t j = static_cast<std::size_t>(std::upper_bound(ts.begin(), ts.end(), t) - ts.begin());
                const std::size_t i = j - 1;
                const double half_h = 0.5 * ts[j] - 0.5 * ts[i];  // halves: no overflow for finite times
                const double s = (0.5 * t - 0.5 * ts[i]) / half_h;
                if (!cubic_) return (1.0 - s) * b_[i] + s * b_[j];
                const double s2 = s * s, s3 = s2 * s;
                return (2 * s3 - 3 * s2 + 1) * b_[i] + (s3 - 2 * s2 + s) * 2.0 * (half_h * c_[i]) +
                       (-2 * s3 + 3 * s2) * b_[j] + (s3 - s2) * 2.0 * (half_h * c_[j]);
            }
        }
        return 0.0;
    }

private:
    static void check_finite(double x, const std::string& what) {
        if (!std::isfinite(x)) throw std::invalid_argument(what + " = " + format_value(x) + " is not finite");
    }
    Kind kind_ = Kind::Constant;
    bool cubic_ = false;
    std::vector<double> a_{0.0}, b_, c_;
};

/// Gyrostat (moments J = diag(A1, A2, A3), rotor momentum k) under the servo torque of paper 004
/// plus, optionally, other torques ΣM_i (TorqueSet).
///
///   G = J ω + k,  Q = ω × G,  δ = η |ω| |G|   (η = 1e-3 by default)
///   n_δ(|Q|) = |Q|                   for |Q| ≥ δ
///            = (|Q|² + δ²) / (2δ)    for |Q| < δ      (C¹ at |Q| = δ; n_δ(0) = δ/2)
///   M_servo = L(t) Q / n_δ            (= L e_L, e_L = Q/|Q|, wherever |Q| ≥ δ)
///   J ω̇ = M_servo + ΣM_i − ω × G  = −g Q + ΣM_i,   g = 1 − L(t)/n_δ
///   τ̇   = g                        (the paper's time change (10); τ(0) = 0 by convention)
///   q̇   = ½ q ⊗ (0, ω)             (attitude, only when asked)
///
/// Regularisation: the direction e_L is undefined at Q = 0 (ω ∥ G or ω = 0: the permanent
/// rotations of the Zhukovsky–Volterra gyrostat), and e_L turns at a rate ∝ |L|/|Q| near it.
/// Below the threshold |Q| < δ the magnitude is tapered to L|Q|/n_δ → 0 (the prescribed L is not
/// applied there; the Python layer flags those times); at and above it the paper's torque is
/// applied exactly. M stays parallel to Q, so |G|² and h = ω·Jω stay exact first integrals and
/// ω(t) = ω_ZV(τ(t)) stays exact; at Q = 0 the torque vanishes and the permanent rotation is an
/// equilibrium. (The smooth form L Q/√(|Q|² + δ²) of the docs also works but changes L by a
/// relative δ²/2|Q|² everywhere: τ(60) moves by 7.6e-4 in scene S1.)
///
/// Q = 0 exactly (rest, or any permanent rotation ω ∥ G, with or without a rotor) has one rule
/// (servo_gain): e_L has no direction, the servo applies nothing (M = 0), τ runs with t (g = 1)
/// and the point is flagged `regularised` (the prescribed L is not applied), whatever δ is there
/// (δ = 0 at ω = 0, δ > 0 at a permanent rotation). Every Q ≠ 0 has ω ≠ 0, G ≠ 0, hence δ > 0 and
/// n_δ ≥ δ/2 > 0: nothing divides by zero.
///
/// State layout: (p, q, r, τ) or (p, q, r, q_w, q_x, q_y, q_z, τ); τ(t0) = 0 when the initial
/// state is given as ω (or ω and the quaternion).
/// Outputs recorded: |G| = |Jω + k| and h = ω·Jω (exact without other torques), g = dτ/dt,
/// L(t), |Q|, δ, `regularised` (1 where |Q| < δ: the prescribed L was not applied), the angles
/// θ_G, φ_G of G in body axes (paper (15): G/|G| = (sin θ sin φ, sin θ cos φ, cos θ)) and, with
/// the attitude, the z-x-z Euler angles ψ, θ, φ.
template <bool WithAttitude>
class OrthogonalTorque : public RateAttitude<OrthogonalTorque<WithAttitude>, WithAttitude ? 8 : 4, WithAttitude> {
public:
    static constexpr int dim = WithAttitude ? 8 : 4;
    static constexpr const char* model_name = "OrthogonalTorque";
    static constexpr int tau_index = dim - 1;
    using State = Eigen::Matrix<double, dim, 1>;
    static constexpr const char* family = "orthogonal_torque";
    static constexpr auto states = concat(rate_states<WithAttitude>(), std::array<Quantity, 1>{{{"tau", "s", "the servo's clock tau (d tau/dt = g)"}}});

    /// smooth = true selects the form n_δ = √(|Q|² + δ²) of the docs' first recommendation
    /// (smooth everywhere, but the applied L is off by a relative δ²/2|Q|² at every |Q|).
    OrthogonalTorque(Body body, MagnitudeLaw law, TorqueSet torques = {}, double eta = 1e-3, bool smooth = false)
        : body_(std::move(body)), law_(std::move(law)), torques_(torques.in_principal_axes(body)), eta_(eta), smooth_(smooth) {
        if (!std::isfinite(eta) || eta <= 0.0)
            throw std::invalid_argument("OrthogonalTorque: regularisation eta = " + format_value(eta) +
                                        " must be finite and positive (the torque direction Q/|Q| is undefined at Q = 0)");
        if constexpr (!WithAttitude) torques_.require_no_attitude("OrthogonalModel(attitude=False)");
    }

    const Body& body() const { return body_; }
    const MagnitudeLaw& law() const { return law_; }
    const TorqueSet& torques() const { return torques_; }
    double eta() const { return eta_; }
    bool smooth() const { return smooth_; }
    bool supports_taylor() const { return false; }

    /// n_δ(|Q|): |Q| above the threshold δ, (|Q|² + δ²)/(2δ) below it (or √(|Q|² + δ²) when smooth).
    double denominator(double q_norm, double delta) const {
        if (smooth_) return std::sqrt(q_norm * q_norm + delta * delta);
        return q_norm >= delta ? q_norm : (q_norm * q_norm + delta * delta) / (2.0 * delta);
    }

    /// L(t)/n_δ(|Q|) for Q ≠ 0, and 0 at Q = 0 (the class comment's one rule): M_servo = gain·Q,
    /// g = 1 − gain.
    double servo_gain(double t, double q_norm, double delta) const {
        return q_norm > 0.0 ? law_(t) / denominator(q_norm, delta) : 0.0;
    }
    /// Whether the prescribed L is not applied at (|Q|, δ): inside the band |Q| < δ, or at Q = 0.
    static bool regularised(double q_norm, double delta) { return q_norm < delta || q_norm == 0.0; }

    /// dτ/dt = g(t, ω) = 1 − L(t)/n_δ(|Q|) (1 at Q = 0).
    double tau_rate(double t, const Vec3& omega) const {
        const Vec3 G = body_.angular_momentum(omega);
        const Vec3 Q = omega.cross(G);
        return 1.0 - servo_gain(t, Q.norm(), eta_ * omega.norm() * G.norm());
    }

    /// The servo torque L(t) Q/n_δ(|Q|) in body axes.
    Vec3 servo_torque(double t, const Vec3& omega) const {
        const Vec3 G = body_.angular_momentum(omega);
        const Vec3 Q = omega.cross(G);
        return servo_gain(t, Q.norm(), eta_ * omega.norm() * G.norm()) * Q;
    }

    /// ω̇ = J⁻¹ (−g Q + ΣM_i);  q̇ = ½ q ⊗ (0, ω);  τ̇ = g   (equations in the class comment).
    void rhs(double t, const State& y, State& dy) const {
        const Vec3 omega = y.template head<3>();
        const Vec3 G = body_.moments().cwiseProduct(omega) + body_.rotor();
        const Vec3 Q = omega.cross(G);
        const double g = 1.0 - servo_gain(t, Q.norm(), eta_ * omega.norm() * G.norm());
        Vec3 m = -g * Q;
        Eigen::Vector4d attitude;
        if (!torques_.empty()) m += torques_.total(t, omega, body_.moments(), system::attitude_of<OrthogonalTorque>(y, attitude));
        dy.template head<3>() = body_.inverse_moments().cwiseProduct(m);
        if constexpr (WithAttitude) {
            dy.template segment<4>(3) = quaternion_rate(y.template segment<4>(3), omega);
        }
        dy[tau_index] = g;
    }

    /// ∂f/∂y of the equations above. With G = Jω + k, Q = ω × G, δ = η|ω||G|:
    ///   ∂Q/∂ω = [ω]× J − [G]×,  ∂δ/∂ω = η (|G| ω/|ω| + |ω| J G/|G|)ᵀ,
    ///   ∂n/∂ω = Qᵀ ∂Q/∂ω / |Q|                              (|Q| ≥ δ),
    ///         = Qᵀ ∂Q/∂ω / δ + (½ − |Q|²/(2δ²)) ∂δ/∂ω       (|Q| < δ: the regularised branch),
    ///         = (Qᵀ ∂Q/∂ω + δ ∂δ/∂ω) / n                     (smooth),
    ///   ∂g/∂ω = L(t)/n² ∂n/∂ω  (0 at Q = 0, where g = 1),
    ///   ∂ω̇/∂ω = J⁻¹ (−Q ∂g/∂ω − g ∂Q/∂ω + ΣM_i'),  ∂ω̇/∂q = J⁻¹ ΣM_q (TorqueSet::add_attitude_jacobian),
    ///   ∂τ̇/∂ω = ∂g/∂ω; the quaternion rows as in
    /// quaternion_rate_jacobian; nothing depends on τ.
    using Jacobian = Eigen::Matrix<double, dim, dim>;
    void jacobian(double t, const State& y, Jacobian& jac) const {
        jac.setZero();
        const Vec3 omega = y.template head<3>();
        const Vec3& J = body_.moments();
        const Vec3 G = J.cwiseProduct(omega) + body_.rotor();
        const Vec3 Q = omega.cross(G);
        const double w_norm = omega.norm(), G_norm = G.norm(), q_norm = Q.norm();
        const double d = eta_ * w_norm * G_norm;
        const double n = denominator(q_norm, d);
        const Mat3 dQ = skew(omega) * J.asDiagonal() - skew(G);
        Eigen::RowVector3d dg = Eigen::RowVector3d::Zero();
        double g = 1.0;
        if (q_norm > 0.0) {
            const double L = law_(t);
            g = 1.0 - L / n;
            Eigen::RowVector3d dd = Eigen::RowVector3d::Zero();
            if (w_norm > 0.0 && G_norm > 0.0)
                dd = eta_ * (G_norm / w_norm * omega.transpose() + w_norm / G_norm * J.cwiseProduct(G).transpose());
            const Eigen::RowVector3d QdQ = Q.transpose() * dQ;
            Eigen::RowVector3d dn;
            if (smooth_) dn = (QdQ + d * dd) / n;
            else if (q_norm >= d) dn = QdQ / q_norm;
            else dn = QdQ / d + (0.5 - q_norm * q_norm / (2.0 * d * d)) * dd;
            dg = L / (n * n) * dn;
        }
        Mat3 dm = -Q * dg - g * dQ;
        Eigen::Vector4d attitude;
        if (!torques_.empty()) dm += torques_.jacobian(t, omega, J, system::attitude_of<OrthogonalTorque>(y, attitude));
        jac.template topLeftCorner<3, 3>() = body_.inverse_moments().asDiagonal() * dm;
        jac.template block<1, 3>(tau_index, 0) = dg;
        if constexpr (WithAttitude) {
            quaternion_rate_jacobian(jac, 3, y.template segment<4>(3), omega);
            Eigen::Matrix<double, 3, 4> d_attitude = Eigen::Matrix<double, 3, 4>::Zero();
            if (torques_.add_attitude_jacobian(t, omega, J, y.template segment<4>(3), d_attitude))
                jac.template block<3, 4>(0, 3) = body_.inverse_moments().asDiagonal() * d_attitude;
        }
    }

    // --- Splitting (integrate/splitting.hpp) ---------------------------------------------------
    // With G = Jω + k and Q = ω × G, −g Q = −Q + (L/n_δ) Q, so f = f_free + f_pert with
    //   f_free = (J⁻¹ G × ω,  ½ q ⊗ (0, ω),  1)      the free gyrostat (exact: FreeBodyFlow), τ = t;
    //   f_pert = (J⁻¹ (L(t) Q/n_δ + ΣM(t, ω)),  0,  −L(t)/n_δ)   the servo torque and the other
    //            torques with t frozen: one 8th-order step on (ω, τ) (integrate::PerturbationFlow).
    // With L = 0 and no other torque the splitting is the exact flow. The servo torque is along
    // Q ⊥ G, so each sub-flow keeps |G| (the free one exactly, the 8th-order step to its order).

    /// Throws std::invalid_argument naming the body when the free gyrostat has no exact flow (a
    /// rotor off the symmetry axis, or an asymmetric body with a rotor).
    void require_splitting() const {
        FreeBodyFlow::require_closed_form(body_, "splitting");
        if (const char* name = torques_.needs_attitude())
            throw std::invalid_argument(std::string("splitting: ") + name +
                                        " depends on the attitude, which the orthogonal-torque model's perturbation "
                                        "sub-flow (omega, tau) does not carry: use dop853 or an implicit method");
    }
    /// y ← the exact free flow over h; τ advances by h.
    void free_flow(double h, State& y) const {
        if constexpr (WithAttitude) {
            const FreeBodyFlow flow(body_, y.template head<3>(), y.template segment<4>(3), 0.0, true, Phases::Double);
            y.template head<7>() = flow.at(h);
        } else {
            const FreeBodyFlow flow(body_, y.template head<3>(), Eigen::Vector4d(1, 0, 0, 0), 0.0, false, Phases::Double);
            y.template head<3>() = flow.omega(h);
        }
        y[tau_index] += h;
    }
    /// |G| = |Jω| is a first integral the splitting projects on (a rigid body, and every other
    /// torque keeps it; the servo torque always does).
    bool keeps_momentum_norm() const { return body_.rotor().squaredNorm() == 0.0 && torques_.keeps_momentum_norm(); }

    /// The perturbation (model/system.hpp): a rate on (ω, τ) at frozen time t.
    Eigen::Vector4d perturbed_part(const State& y) const { return Eigen::Vector4d(y[0], y[1], y[2], y[tau_index]); }
    void set_perturbed_part(State& y, const Eigen::Vector4d& x) const {
        y.template head<3>() = x.template head<3>();
        y[tau_index] = x[3];
    }
    Eigen::Vector4d perturbation_rate(double t, const Eigen::Vector4d& state) const {
        const Vec3& J = body_.moments();
        const Vec3 omega = state.template head<3>();
        const Vec3 G = J.cwiseProduct(omega) + body_.rotor();
        const Vec3 Q = omega.cross(G);
        const double servo = servo_gain(t, Q.norm(), eta_ * omega.norm() * G.norm());
        Vec3 m = servo * Q;
        if (!torques_.empty()) m += torques_.total(t, omega, J);
        Eigen::Vector4d rate;
        rate.template head<3>() = body_.inverse_moments().cwiseProduct(m);
        rate[3] = -servo;
        return rate;
    }

    static constexpr std::array<OutputInfo, 10> own_outputs{{{"angular_momentum_norm", "kg m^2/s", "|G| = |J omega + k|, the norm of the angular momentum", true, true},
                                                            {"h", "kg m^2/s^2", "omega . J omega (= 2T)", true},
                                                            {"g", "1", "d tau/dt, the servo's gain", false},
                                                            {"L", "N m", "the torque's magnitude law L(t)", false},
                                                            {"Q_norm", "kg m^2/s^2", "|omega x G|, the norm of the torque's direction before normalising", false},
                                                            {"delta", "kg m^2/s^2", "eta |omega| |G|, the regularisation threshold", false},
                                                            {"regularised", "1", "1 where |omega x G| is below delta and the torque is regularised, else 0", false},
                                                            {"theta_G", "rad", "the polar angle of G in body axes", false},
                                                            {"phi_G", "rad", "the azimuth of G in body axes", false},
                                                            nutation_angle_info}};
    static constexpr auto outputs_info = with_euler_outputs<WithAttitude>(own_outputs);
    void outputs(double t, const State& y, double* out) const {
        const Vec3 omega = y.template head<3>();
        const Vec3 G = body_.angular_momentum(omega);
        const double q_norm = omega.cross(G).norm();
        const double d = eta_ * omega.norm() * G.norm();
        out[0] = G.norm();
        out[1] = omega.dot(body_.moments().cwiseProduct(omega));
        out[2] = tau_rate(t, omega);
        out[3] = law_(t);
        out[4] = q_norm;
        out[5] = d;
        out[6] = regularised(q_norm, d) ? 1.0 : 0.0;
        out[7] = std::atan2(std::hypot(G[0], G[1]), G[2]);
        out[8] = std::atan2(G[0], G[1]);
        // the same angle as theta_G under the name every family records (model/system.hpp)
        out[9] = nutation_angle(G);
        this->attitude_outputs(y, out + 10);
    }
    /// |G| and h are kept by the servo's torque (orthogonal to ω and G); other torques change them.
    bool keeps(std::size_t /*output*/) const { return torques_.empty(); }
    /// The free rigid body's separatrix at ω (Body::separatrix; NaN with a rotor).
    double separatrix(const State& y) const { return body_.separatrix(y.template head<3>()); }

private:
    Body body_;
    MagnitudeLaw law_;
    TorqueSet torques_;
    double eta_;
    bool smooth_ = false;
};

}  // namespace gyrostat::model
