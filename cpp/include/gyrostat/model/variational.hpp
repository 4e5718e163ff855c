// The variational equations of any model (model/system.hpp): its state y and the sensitivities
// S_j = ∂y/∂p_j of the solution to an initial component or a parameter p_j, integrated together
// (integrate/variational.hpp):
//
//   y'   = f(t, y; p),
//   S_j' = ∂f/∂y (t, y; p) · S_j + ∂f/∂p_j (t, y; p),      S_j(t0) = ∂y(t0)/∂p_j,
//
// (Hairer, Nørsett & Wanner, Solving ODEs I, §I.14). The terms:
// * ∂f/∂y · S_j: the model's analytic Jacobian where it gives one (every full model; f and the
//   products with all the columns in one evaluation where the model gives them so (system.hpp:
//   rate_with_products): the gyrostat's torques and their derivatives once, the moving mass's dual
//   numbers with a direction per column), else the
//   directional central difference (f(y + δ S_j) − f(y − δ S_j)) / 2δ with δ‖S_j‖ = ε^{1/3} ‖y‖
//   (truncation and rounding both ~ε^{2/3} ≈ 4e-11 relative: the averaged models);
// * ∂f/∂p_j: (f(t, y; p_j + h_j) − f(t, y; p_j − h_j)) / 2h_j on the two models the caller built
//   with the parameter moved (truncation O(h²): ~1e-11 relative at h_j = ε^{1/3} |p_j|; exact up to
//   rounding where f is affine in p_j, as in every torque's gain; there, where the torque or the
//   model declares it (affine_in), the one-sided (f(t, y; p_j + H_j) − f(t, y; p_j)) / H_j with
//   H_j = |p_j| (the parameter's size: the difference far above f's rounding, whose noise would
//   otherwise hold the steps at tight tolerances) costs one moved right-hand side instead of two;
//   where the model gives that difference as linear in y (system::has_linear_rate_change: the
//   gyrostat's folded torques, f_far − f = J⁻¹ (ΔM0 − ΔD ω)), b + a y with b, a taken once, and
//   no moved right-hand side at all). A column for an initial
//   component has no such term. A body's parameter moved (an inertia tensor's entry) turns the
//   principal axes the moved model runs in: its f is taken through the user's frame,
//   U⁻¹ U_± f_±(U_±⁻¹ U y) (model/frame.hpp: reframe), so that the difference is the user frame's
//   ∂F/∂p written in this model's axes, whatever the eigenvectors of the two tensors.
// The models name their parameters in Python (gyrostat/sensitivity.py) and build the moved ones;
// nothing here knows what a parameter is.
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <limits>
#include <vector>

#include "gyrostat/model/frame.hpp"
#include "gyrostat/model/system.hpp"

namespace gyrostat::model {

/// The relative accuracy of a difference quotient here (ε^{2/3} ≈ 4e-11 rounding per evaluation,
/// ~1e-11 truncation): a column whose rate is one is integrated to at least this relative error
/// (integrate/variational.hpp's per-block rtol), and reports at least it (gyrostat.sensitivity).
inline constexpr double kDifferenceAccuracy = 1e-10;

/// One sensitivity column of a model of type M: a parameter (the model built with it moved by
/// ±step; `far`: where f is affine in it, the model with it moved by far_step, whose one-sided
/// difference is exact) or, with `plus` null, a component of the initial state.
template <class M>
struct Varied {
    const M* plus = nullptr;
    const M* minus = nullptr;
    double step = 0.0;
    const M* far = nullptr;
    double far_step = 0.0;
    int analytic = -1;  ///< the model's own ∂f/∂p (system::has_parameter_rate), by its index in analytic_in; −1: none
};

/// The augmented system (y, S_1, …, S_m) of `model`, m = columns.size(), state of size
/// M::dim · (1 + m), S_j after y.
template <class M>
class Variational {
public:
    using State = typename M::State;
    static constexpr int dim = M::dim;

    Variational(const M& model, std::vector<Varied<M>> columns) : model_(model), columns_(std::move(columns)) {
        if constexpr (system::has_linear_rate_change<M>::value) {
            linear_.resize(columns_.size());
            for (std::size_t j = 0; j < columns_.size(); ++j)
                if (columns_[j].analytic < 0 && columns_[j].far)
                    linear_[j].given = model_.linear_rate_change(*columns_[j].far, columns_[j].far_step, linear_[j].b, linear_[j].a);
        }
    }

