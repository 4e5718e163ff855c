// The Taylor method on the variational equations of the gyrostat under constant and linear
// torques (model/variational.hpp): the state y and its sensitivities S_j = ∂y/∂p_j integrated
// together by the step loop of taylor.hpp.
//
// The equations. With torques M = M0 − D ω the rate is a quadratic polynomial (affine_euler.hpp),
//   ω̇_i = f_i(ω) = Q_i ω_j ω_k + Σ_l L_il ω_l + C_i,      (i, j, k) cyclic,
//   q̇   = ½ q ⊗ (0, ω),
// Q_i = J_i⁻¹ (A_j − A_k), L = J⁻¹ (−D − [k×]), C = J⁻¹ M0 (model::AffineEulerRate). The augmented
// system Y = (y, S_1, …, S_m),
//   S_j' = ∂f/∂y(y) S_j + ∂f/∂p_j(y),
//   ∂f/∂y(y) S:  S_ω,i' = Q_i (ω_j S_k + S_j ω_k) + Σ_l L_il S_l,   S_q' = ½ (q ⊗ (0, S_ω) + S_q ⊗ (0, ω)),
//   ∂f/∂p_j(y):  Q'_i ω_j ω_k + Σ_l L'_il ω_l + C'_i   (0 on q, and for a column of the initial state),
// is polynomial in Y: bilinear in (y, S_j) plus quadratic in y. f is linear in its coefficients,
// so ∂f/∂p_j is f's form with the coefficients' derivatives Q', L', C', taken as the central
// difference of the coefficients of the two models the caller built with p_j moved by ±step
// (AffineEulerRate::derivative): the same number as model/variational.hpp's central difference
// of the two rates (DOP853's and CVODE's path) up to rounding, and that rounding is smaller (~ε of
// the coefficients over 2·step, against ~ε|f| over 2·step: for a rotor component, 2.9e-12 against
// 1.0e-10 of ∂y/∂p, measured against Richardson in tests/test_sensitivity_taylor.py).
//
// The recursion. With y(t + h) = Σ y[n] hⁿ and S_j(t + h) = Σ S_j[n] hⁿ, the n-th coefficient of
// a product along the solution is a Cauchy product of the factors' coefficients, so
//   y[n+1]   = the model's own recursion (Gyrostat::taylor_coefficients: euler_taylor_recursion,
//              or its AVX2 form; the same coefficients as the plain Taylor method's),
//   S_j[n+1] = ([∂f/∂y(y) S_j]_n + [∂f/∂p_j(y)]_n) / (n + 1)      (model::affine_euler_tangent_order)
// where [∂f/∂y(y) S]_n = Q_i Σ_{m≤n} (ω_j[m] S_k[n−m] + S_j[m] ω_k[n−m]) + Σ_l L_il S_l[n] and
// ½ Σ_{m≤n} (q[m] ⊗ (0, S_ω[n−m]) + S_q[m] ⊗ (0, ω[n−m])), written directly as bilinear Cauchy
// products (exact to rounding: f is quadratic), and [∂f/∂p_j(y)]_n = Q'_i P_i[n] + Σ_l L'_il ω_l[n]
// + C'_i δ_{n0} with P_i[n] = Σ_{m≤n} ω_j[m] ω_k[n−m], once per step for all parameter columns.
// y's coefficients do not depend on S: they come first, whole, then each column's order by order.
// A step costs the plain recursion plus ~(6 + 24)(n + 1) multiply-adds per order n and column (ω;
// q), and P once: ~3 (n + 1).
//
// The step. Jorba & Zou's rule (taylor.hpp) on y's block alone (the plain run's order and steps),
// or, with Options::sensitivity_error_control, on every block b of Y (y, then each S_j), each with
// its own tolerance as the DOP853 path's error norm (atol[b]; rtol shared): block b is in relative
// mode when rtol·‖Y_b‖∞ > atol[b] (ε_b = rtol, scale ‖Y_b‖∞), else absolute (ε_b = atol[b], scale 1);
// the order is taylor.hpp's for the smallest ε_b (order_for), and the step the least over the
// blocks of ρ_b·safety_for(ε_b, p), ρ_b = min((scale_b/‖Y_b[p−1]‖∞)^{1/(p−1)}, (scale_b/‖Y_b[p]‖∞)^{1/p}):
// each block's local truncation error stays near local_error_fraction(ε_b)·ε_b of its scale. No
// step is rejected. Below ε = 1e-12 (compensate_below) every component is carried with its
// rounding error (advance_compensated; y's rate error from the model's taylor_rate_error). After
// each step y's quaternion is projected back on |q| = 1 (the model's projection, as the DOP853
// path's system.project), the sensitivities as they are. Outputs inside a step, and the dense
// output, are the step's Taylor polynomial.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <variant>
#include <vector>

