// Dense output: the continuous extension of every step of a run, kept to evaluate the solution
// anywhere in the span after the run (memory grows with the steps taken).
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

#include "gyrostat/body.hpp"
#include "gyrostat/numeric/unit_vector.hpp"

namespace gyrostat::integrate {

/// The solution as a piecewise polynomial: on the step [t_a, t_b],
///   y(t) = Σ_k c_k s^k,  s = (t − t_ref)/scale,
/// with the integrator's own continuous extension (DOP853's 7th-order dense output, the Taylor
/// polynomial, CVODE's Nordsieck interpolant, ARKODE's Hermite interpolant), or the closed form
/// of a model that needs no integration. A quaternion in the state is normalised on evaluation.
class DenseOutput {
public:
    DenseOutput(int dim, int quaternion) : dim_(dim), quaternion_(quaternion) {}

    int dim() const { return dim_; }
    std::size_t steps() const { return t_a_.size(); }
    bool empty() const { return t_a_.empty() && !exact_; }

    /// Adds the step [ta, tb]: `coefficients` holds (order + 1) states, c_0 first.
    void add(double ta, double tb, double t_ref, double scale, int order, const double* coefficients) {
        t_a_.push_back(ta);
        t_b_.push_back(tb);
        t_ref_.push_back(t_ref);
        scale_.push_back(scale);
        order_.push_back(order);
        offset_.push_back(coefficients_.size());
        coefficients_.insert(coefficients_.end(), coefficients, coefficients + (order + 1) * dim_);
    }
    /// A closed form valid on [ta, tb] instead of steps.
    void set_exact(double ta, double tb, std::function<Eigen::VectorXd(double)> exact) {
        exact_ = std::move(exact);
        exact_a_ = ta, exact_b_ = tb;
    }

    /// y(t) for t in the span of the run (throws std::invalid_argument naming t otherwise).
    Eigen::VectorXd operator()(double t) const {
        Eigen::VectorXd y(dim_);
        if (exact_) {
            check_inside(t, exact_a_, exact_b_);
            y = exact_(t);
        } else {
            if (t_a_.empty()) throw std::invalid_argument("the run took no step: there is no dense output to evaluate");
            const bool forward = t_b_.back() >= t_a_.front();
            check_inside(t, t_a_.front(), t_b_.back());
            // the first step whose end is at or beyond t in the direction of integration
            const auto it = forward ? std::lower_bound(t_b_.begin(), t_b_.end(), t)
                                    : std::lower_bound(t_b_.begin(), t_b_.end(), t, std::greater<double>());
            const std::size_t i = std::min<std::size_t>(static_cast<std::size_t>(it - t_b_.begin()), t_b_.size() - 1);
            const double s = (t - t_ref_[i]) / scale_[i];
            const double* c = coefficients_.data() + offset_[i];
            y = Eigen::Map<const Eigen::VectorXd>(c + order_[i] * dim_, dim_);
            for (int k = order_[i] - 1; k >= 0; --k) y = y * s + Eigen::Map<const Eigen::VectorXd>(c + k * dim_, dim_);
        }
        if (quaternion_ >= 0) normalize_in_place(y.segment<4>(quaternion_));
        if (transform_) transform_(y.data());
        return y;
    }
    /// A map applied to every state returned (the model's principal axes to the user's frame:
    /// model/frame.hpp).
    void set_transform(std::function<void(double*)> transform) { transform_ = std::move(transform); }

private:
    static void check_inside(double t, double a, double b) {
        if (!(t >= std::min(a, b) && t <= std::max(a, b)))
            throw std::invalid_argument("t = " + format_value(t) + " lies outside the span of the run [" +
                                        format_value(std::min(a, b)) + ", " + format_value(std::max(a, b)) + "]");
    }

    int dim_, quaternion_;
    std::vector<double> t_a_, t_b_, t_ref_, scale_;
    std::vector<int> order_;
    std::vector<std::size_t> offset_;
    std::vector<double> coefficients_;
    std::function<Eigen::VectorXd(double)> exact_;
    double exact_a_ = 0.0, exact_b_ = 0.0;
    std::function<void(double*)> transform_;
};

}  // namespace gyrostat::integrate
