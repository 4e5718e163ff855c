// The explicit model behind the damper reduction: a rigid carrier plus a point mass on a spring
// with a viscous damper. Stiff when the damper is strong: the standard stiff test case.
#pragma once

#include <array>
#include <cmath>
#include <stdexcept>

#include "gyrostat/body.hpp"
#include "gyrostat/numeric/dual.hpp"
#include "gyrostat/model/frame.hpp"
#include "gyrostat/model/system.hpp"
#include "gyrostat/torque/set.hpp"

namespace gyrostat::model {

/// Carrier with principal moments J_B = diag(A1 − μρ², A2 − μρ², A3) about its own centre of
/// mass, so that (A1, A2, A3) are the system's moments with the mass at rest; a point mass μ
/// (reduced mass mM/(m + M)) attached at d0 = ρ e3 by an isotropic spring (Ω² = c/μ) and a
/// viscous damper (λ = δ/μ), displaced by u. State (body axes):
///   y = (ω, u, v),  v = u̇ (velocity of the mass relative to the carrier).
/// Derived in docs/papers/001_moving_mass.md §C:
///   d = d0 + u,  s = ω × d + v,  K = J_B ω + μ d × s                  (total angular momentum)
///   R = −2 ω × v − ω × (ω × d) − Ω² u − λ v
///   J_B ω̇ = M_ext − ω × K − μ [2 (d·v) ω − v (d·ω) − d (v·ω)] − μ d × R
///   u̇ = v,   v̇ = R − ω̇ × d
/// (the Schur complement of the implicit (ω̇, v̇) system is exactly J_B: no linear solve).
/// M_ext: the torques of the set, acting on the carrier. Invariants: |K| (conserved without
/// M_ext) and E = ½ ω·J_B ω + ½ μ |s|² + ½ μ Ω² |u|² (dE/dt = ω·M_ext − μλ|v|² ≤ 0).
/// Eigenvalues of the (u, v) block ≈ −λ/2 ± √(λ²/4 − Ω²): stiff for λ h ≫ 1 (use cvode_bdf).
class MovingMass {
public:
    static constexpr int dim = 9;
    using State = Eigen::Matrix<double, 9, 1>;
    static constexpr const char* family = "moving_mass";
    static constexpr std::array<Quantity, dim> states{{{"p", "rad/s", "angular velocity about body x", "omega"},
                                                        {"q", "rad/s", "angular velocity about body y", "omega"},
                                                        {"r", "rad/s", "angular velocity about body z", "omega"},
                                                        {"u_1", "m", "the mass's displacement from its attachment, body x", "displacement"},
                                                        {"u_2", "m", "the displacement, body y", "displacement"},
                                                        {"u_3", "m", "the displacement, body z", "displacement"},
                                                        {"v_1", "m/s", "the displacement's rate, body x", "velocity"},
                                                        {"v_2", "m/s", "the displacement's rate, body y", "velocity"},
                                                        {"v_3", "m/s", "the displacement's rate, body z", "velocity"}}};

    /// ω, u and v are vectors in body axes (model/frame.hpp); on a body given by its inertia
    /// tensor the mass moves about its attachment on the third principal axis.
    static constexpr std::array<int, 3> body_vectors{{0, 3, 6}};
    /// Its own numbers (as gyrostat.sensitivity names them) whose ∂f/∂p it gives in closed form
    /// (system::has_parameter_rate, parameter_rate below): λ.
    static constexpr std::array<const char*, 1> analytic_in{{"damping"}};

    MovingMass(Body system_body, double mass, double arm, double frequency, double damping, TorqueSet external)
        : body_(std::move(system_body)), torques_(external.in_principal_axes(system_body)), mu_(mass), rho_(arm),
          omega2_(frequency * frequency), lambda_(damping) {
        // the parameters are validated as those of the reduced torque
        torque::MovingMassDamper check(mass, arm, frequency, damping);
        (void)check;
        torques_.require_no_attitude("MovingMassModel");
        // The carrier is rigid (docs/papers/001_moving_mass.md): a rotor given here was ignored.
        if (body_.rotor().squaredNorm() != 0.0)
            throw std::invalid_argument("MovingMassModel: the carrier is a rigid body (rotor k = 0); this body has |k| = " +
                                        format_value(body_.rotor().norm()) +
                                        ": for a gyrostat with a damper use gyrostat.Model with a MovingMassDamper torque");
        const double shift = mu_ * rho_ * rho_;
        carrier_ = Vec3(body_.moments()[0] - shift, body_.moments()[1] - shift, body_.moments()[2]);
        if (!(carrier_[0] > 0.0) || !(carrier_[1] > 0.0))
            throw std::invalid_argument("MovingMass: the carrier's moments A1 − μρ² = " + format_value(carrier_[0]) +
                                        ", A2 − μρ² = " + format_value(carrier_[1]) +
                                        " must be positive (μρ² = " + format_value(shift) + ")");
        Body carrier_check(carrier_);  // triangle inequality of the carrier alone
        (void)carrier_check;
    }