#include "gyrostat/integrate/control.hpp"
#include "gyrostat/integrate/dense.hpp"
#include "gyrostat/integrate/options.hpp"
#include "gyrostat/integrate/taylor.hpp"
#include "gyrostat/integrate/variational.hpp"
#include "gyrostat/model/affine_euler.hpp"
#include "gyrostat/model/variational.hpp"

namespace gyrostat::integrate {

/// The augmented state Y = (y, S_1, …, S_m) of an affine gyrostat M (model/gyrostat.hpp,
/// model/orbiting.hpp: `affine_euler()`) as a run of taylor_steps (taylor.hpp). Its coefficients
/// live in the run's own buffer, component by component (Y_i[0 … p] contiguous: the per-component
/// helpers of taylor.hpp take them as they are), so the loop's array of coefficients is unused.
template <class M>
class VariationalTaylorRun {
public:
    using Value = double;
    using State = Eigen::VectorXd;
    using Vector = std::array<Eigen::VectorXd, 1>;
    struct Coefficient {};  // (in the run's buffer: above)
    static constexpr int max_taylor_order = M::max_taylor_order;
    static constexpr int dim = M::dim;

    VariationalTaylorRun(const M& model, const std::vector<model::Varied<M>>& columns, VariationalRun& run,
                         const std::vector<double>& times, const std::vector<double>& atol, double t0, double t1,
                         DenseOutput* dense)
        : model_(model), columns_(columns), run_(run), times_(times), atol_(atol), direction_(t1 >= t0 ? 1.0 : -1.0), t1_(t1),
          dense_(dense), rate_(model::AffineEulerRate::of(model.affine_euler())) {
        for (const model::Varied<M>& column : columns)
            parameters_.push_back(column.plus ? model::AffineEulerRate::derivative(column.plus->affine_euler(),
                                                                                   column.minus->affine_euler(), column.step)
                                              : model::AffineEulerRate{});
        for (const model::Varied<M>& column : columns) any_varied_ = any_varied_ || column.plus;
        blocks_ = static_cast<int>(1 + columns.size());
        size_ = dim * blocks_;
        buffer_.resize(static_cast<std::size_t>(size_) * (max_taylor_order + 1));
        if (dense_) scaled_.resize(buffer_.size());
        low_ = y_before_ = value_ = Eigen::VectorXd::Zero(size_);
        block_eps_.assign(static_cast<std::size_t>(blocks_), -1.0);
        safety_.resize(static_cast<std::size_t>(blocks_));
        scale_.resize(static_cast<std::size_t>(blocks_));
    }

    int count() const { return 1; }
    bool active(int) const { return active_; }
    bool any_active() const { return active_; }
    Stats& stats(int) { return run_.stats; }
    static const State& state(const Vector& y, int) { return y[0]; }
    void fill_done_lanes(double&, Vector&) const {}
    void fail(int, Status status, std::string message, double, const State&, double) {
        run_.status = status;
        run_.message = std::move(message);
        active_ = false;
    }
    bool keep_going(Ticker& ticker, double t, const Vector&, double) {
        if (ticker.keep_going(t)) return true;
        fail(0, Status::Interrupted, interrupted_message(t), t, value_, 0.0);
        return false;
    }
    /// y's quaternion back on |q| = 1 (its low part dropped where it moves: project_compensated).
    void project(Vector& y) {
        typename M::State head = y[0].template head<dim>(), low = low_.template head<dim>();
        taylor_detail::project_compensated(model_, head, low);
        y[0].template head<dim>() = head;
        low_.template head<dim>() = low;
    }
    /// The outputs at t0.
    void start(double t0, const Vector& y) {
        while (next_ < times_.size() && times_[next_] == t0) record(t0, y[0]);
    }
    void empty_span(int, double, const Vector&) { active_ = false; }

