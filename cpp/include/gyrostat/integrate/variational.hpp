// DOP853 on a state whose size is known only at run time: the variational equations of a model
// (model/variational.hpp), y and its sensitivities S = ∂y/∂p integrated together. The tableau,
// the step-size controller and the 7th-order dense output are dop853.hpp's (same constants, same
// monomials); what differs is the state's storage (one dynamic vector, allocated once) and the
// error norm: on y alone by default, so that the steps are the plain run's (CVODES's errconS =
// false); with Options::sensitivity_error_control, on each block (y, then every sensitivity
// column) and the largest kept, so that many sensitivities do not dilute the control of the state
// (CVODES's errconS = true, with each column's own absolute tolerance: see `scale` below).
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "gyrostat/integrate/control.hpp"
#include "gyrostat/integrate/dense.hpp"
#include "gyrostat/integrate/dop853.hpp"
#include "gyrostat/integrate/options.hpp"
#include "gyrostat/integrate/recorder.hpp"
#include "gyrostat/numeric/dop853_tableau.hpp"

namespace gyrostat::integrate {

/// What a variational run returns: the augmented state at each output time reached.
struct VariationalRun {
    std::vector<double> t;               ///< the output times reached, in order
    std::vector<Eigen::VectorXd> state;  ///< the augmented state (y, then S column by column) at each
    Stats stats;
    Status status = Status::Success;
    std::string message;
};

/// The message of a variational run interrupted at t (Control: Ctrl-C or a progress callback).
inline std::string interrupted_message(double t) {
    return "interrupted at t = " + format_number(t) + " (the outputs up to there are kept)";
}

/// Integrates Y' = rhs(t, Y) from (t0, Y0) to t1, Y = (y, S_1, …, S_m) with blocks of `block`
/// components, recording Y at `times` (in the run's direction, inside the span). `atol[b]` and
/// `rtol[b]` are block b's tolerances. `project(Y)` runs after each accepted step
/// (the model's manifold, on y) and says whether the model has one. With a `dense` output, every
/// step's continuous extension goes into it (the whole augmented state). Fails as dop853 does
/// (max_steps, a step below the resolution of t, a non-finite state) with the partial record and
/// a message. `quadratures`: the model's (model/system.hpp), left out of the error test in every
/// block as dop853.hpp leaves them out of the plain run's.
template <class Rhs, class Project>
VariationalRun variational_dop853(const Rhs& rhs, const Project& project, Eigen::Index block, double t0,
                                  Eigen::VectorXd y, double t1, const std::vector<double>& times,
                                  const std::vector<double>& atol, const std::vector<double>& rtol,
                                  const Options& options, const Control* control, DenseOutput* dense = nullptr,
                                  const std::vector<int>& quadratures = {}) {
    namespace tab = dop853_tableau;
    using namespace dop853_detail;
    const Eigen::Index size = y.size(), blocks = options.sensitivity_error_control ? size / block : 1;
    const Eigen::Index controlled = blocks * block;  // the components the steps are chosen on
    // the components each block's norm counts (as dop853.hpp's `controlled`: its quadratures left out)
    const double counted = static_cast<double>(std::max<Eigen::Index>(1, block - static_cast<Eigen::Index>(quadratures.size())));
    const double direction = t1 >= t0 ? 1.0 : -1.0, span = std::abs(t1 - t0);
    VariationalRun run;
    std::size_t next = 0;  // the next output time
    auto record = [&](double time, const Eigen::VectorXd& value) {
        run.t.push_back(time);
        run.state.push_back(value);
        ++next;
    };
    auto fail = [&](Status status, std::string message) {
        run.status = status;
        run.message = std::move(message);
        return run;
    };
    // The error of a step: DOP853's combination of its 5th- and 3rd-order estimates on each
    // controlled block, the largest.
    auto error_norm = [&](const Eigen::VectorXd& e5, const Eigen::VectorXd& e3, const Eigen::VectorXd& scale, double h) {
        double worst = 0.0;
        for (Eigen::Index b = 0; b < blocks; ++b) {
            double s5 = 0.0, s3 = 0.0;
            for (Eigen::Index i = b * block; i < (b + 1) * block; ++i) {
                if (e5[i] != 0.0) s5 += (e5[i] / scale[i]) * (e5[i] / scale[i]);
                if (e3[i] != 0.0) s3 += (e3[i] / scale[i]) * (e3[i] / scale[i]);
            }
            if (s5 != 0.0 || s3 != 0.0)
                worst = std::max(worst, h * s5 / std::sqrt((s5 + 0.01 * s3) * counted));
        }
        return worst;
    };
    // The working vectors, allocated once here (none in the loop).
    Eigen::VectorXd scale(size), absolute(size), relative(size);
    for (Eigen::Index i = 0; i < size; ++i) {
        absolute[i] = atol[static_cast<std::size_t>(i / block)];
        relative[i] = rtol[static_cast<std::size_t>(i / block)];
    }
    for (Eigen::Index b = 0; b < size / block; ++b)  // a quadrature's scale infinite: v / ∞ = 0
        for (const int q : quadratures) absolute[b * block + q] = std::numeric_limits<double>::infinity();
    auto scale_of = [&](const Eigen::VectorXd& a, const Eigen::VectorXd& b) -> const Eigen::VectorXd& {
        scale = absolute + relative.cwiseProduct(a.cwiseAbs().cwiseMax(b.cwiseAbs()));
        return scale;
    };

    project(y);
    double t = t0;
    while (next < times.size() && times[next] == t0) record(t0, y);
    std::array<Eigen::VectorXd, tab::n_stages_extended> k;
    Eigen::VectorXd f(size), y_new(size), f_new(size), stage(size), e5(size), e3(size), value(size);
    for (Eigen::VectorXd& stage_rate : k) stage_rate.resize(size);
    std::array<Eigen::VectorXd, 7> F;  // the dense output's coefficients, then its monomials c
    std::array<Eigen::VectorXd, 8> c;
    for (Eigen::VectorXd& v : F) v.resize(size);
    for (Eigen::VectorXd& v : c) v.resize(size);
    std::vector<double> coefficients(dense ? 8 * static_cast<std::size_t>(size) : 0);  // c_0 … c_7, for `dense`
    rhs(t, y, f);
    ++run.stats.rhs_evals;
    if (t0 == t1) return run;
    if (!y.allFinite() || !f.allFinite())
        return fail(Status::NonFiniteState, "the right-hand side is not finite at the initial state (t = " + format_number(t0) + ")");

    // The first step (Hairer's rule with dop853.hpp's slow-system scale, on the controlled components).
    double h_abs = options.first_step;
    if (h_abs == 0.0) {
        const Eigen::VectorXd& first_scale = scale_of(y, y);
        auto rms_over = [&](const Eigen::VectorXd& v) {  // weighted as dop853.hpp's: 0/0 = 0
            double squares = 0.0;
            for (Eigen::Index i = 0; i < controlled; ++i)
                if (v[i] != 0.0) squares += (v[i] / first_scale[i]) * (v[i] / first_scale[i]);
            return std::sqrt(squares / (counted * static_cast<double>(blocks)));
        };
        const double d0 = rms_over(y), d1 = rms_over(f);
        const double h0 = std::min(d0 < 1e-5 || d1 < 1e-5 ? 1e-6 : 0.01 * d0 / d1, span);
        rhs(t + h0 * direction, y + h0 * direction * f, f_new);
        ++run.stats.rhs_evals;
        const double d2 = rms_over(f_new - f) / h0;
        double h1 = d1 <= 1e-15 && d2 <= 1e-15 ? std::max(1e-6, h0 * 1e-3) : std::pow(0.01 / std::max(d1, d2), 1.0 / 8.0);
        const double tau = d0 / d1;  // a slow system's own time scale (dop853.hpp's initial_step)
        if (tau > 10.0 && std::isfinite(tau)) h1 = std::max(h1, tau * std::pow(0.01 / std::max(d0, tau * tau * d2), 1.0 / 8.0));
        h_abs = std::min({100 * h0, h1, span});
        if (!std::isfinite(h_abs) || h_abs <= 0.0) h_abs = std::min(1e-6, span);
    }
    // out = base + h Σ_j w_j k_j over the nonzero weights of w[0 .. count), in one pass over the
    // components (each component's sum in the order of j, as a sum of whole vectors would take it);
    // with `base` null, out = h Σ_j w_j k_j.
    auto combine = [&](const double* w, int count, double h, const Eigen::VectorXd* base, Eigen::VectorXd& out) {
        std::array<const double*, tab::n_stages_extended> rates;
        std::array<double, tab::n_stages_extended> weights;
        int used = 0;
        for (int j = 0; j < count; ++j)
            if (w[j] != 0.0) rates[used] = k[j].data(), weights[used++] = w[j];
        double* to = out.data();
        for (Eigen::Index i = 0; i < size; ++i) {
            double total = weights[0] * rates[0][i];
            for (int u = 1; u < used; ++u) total += weights[u] * rates[u][i];
            to[i] = base ? (*base)[i] + h * total : h * total;
        }
    };
    auto compute_stage = [&](int s, double h) {
        combine(tab::a[s], s, h, &y, stage);
        rhs(t + tab::c[s] * h, stage, k[s]);
    };
    Ticker ticker(control, t0, t1);
    bool rejected = false;
    int non_finite_trials = 0;
    while (true) {
        if (!ticker.keep_going(t))
            return fail(Status::Interrupted, interrupted_message(t));
        if (run.stats.steps >= options.max_steps)
            return fail(Status::MaxStepsReached, "max_steps = " + std::to_string(options.max_steps) + " reached at t = " +
                                                     format_number(t) + " before t1 = " + format_number(t1));
        const double smallest = min_step(t, direction);
        if (!rejected) h_abs = std::max(std::min(h_abs, options.max_step), smallest);
        if (h_abs < smallest || non_finite_trials >= kMaxNonFiniteTrials)
            return fail(non_finite_trials > 0 ? Status::NonFiniteState : Status::StepSizeUnderflow,
                        (non_finite_trials > 0 ? "the state or its sensitivities became non-finite on every trial step from t = "
                                               : "step size underflow at t = ") + format_number(t, 17));
        double t_new = t + h_abs * direction;
        if (direction * (t_new - t1) > 0.0) t_new = t1;
        const double h = t_new - t;
        h_abs = std::abs(h);

        k[0] = f;
        for (int s = 1; s < tab::n_stages; ++s) compute_stage(s, h);
        combine(tab::b, tab::n_stages, h, &y, y_new);
        rhs(t_new, y_new, f_new);
        k[tab::n_stages] = f_new;
        run.stats.rhs_evals += tab::n_stages;
        combine(tab::e5, tab::n_stages + 1, 1.0, nullptr, e5);
        combine(tab::e3, tab::n_stages + 1, 1.0, nullptr, e3);
        const double err = error_norm(e5, e3, scale_of(y, y_new), h_abs);
        if (!std::isfinite(err) || !y_new.allFinite()) {
            ++non_finite_trials, ++run.stats.rejected_steps;
            h_abs *= kMinFactor;
            rejected = true;
            continue;
        }
        if (err >= 1.0) {
            h_abs *= std::max(kMinFactor, kSafety * std::pow(err, kErrorExponent));
            ++run.stats.rejected_steps;
            rejected = true;
            continue;
        }
        double factor = err == 0.0 ? kMaxFactor : std::min(kMaxFactor, kSafety * std::pow(err, kErrorExponent));
        if (rejected) factor = std::min(1.0, factor);
        non_finite_trials = 0;
        ++run.stats.steps;
        run.stats.last_step = h_abs;

        // The outputs inside the step, from the 7th-order dense output (its three extra stages);
        // every step's, with a `dense` output.
        if (dense || (next < times.size() && direction * (times[next] - t_new) <= 0.0)) {
            for (int s = tab::n_stages + 1; s < tab::n_stages_extended; ++s) compute_stage(s, h);
            run.stats.rhs_evals += tab::n_stages_extended - tab::n_stages - 1;
            F[0].noalias() = y_new - y;
            F[1].noalias() = h * k[0] - F[0];
            F[2].noalias() = 2.0 * F[0] - h * (f_new + k[0]);
            for (int r = 0; r < 4; ++r) combine(tab::d[r], tab::n_stages_extended, h, nullptr, F[3 + r]);
            monomials(F, y, c.data());
            if (dense) {
                for (int r = 0; r < 8; ++r) std::copy(c[r].data(), c[r].data() + size, coefficients.data() + r * size);
                dense->add(t, t_new, t, h, 7, coefficients.data());  // y(t + s h) = Σ c_r s^r
            }
            while (next < times.size() && direction * (times[next] - t_new) <= 0.0) {
                if (times[next] == t_new) {
                    record(t_new, y_new);
                    continue;
                }
                const double x = (times[next] - t) / h;
                value = c[7];
                for (int r = 6; r >= 0; --r) value = c[r] + x * value;
                record(times[next], value);
            }
        }
        y = y_new;
        t = t_new;
        f = f_new;
        if (project(y)) {  // back on the model's manifold: the rate there
            rhs(t, y, f);
            ++run.stats.rhs_evals;
        }
        h_abs *= factor;
        rejected = false;
        if (t == t1) return run;
    }
}

}  // namespace gyrostat::integrate