    const std::vector<Varied<M>>& columns() const { return columns_; }

    void rhs(double t, const Eigen::VectorXd& Y, Eigen::VectorXd& dY) const {
        dY.resize(Y.size());
        const State y = Y.template head<dim>();
        State f;
        // f and every column's product in one evaluation where the model gives them so
        // (system::has_rate_with_products), else f alone and then the whole Jacobian once.
        bool together = false;
        if constexpr (system::has_rate_with_products<M>::value)
            together = !columns_.empty() && model_.rate_with_products(t, y, Y.data() + dim, columns_.size(), f, dY.data() + dim);
        if (!together) model_.rhs(t, y, f);
        dY.template head<dim>() = f;
        [[maybe_unused]] system::Jacobian<M> jacobian;
        if constexpr (system::has_jacobian<M>::value)
            if (!together) model_.jacobian(t, y, jacobian);
        for (std::size_t j = 0; j < columns_.size(); ++j) {
            const Eigen::Index at = dim * static_cast<Eigen::Index>(1 + j);
            State rate;
            if (together) {
                rate = dY.template segment<dim>(at);
            } else if constexpr (system::has_jacobian<M>::value) {
                rate.noalias() = jacobian * Y.template segment<dim>(at);
            } else {
                rate = directional(t, y, Y.template segment<dim>(at));
            }
            const Varied<M>& column = columns_[j];
            if (column.analytic >= 0) {
                if constexpr (system::has_parameter_rate<M>::value) {
                    State parameter_rate;
                    model_.parameter_rate(static_cast<std::size_t>(column.analytic), t, y, parameter_rate);
                    rate += parameter_rate;
                }
            } else if (!linear_.empty() && linear_[j].given) {
                rate += linear_[j].b;
                rate.noalias() += linear_[j].a * y;
            } else if (column.far)
                rate += (moved_rate(*column.far, t, y) - f) / column.far_step;
            else if (column.plus)
                rate += (moved_rate(*column.plus, t, y) - moved_rate(*column.minus, t, y)) / (2.0 * column.step);
            dY.template segment<dim>(at) = rate;
        }
    }

    /// The model's projection of y (|q| = 1), the sensitivities as they are; false: it has none.
    bool project(Eigen::VectorXd& Y) const {
        if constexpr (system::has_projection<M>::value) {
            State y = Y.template head<dim>();
            model_.project(y);
            Y.template head<dim>() = y;
            return true;
        } else {
            return false;
        }
    }

private:
    /// The rate of the model with a parameter moved, at y, both in this model's principal axes
    /// (frame::reframe: a body's parameter moved turns its principal axes).
    State moved_rate(const M& moved, double t, const State& y) const {
        State rate;
        if (!frame::rotated(model_) && !frame::rotated(moved)) {
            moved.rhs(t, y, rate);
            return rate;
        }
        State there = y;
        frame::reframe(model_, moved, there.data());
        moved.rhs(t, there, rate);
        frame::reframe(moved, model_, rate.data());
        return rate;
    }

    /// ∂f/∂y · s by the central difference along s.
    State directional(double t, const State& y, const State& s) const {
        const double size = s.norm();
        if (size == 0.0) return State::Zero();
        const double delta = std::cbrt(std::numeric_limits<double>::epsilon()) * std::max(y.norm(), 1e-300) / size;
        State plus = y + delta * s, minus = y - delta * s, f_plus, f_minus;
        model_.rhs(t, plus, f_plus);
        model_.rhs(t, minus, f_minus);
        return (f_plus - f_minus) / (2.0 * delta);
    }

    /// A far column's ∂f/∂p = b + a y where the model gives it so (system::has_linear_rate_change).
    struct LinearChange {
        bool given = false;
        State b = State::Zero();
        system::Jacobian<M> a = system::Jacobian<M>::Zero();
    };

    const M& model_;
    std::vector<Varied<M>> columns_;
    std::vector<LinearChange> linear_;
};

}  // namespace gyrostat::model