    const Body& body() const { return body_; }
    const TorqueSet& torques() const { return torques_; }
    const Vec3& carrier_moments() const { return carrier_; }

    void rhs(double t, const State& y, State& dy) const {
        const Vec3 M = torques_.empty() ? Vec3::Zero() : torques_.total(t, y.head<3>(), body_.moments());
        std::array<double, dim> x, f;
        for (int i = 0; i < dim; ++i) x[i] = y[i];
        evaluate(x, {M[0], M[1], M[2]}, f);
        for (int i = 0; i < dim; ++i) dy[i] = f[i];
    }

    /// The exact ∂f/∂y: the same equations evaluated on dual numbers (numeric/dual.hpp), the
    /// external torques entering through their own ∂M/∂ω.
    using Jacobian = Eigen::Matrix<double, dim, dim>;
    void jacobian(double t, const State& y, Jacobian& jac) const {
        using D = Dual<dim>;
        std::array<D, dim> x, f;
        for (int i = 0; i < dim; ++i) x[i] = D::variable(y[i], i);
        Eigen::Matrix<double, 3, dim> along = Eigen::Matrix<double, 3, dim>::Zero();  // ω's part of each variable
        along.template leftCols<3>().setIdentity();
        evaluate(x, torque_along<dim>(t, y, along), f);
        for (int i = 0; i < dim; ++i)
            for (int k = 0; k < dim; ++k) jac(i, k) = f[i].d[k];
    }

    /// f and ∂f/∂y · s_j for up to four columns s_j at once (system::has_rate_with_products): the
    /// equations on dual numbers with one direction per column, whose values are f (the same
    /// operations as rhs's on doubles), where one directional evaluation per column would compute
    /// f's shared parts again each time. False for more columns (the whole Jacobian serves them).
    bool rate_with_products(double t, const State& y, const double* columns, std::size_t count, State& f,
                            double* products) const {
        switch (count) {
            case 1: rate_with_products_of<1>(t, y, columns, f, products); return true;
            case 2: rate_with_products_of<2>(t, y, columns, f, products); return true;
            case 3: rate_with_products_of<3>(t, y, columns, f, products); return true;
            case 4: rate_with_products_of<4>(t, y, columns, f, products); return true;
            default: return false;
        }
    }

    /// ∂f/∂λ (k = 0, the one number of analytic_in). λ enters through R alone, ∂R/∂λ = −v, and f
    /// is affine in R:
    ///   J_B ∂ω̇/∂λ = −μ d × ∂R = μ d × v,   ∂u̇/∂λ = 0,   ∂v̇/∂λ = ∂R − ∂ω̇/∂λ × d = −v − ∂ω̇/∂λ × d.
    void parameter_rate(std::size_t /*k*/, double /*t*/, const State& y, State& rate) const {
        const Vec3 u = y.segment<3>(3), v = y.tail<3>();
        const Vec3 d = Vec3(0.0, 0.0, rho_) + u;
        const Vec3 spin_rate = (mu_ * d.cross(v)).cwiseQuotient(carrier_);
        rate << spin_rate, Vec3::Zero(), -v - spin_rate.cross(d);
    }

