// The window estimate of a run (gyrostat/measure.hpp).
#include "gyrostat/measure.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>

namespace gyrostat {

Grown grow(double last, double half, double end, double middle, double far, double least) {
    if (far <= end || last == 0.0) return {last, 1.0};
    // (std::max keeps `least` for a NaN fit, as the rule's Python did)
    const double k = half <= 0.0 ? 1.0 : std::min(2.0, std::max(least, std::log(last / half) / std::log(end / middle)));
    return {last * std::pow(far / end, k), k};
}

WindowEstimate window_from_differences(const Eigen::Ref<const Eigen::MatrixXd>& apart, const std::vector<double>& times,
                                       double t0, double horizon, const WindowRule& rule, bool to_horizon,
                                       long companion_steps) {
    const Eigen::Index n = apart.cols();
    if (n == 0 || static_cast<std::size_t>(n) != times.size())
        throw std::invalid_argument("window_from_differences: " + std::to_string(n) + " differences at " +
                                    std::to_string(times.size()) + " times (at least one, as many as times)");
    WindowEstimate made;
    made.made = true;
    made.window_end = times.back();
    made.times = times.size();
    const std::size_t middle_row = times.size() / 2;
    const double end = std::abs(times.back() - t0), middle = std::abs(times[middle_row] - t0), far = std::abs(horizon - t0);
    made.grown = to_horizon && far > end;
    made.fitted = companion_steps >= rule.fit_steps;  // (else k = 1: a staircase of a few steps, the header)
    for (Eigen::Index q = 0; q < apart.rows(); ++q) {
        // the running maxima at the window's end and at its middle output time (NaN stays NaN)
        double last = 0.0, half = 0.0;
        for (Eigen::Index k = 0; k < n; ++k) {
            const double d = apart(q, k);
            if (std::isnan(d) || std::isnan(last)) last = std::numeric_limits<double>::quiet_NaN();
            else last = std::max(last, d);
            if (k == static_cast<Eigen::Index>(middle_row)) half = last;
        }
        Grown value{last * rule.gain, 1.0};
        if (made.grown) {
            value = grow(last * rule.gain, made.fitted ? half * rule.gain : 0.0, end, middle, far);
            value.value *= rule.safety;
        }
        made.per_quantity.push_back(std::isnan(value.value) ? value.value : std::max(value.value, rule.floor));
        made.k = q == 0 ? value.k : std::max(made.k, value.k);
    }
    return made;
}

namespace {

/// How many of the answer's output times the measurement compares: those in the window (the
/// first ones), or all of them over the whole span.
std::size_t compared_times(const integrate::Result& answer, double t0, double t1, const WindowRule& rule, bool whole_span) {
    const std::size_t n = answer.t.size();
    if (whole_span) return n;
    const double direction = t1 >= t0 ? 1.0 : -1.0, reach = rule.fraction * std::abs(t1 - t0);
    std::size_t count = 0;
    while (count < n && (answer.t[count] - t0) * direction <= reach) ++count;
    return count;
}

/// Whether the engine measures this answer: a run that reached past t0 with output times; over a
/// window, at least least_times of them there, at least kFewSteps steps (a run of fewer has its
/// error inside its long steps' interpolation, which runs over a window do not share) and no
/// separatrix crossed after the window's first half (the window cannot foresee the jump of the
/// error there). The caller measures the others over the whole span.
bool measurable(const AnyModel& model, const integrate::Result& answer, std::size_t count, double t0, double t1,
                const WindowRule& rule, bool whole_span) {
    if (answer.t.empty() || t1 == t0 || !answer.success()) return false;
    if (whole_span) return true;
    return count >= rule.least_times && !std::isfinite(companion_step_limit(answer, t0)) &&
           std::isnan(first_crossing(model, answer, t0 + 0.5 * rule.fraction * (t1 - t0)));
}

double horizon_of(const integrate::Result& answer) {
    return std::isnan(answer.t_last) ? answer.t.back() : answer.t_last;
}

/// Whether a run measures its own error, so that no companion measures it here: method
/// splitting (Richardson over its step) and a closed form (its rounding).
bool measures_itself(const integrate::Result& answer) {
    return answer.method == "splitting" || answer.method == "closed_form";
}

/// The companion's options: `companion` at the answer's first `count` output times, without
/// events, dense output or every step, its steps at most `step_limit` (companion_step_limit); over a
/// window, recording only the measured outputs (a whole span's companion may become the answer,
/// python/gyrostat/contract.py, unless `companion` says only_measured_outputs itself).
integrate::Options companion_options(const integrate::Options& companion, const integrate::Result& answer, std::size_t count,
                                     bool whole_span, double step_limit) {
    integrate::Options options = companion;
    options.max_step = std::min(options.max_step, step_limit);
    options.t_eval.assign(answer.t.begin(), answer.t.begin() + static_cast<std::ptrdiff_t>(count));
    options.events.clear();
    options.every_step = options.dense_output = false;
    if (!whole_span) options.only_measured_outputs = true;
    return options;
}

/// The answer measured against its companion's run at its first `count` output times.
WindowEstimate measured_against(const AnyModel& model, const integrate::Result& answer, integrate::Result other,
                                std::size_t count, double t0, const WindowRule& rule, bool whole_span) {
    WindowEstimate made;
    if (!other.success() || other.t.size() != count) {
        made.made = true;
        made.failure = other.success() ? "the companion recorded " + std::to_string(other.t.size()) + " of " +
                                             std::to_string(count) + " times"
                                       : std::string(integrate::status_name(other.status)) + ": " + other.message;
        made.companion = std::move(other);
        return made;
    }
    std::vector<std::size_t> rows;
    if (count < answer.t.size()) {
        rows.resize(count);
        for (std::size_t k = 0; k < count; ++k) rows[k] = k;
    }
    // relative to the companion's sizes over a window, to the answer's over the whole span
    const Eigen::MatrixXd apart = whole_span ? measured_differences(model, answer, other, {}, {})
                                             : measured_differences(model, other, answer, {}, rows);
    const std::vector<double> times(answer.t.begin(), answer.t.begin() + static_cast<std::ptrdiff_t>(count));
    made = window_from_differences(apart, times, t0, horizon_of(answer), rule, !whole_span, other.stats.steps);
    made.companion = std::move(other);
    return made;
}

}  // namespace

double companion_step_limit(const integrate::Result& answer, double t0, const integrate::Stats* first) {
    constexpr double none = std::numeric_limits<double>::infinity();
    const long steps = answer.stats.steps;
    if (steps <= 0 || answer.t.empty()) return none;
    const bool one_order = answer.method == "dop853" || answer.method == "arkode_verner6" ||
                           answer.method == "arkode_fehlberg8";
    const bool unset = steps < kFewSteps || (first != nullptr && one_order && first->steps > 0 &&
                                             static_cast<double>(first->steps) < kStepsFollowTolerance * steps);
    const double limit = 0.5 * std::abs(horizon_of(answer) - t0) / static_cast<double>(steps);
    return unset && limit > 0.0 && std::isfinite(limit) ? limit : none;
}

WindowEstimate window_estimate(const AnyModel& model, const integrate::Result& answer, double t0,
                               const Eigen::Ref<const Eigen::VectorXd>& y0, double t1,
                               const integrate::Options& companion, const WindowRule& rule,
                               const integrate::Control* control, bool whole_span) {
    if (measures_itself(answer)) return {};
    const std::size_t count = compared_times(answer, t0, t1, rule, whole_span);
    if (!measurable(model, answer, count, t0, t1, rule, whole_span)) return {};
    const double end = whole_span ? horizon_of(answer) : answer.t[count - 1];
    integrate::Options options = companion_options(companion, answer, count, whole_span, companion_step_limit(answer, t0));
    integrate::Result other = solve(model, t0, y0, end, options, control);
    // over the whole span, a companion whose steps its tolerance did not set runs again, limited
    const double limit = whole_span && other.success() ? companion_step_limit(answer, t0, &other.stats) : options.max_step;
    if (limit < options.max_step) {
        options.max_step = limit;
        other = solve(model, t0, y0, end, options, control);
    }
    WindowEstimate made = measured_against(model, answer, std::move(other), count, t0, rule, whole_span);
    made.companion_max_step = options.max_step;
    return made;
}

MeasuredRun solve_measured(const AnyModel& model, double t0, const Eigen::Ref<const Eigen::VectorXd>& y0, double t1,
                           const integrate::Options& options, const integrate::Options& companion,
                           const WindowRule& rule, const integrate::Control* control, bool whole_span,
                           bool measured_only) {
    MeasuredRun made{solve(model, t0, y0, t1, options, control), {}};
    if (!measured_only || !whole_span) {
        made.estimate = window_estimate(model, made.answer, t0, y0, t1, companion, rule, control, whole_span);
    } else {
        integrate::Options measuring = companion;
        measuring.only_measured_outputs = true;
        made.estimate = window_estimate(model, made.answer, t0, y0, t1, measuring, rule, control, whole_span);
    }
    return made;
}

std::vector<WindowEstimate> window_estimates(const std::vector<const AnyModel*>& models,
                                             const std::vector<const integrate::Result*>& answers, double t0,
                                             const std::vector<Eigen::VectorXd>& y0s, double t1,
                                             const integrate::Options& companion, const WindowRule& rule, int threads,
                                             const integrate::Control* control, bool batch, bool whole_span) {
    const std::size_t n = answers.size();
    if (models.size() != 1 && models.size() != n)
        throw std::invalid_argument("window_estimates: " + std::to_string(models.size()) + " models for " +
                                    std::to_string(n) + " answers: give 1 or " + std::to_string(n));
    if (y0s.size() != n)
        throw std::invalid_argument("window_estimates: " + std::to_string(y0s.size()) + " initial states for " +
                                    std::to_string(n) + " answers");
    auto model_of = [&](std::size_t i) -> const AnyModel& { return *models[models.size() == 1 ? 0 : i]; };
    std::vector<WindowEstimate> made(n);
    // the members measured here: those measurable whose compared times are the first one's (one
    // companion ensemble at those times)
    std::vector<std::size_t> members;
    std::size_t count = 0;
    double end = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
        const integrate::Result& answer = *answers[i];
        const std::size_t here = compared_times(answer, t0, t1, rule, whole_span);
        if (!measurable(model_of(i), answer, here, t0, t1, rule, whole_span)) continue;
        if (!members.empty()) {
            const integrate::Result& first = *answers[members.front()];
            if (here != count || answer.t.size() != first.t.size() ||
                !std::equal(answer.t.begin(), answer.t.begin() + static_cast<std::ptrdiff_t>(count), first.t.begin()))
                continue;
        }
        count = here;
        end = whole_span ? (members.empty() ? horizon_of(answer) : std::max(end, horizon_of(answer))) : answer.t[count - 1];
        members.push_back(i);
    }
    if (members.empty()) return made;
    std::vector<const AnyModel*> chosen;
    std::vector<Eigen::VectorXd> starts;
    for (std::size_t i : members) {
        if (models.size() != 1 || chosen.empty()) chosen.push_back(&model_of(i));
        starts.push_back(y0s[i]);
    }
    const integrate::Options options = companion_options(companion, *answers[members.front()], count, whole_span,
                                                         std::numeric_limits<double>::infinity());
    std::vector<integrate::Result> companions = solve_ensemble(chosen, starts, t0, end, options, threads, control, batch);
    for (std::size_t k = 0; k < members.size(); ++k) {
        const std::size_t i = members[k];
        integrate::Options own = options;
        // over the whole span, a companion whose steps its tolerance did not set runs again, limited by its own
        // member's rule (window_estimate; a member's measurement is the same in any ensemble)
        const double limit =
            whole_span && companions[k].success() ? companion_step_limit(*answers[i], t0, &companions[k].stats) : own.max_step;
        if (limit < own.max_step) {
            own.max_step = limit;
            companions[k] = solve(model_of(i), t0, starts[k], end, own, control);
        }
        made[i] = measured_against(model_of(i), *answers[i], std::move(companions[k]), count, t0, rule, whole_span);
        made[i].companion_max_step = own.max_step;
    }
    return made;
}

}  // namespace gyrostat