    /// The order of the next step, and each block's mode (relative or absolute) at Y.
    int prepare(const Vector& yv, const Options& options) {
        const Eigen::VectorXd& y = yv[0];
        bool changed = false;
        double least = std::numeric_limits<double>::infinity();
        controlled_ = options.sensitivity_error_control ? blocks_ : 1;
        for (int b = 0; b < controlled_; ++b) {
            const double norm = y.segment(b * dim, dim).cwiseAbs().maxCoeff();
            const double atol = atol_[static_cast<std::size_t>(b)];
            const bool relative = options.rtol * norm > atol;
            const double eps = std::max(relative ? options.rtol : atol, 1e-300);
            scale_[static_cast<std::size_t>(b)] = relative ? norm : 1.0;
            changed = changed || eps != block_eps_[static_cast<std::size_t>(b)];
            block_eps_[static_cast<std::size_t>(b)] = eps;
            least = std::min(least, eps);
        }
        if (changed) {  // only when a block's mode switches
            order_ = taylor_detail::order_for(least, max_taylor_order);
            for (std::size_t b = 0; b < static_cast<std::size_t>(controlled_); ++b)
                safety_[b] = taylor_detail::safety_for(block_eps_[b], order_);
            compensated_ = least < taylor_detail::compensate_below;
            if (!compensated_) low_.setZero();  // (no stale low part if compensation resumes)
        }
        return order_;
    }

    /// Y's coefficients 0 … Order into the buffer: y's by the model's recursion, then each column's
    /// (model::affine_euler_tangent_order).
    template <int Order>
    void coefficients(double t, const Vector& yv, Coefficient*) {
        constexpr int stride = Order + 1;
        const Eigen::VectorXd& y = yv[0];
        typename M::State solution[Order + 1];
        model_.template taylor_coefficients<Order>(t, y.template head<dim>(), solution);
        for (int i = 0; i < dim; ++i)
            for (int n = 0; n <= Order; ++n) buffer_[static_cast<std::size_t>(i * stride + n)] = solution[n][i];
        auto ys = [&](int n, int i) -> double { return solution[n][i]; };
        double products[Order][3] = {};
        if (any_varied_)
            for (int n = 0; n < Order; ++n) model::affine_euler_products(n, ys, products[n]);
        for (int j = 0; j + 1 < blocks_; ++j) {
            double* column = buffer_.data() + static_cast<std::ptrdiff_t>(dim * (1 + j) * stride);
            auto s = [column](int n, int i) -> double& { return column[i * stride + n]; };
            for (int i = 0; i < dim; ++i) s(0, i) = y[dim * (1 + j) + i];
            const std::size_t k = static_cast<std::size_t>(j);
            const model::AffineEulerRate* parameter = columns_[k].plus ? &parameters_[k] : nullptr;
            for (int n = 0; n < Order; ++n)
                model::affine_euler_tangent_order<dim == 7>(rate_, parameter, products[n], n, ys, s);
        }
        stride_ = stride;
    }

    /// The least over the blocks of Jorba & Zou's step (taylor_detail::step_size, each block its
    /// own scale and safety).
    template <int Order>
    double step_size(const Coefficient*) const {
        constexpr int stride = Order + 1;
        double h = std::numeric_limits<double>::infinity();
        for (int b = 0; b < controlled_; ++b) {
            double low = 0.0, high = 0.0;
            for (int i = b * dim; i < (b + 1) * dim; ++i) {
                low = std::max(low, std::abs(buffer_[static_cast<std::size_t>(i * stride + Order - 1)]));
                high = std::max(high, std::abs(buffer_[static_cast<std::size_t>(i * stride + Order)]));
            }
            h = std::min(h, taylor_detail::step_size(scale_[static_cast<std::size_t>(b)], low, high, Order,
                                                     safety_[static_cast<std::size_t>(b)]));
        }
        return h;
    }
    /// Whether the step's last coefficients are finite (and its size not NaN).
    bool finite(int, const Coefficient&, double h) const {
        for (int i = 0; i < size_; ++i)
            if (!std::isfinite(buffer_[static_cast<std::size_t>((i + 1) * stride_ - 1)])) return false;
        return !std::isnan(h);
    }
    static bool too_small(double, double, double, double) { return false; }  // (checked in advance)