    /// The equations above for any scalar T (double, or Dual for the Jacobian); M the external torque.
    template <class T>
    void evaluate(const std::array<T, dim>& y, const std::array<T, 3>& M, std::array<T, dim>& dy) const {
        const T &p = y[0], &q = y[1], &r = y[2], &u1 = y[3], &u2 = y[4], &u3 = y[5], &v1 = y[6], &v2 = y[7], &v3 = y[8];
        const double mu = mu_;
        const T d1 = u1, d2 = u2, d3 = rho_ + u3;
        const T s1 = q * d3 - r * d2 + v1, s2 = r * d1 - p * d3 + v2, s3 = p * d2 - q * d1 + v3;
        const T K1 = carrier_[0] * p + mu * (d2 * s3 - d3 * s2);
        const T K2 = carrier_[1] * q + mu * (d3 * s1 - d1 * s3);
        const T K3 = carrier_[2] * r + mu * (d1 * s2 - d2 * s1);
        const T wd = p * d1 + q * d2 + r * d3, ww = p * p + q * q + r * r;
        const T R1 = -2.0 * (q * v3 - r * v2) - (p * wd - d1 * ww) - omega2_ * u1 - lambda_ * v1;
        const T R2 = -2.0 * (r * v1 - p * v3) - (q * wd - d2 * ww) - omega2_ * u2 - lambda_ * v2;
        const T R3 = -2.0 * (p * v2 - q * v1) - (r * wd - d3 * ww) - omega2_ * u3 - lambda_ * v3;
        const T dv = d1 * v1 + d2 * v2 + d3 * v3, vw = v1 * p + v2 * q + v3 * r;
        const T f1 = M[0] - (q * K3 - r * K2) - mu * (2.0 * dv * p - v1 * wd - d1 * vw) - mu * (d2 * R3 - d3 * R2);
        const T f2 = M[1] - (r * K1 - p * K3) - mu * (2.0 * dv * q - v2 * wd - d2 * vw) - mu * (d3 * R1 - d1 * R3);
        const T f3 = M[2] - (p * K2 - q * K1) - mu * (2.0 * dv * r - v3 * wd - d3 * vw) - mu * (d1 * R2 - d2 * R1);
        const T a1 = f1 / carrier_[0], a2 = f2 / carrier_[1], a3 = f3 / carrier_[2];
        dy = {a1, a2, a3, v1, v2, v3, R1 - (a2 * d3 - a3 * d2), R2 - (a3 * d1 - a1 * d3), R3 - (a1 * d2 - a2 * d1)};
    }

    /// |K| (conserved without external torques) and E (dissipated by the damper): see above.
    /// Outputs: |K|, E, and |u|/ρ, the mass's displacement against its arm: the explicit model is
    /// a point mass on a linear spring near its attachment, so |u|/ρ ≪ 1 is its assumption (a soft
    /// spring, Ω near the spin rate, lets the mass drift metres on a 1 m arm; the validity check
    /// reports it like every other assumption).
    /// The nutation angle ϑ is that of the system's angular momentum K (carrier and mass) to the
    /// carrier's z axis (model/system.hpp: nutation_angle).
    static constexpr std::array<OutputInfo, 5> outputs_info{
        {{"angular_momentum_norm", "kg m^2/s", "|G| = |J omega + k|, the norm of the angular momentum", true, true}, {"energy", "J", "the total energy: the carrier's rotation, the mass's motion and the spring", false, true}, {"displacement_ratio", "1", "|u|/rho: the mass's displacement against its arm (the model assumes it small)", false}, nutation_angle_info,
         {"kinetic_energy", "J", "T = omega . J omega / 2 with J the system's moments with the mass at rest: the rotation's energy the reduced and averaged models carry", false, true}}};
    void outputs(double, const State& y, double* out) const {
        const Vec3 w = y.head<3>(), u = y.segment<3>(3), v = y.tail<3>();
        const Vec3 d = Vec3(0, 0, rho_) + u;
        const Vec3 s = w.cross(d) + v;
        const Vec3 K = carrier_.cwiseProduct(w) + mu_ * d.cross(s);
        out[0] = K.norm();
        out[1] = 0.5 * w.dot(carrier_.cwiseProduct(w)) + 0.5 * mu_ * s.squaredNorm() + 0.5 * mu_ * omega2_ * u.squaredNorm();
        out[2] = u.norm() / rho_;
        out[3] = nutation_angle(K);
        out[4] = 0.5 * w.dot(body_.moments().cwiseProduct(w));
    }
    /// |K| is a first integral without external torques (the damper is internal).
    bool keeps(std::size_t /*output*/) const { return torques_.empty(); }