    /// Y over dt: every component by its Taylor polynomial (compensated below 1e-12), the outputs
    /// and the dense output inside the step from the same polynomials.
    template <int Order>
    void advance(double& t, Vector& yv, const Coefficient*, double dt, double t1) {
        if (!active_) return;  // (failed before its step: Step::run)
        constexpr int stride = Order + 1;
        Eigen::VectorXd& y = yv[0];
        y_before_ = y;
        const double t_new = (std::abs(t1 - t) <= std::abs(dt)) ? t1 : t + dt;
        const double h = t_new - t;
        const double* c = buffer_.data();
        if (dense_ && h != 0.0) {  // the Taylor polynomial in s = (t' − t)/h: coefficients c_n hⁿ, order by order
            double power = 1.0;
            for (int n = 0; n <= Order; ++n, power *= h)
                for (int i = 0; i < size_; ++i) scaled_[static_cast<std::size_t>(n * size_ + i)] = c[i * stride + n] * power;
            dense_->add(t, t_new, t, h, Order, scaled_.data());
        }
        while (next_ < times_.size() && direction_ * (times_[next_] - t_new) < 0.0) {  // (Y and its low part as at t)
            for (int i = 0; i < size_; ++i)
                value_[i] = taylor_detail::evaluate_step<Order>(c + i * stride, times_[next_] - t, compensated_, low_[i]);
            record(times_[next_], value_);
        }
        if (compensated_) {
            if constexpr (model::system::has_taylor_rate_error<M>::value) {
                typename M::State first, head = y.template head<dim>(), low = low_.template head<dim>();
                for (int i = 0; i < dim; ++i) first[i] = c[i * stride + 1];
                low_.template head<dim>() += model_.taylor_rate_error(head, low, first) * h;
            }
            for (int i = 0; i < size_; ++i) taylor_detail::advance_compensated<Order>(y[i], low_[i], c + i * stride, h);
        } else {
            for (int i = 0; i < size_; ++i) y[i] = taylor_detail::evaluate_polynomial<Order>(c + i * stride, h);
        }
        ++run_.stats.rhs_evals;  // one evaluation of the coefficient recursion per step
        if (taylor_detail::below_resolution(t, h, t1)) {
            y = y_before_;
            fail(0, Status::StepSizeUnderflow, taylor_detail::underflow_message(t, std::abs(h)), t, y, 0.0);
            return;
        }
        project(yv);
        ++run_.stats.steps;
        run_.stats.last_step = std::abs(h);
        t = (std::abs(t1 - t) <= std::abs(h)) ? t1 : t + h;
        while (next_ < times_.size() && times_[next_] == t) record(t, y);
        if (direction_ * (t - t1_) >= 0.0) active_ = false;
    }

private:
    void record(double t, const Eigen::VectorXd& y) {
        run_.t.push_back(t);
        run_.state.push_back(y);
        ++next_;
    }

    const M& model_;
    std::vector<model::Varied<M>> columns_;
    VariationalRun& run_;
    const std::vector<double>& times_;
    const std::vector<double>& atol_;
    double direction_, t1_;
    DenseOutput* dense_;
    model::AffineEulerRate rate_;                   // f's coefficients
    std::vector<model::AffineEulerRate> parameters_;  // ∂f/∂p_j's (a column of the initial state: unused)
    bool any_varied_ = false;                       // some column is a parameter's
    int blocks_ = 1, size_ = dim, stride_ = 1;
    int controlled_ = 1;  // the blocks order and step are chosen on: y's alone, or every one (Options::sensitivity_error_control)      // (stride_: the last coefficients' order + 1)
    std::vector<double> buffer_, scaled_;           // the coefficients (component by component); for the dense output
    Eigen::VectorXd low_, y_before_, value_;        // Y's rounding error (compensated); Y before the step; an output
    std::vector<double> block_eps_, safety_, scale_;
    std::size_t next_ = 0;
    int order_ = 0;
    bool compensated_ = false, active_ = true;
};

/// Integrates the variational equations of the affine gyrostat `model` (its columns: model/
/// variational.hpp) by the Taylor method from (t0, Y0) to t1, as variational_dop853 does (the
/// same arguments and result: outputs at `times`, atol per block, the dense output of the whole
/// augmented state). Throws std::invalid_argument when `model` has torques beyond the constant
/// and linear ones.
template <class M>
VariationalRun variational_taylor(const M& model, const std::vector<model::Varied<M>>& columns, double t0,
                                  const Eigen::VectorXd& y0, double t1, const std::vector<double>& times,
                                  const std::vector<double>& atol, const Options& options, const Control* control,
                                  DenseOutput* dense = nullptr) {
    if (!model.supports_taylor()) {
        const std::string name = std::visit([](const auto& x) { return std::string(std::decay_t<decltype(x)>::python_name); },
                                            model.torques().others().front());
        throw std::invalid_argument("sensitivities by method 'taylor' cover constant and linear torques only (a "
                                    "quadratic right-hand side, whose variational equations are polynomial); this "
                                    "model's " + name + " is not constant or linear in ω: use dop853 or cvode_bdf");
    }
    VariationalRun run;
    VariationalTaylorRun<M> taylor(model, columns, run, times, atol, t0, t1, dense);
    taylor_steps(taylor, t0, {y0}, t1, options, control);
    return run;
}

}  // namespace gyrostat::integrate