    /// (u, v) of the forced quasi-static motion for a given ω (docs/papers/001 §C): the initial
    /// state that starts the mass without a free oscillation. Elastic part
    /// u1 = −Ω⁻² [ω (ω·d0) − d0 |ω|² + ω̇ × d0] with ω̇ from the torque-free Euler equations of
    /// the system, damper part u2 = −λ Ω⁻² u̇1; v = u̇1 + u̇2 from the same series.
    /// ω and the state returned are in the frame the body was given in (model/frame.hpp).
    State quasi_static_state(const Vec3& omega) const;

private:
    /// The external torque on dual numbers with N directions: M, and its derivative along each
    /// direction from the torques' ∂M/∂ω and the direction's ω part (a column of `along`).
    template <int N>
    std::array<Dual<N>, 3> torque_along(double t, const State& y, const Eigen::Matrix<double, 3, N>& along) const {
        std::array<Dual<N>, 3> M{Dual<N>(0.0), Dual<N>(0.0), Dual<N>(0.0)};
        if (torques_.empty()) return M;
        const Vec3 m = torques_.total(t, y.head<3>(), body_.moments());
        const Eigen::Matrix<double, 3, N> dm = torques_.jacobian(t, y.head<3>(), body_.moments()) * along;
        for (int i = 0; i < 3; ++i) {
            M[i] = Dual<N>(m[i]);
            for (int j = 0; j < N; ++j) M[i].d[j] = dm(i, j);
        }
        return M;
    }

    template <int N>
    void rate_with_products_of(double t, const State& y, const double* columns, State& f, double* products) const {
        using D = Dual<N>;
        std::array<D, dim> x, rate;
        Eigen::Matrix<double, 3, N> along;  // ω's part of each column
        for (int i = 0; i < dim; ++i) {
            x[i] = D(y[i]);
            for (int j = 0; j < N; ++j) x[i].d[j] = columns[j * dim + i];
        }
        for (int j = 0; j < N; ++j) along.col(j) = Vec3(columns[j * dim], columns[j * dim + 1], columns[j * dim + 2]);
        evaluate(x, torque_along<N>(t, y, along), rate);
        for (int i = 0; i < dim; ++i) {
            f[i] = rate[i].v;
            for (int j = 0; j < N; ++j) products[j * dim + i] = rate[i].d[j];
        }
    }

    State quasi_static_state_in_principal_axes(const Vec3& omega) const;

    Body body_;
    TorqueSet torques_;
    double mu_, rho_, omega2_, lambda_;
    Vec3 carrier_;
};

inline MovingMass::State MovingMass::quasi_static_state(const Vec3& omega) const {
    Vec3 principal = omega;
    frame::rotate_vector(body_, principal.data(), frame::To::Principal);
    State y = quasi_static_state_in_principal_axes(body_.principal() ? omega : principal);
    frame::convert_state<MovingMass>(body_, y.data(), frame::To::User);
    return y;
}

inline MovingMass::State MovingMass::quasi_static_state_in_principal_axes(const Vec3& omega) const {
    // Taylor coefficients of ω(t) along J ω̇ = Jω × ω (system moments), orders 0..4.
    constexpr int N = 4;
    const Vec3& J = body_.moments();
    std::array<Vec3, N + 1> W;
    W[0] = omega;
    for (int k = 0; k < N; ++k) {
        Vec3 s = Vec3::Zero();
        for (int i = 0; i <= k; ++i) s += J.cwiseProduct(W[i]).cross(W[k - i]);
        W[k + 1] = s.cwiseQuotient(J) / (k + 1);
    }
    auto derivative = [](const std::array<Vec3, N + 1>& a) {
        std::array<Vec3, N + 1> d;
        for (int k = 0; k < N; ++k) d[k] = (k + 1) * a[k + 1];
        d[N] = Vec3::Zero();
        return d;
    };
    const Vec3 d0(0.0, 0.0, rho_);
    const auto Wd = derivative(W);
    std::array<Vec3, N + 1> u1;
    for (int k = 0; k <= N; ++k) {
        Vec3 acc = Vec3::Zero();
        for (int i = 0; i <= k; ++i) acc += W[i].dot(d0) * W[k - i] - W[i].dot(W[k - i]) * d0;
        acc += Wd[k].cross(d0);
        u1[k] = -acc / omega2_;
    }
    const auto u1d = derivative(u1);
    std::array<Vec3, N + 1> u;
    for (int k = 0; k <= N; ++k) u[k] = u1[k] - lambda_ / omega2_ * u1d[k];
    const auto ud = derivative(u);
    State y;
    y << omega, u[0], ud[0];
    return y;
}

}  // namespace gyrostat::model
