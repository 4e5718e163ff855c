// The accuracy contract's window estimate (python/gyrostat/accuracy.py, module doc), in the
// engine: a run at given tolerances is repeated over the first part of its span (the window) at
// tolerances ρ times smaller, the two compared at the run's own output times there, and each
// quantity's largest difference over the window is grown to the run's end as t^k. Here so that a
// run's estimate costs one engine call and no Python per output time; the Python layer keeps the
// rules' numbers (the window's fraction, ρ, the safety factor) and says the basis in words.
#pragma once

#include <Eigen/Core>
#include <limits>
#include <string>
#include <vector>

#include "gyrostat/engine.hpp"

namespace gyrostat {

/// A difference's running maximum over a window, `last` at its end and `half` at its middle
/// output time, grown to the horizon as t^k: k = ln(last/half)/ln(end/middle) fitted over the
/// window's second half, kept within [least, 2] (1 where `half` is 0; linear drift of the
/// invariants to quadratic growth of a phase error whose frequency error itself drifts). `end`,
/// `middle`, `far`: the distances from t0 of the window's end, of its middle output time and of
/// the horizon (a backward run grows the same way). Returns (value, k); `last` itself, k = 1, when
/// the horizon is inside the window or `last` is 0.
struct Grown {
    double value = 0.0;
    double k = 1.0;
};
Grown grow(double last, double half, double end, double middle, double far, double least = 1.0);

/// The numbers a window estimate is made with. They are the accuracy contract's and live in
/// python/gyrostat/accuracy.py (WINDOW, WINDOW_TIMES, WINDOW_SAFETY, FLOOR, WINDOW_FIT_STEPS and
/// the companion's gain ρ/(ρ − 1)), which passes them in: no default here restates them.
struct WindowRule {
    double fraction;           ///< the part of the span the window covers
    std::size_t least_times;   ///< the run's output times the window needs (else: not made here)
    double safety;             ///< a grown estimate is multiplied by this
    double floor;              ///< no quantity's estimate is below this
    double gain;               ///< the difference times this is the run's own error
    long fit_steps;            ///< the companion's least steps over the window for k to be fitted (else k = 1)
};

/// A window estimate of one run: each measured quantity's (engine.hpp: measured_quantities, in
/// that order), the largest growth exponent (`fitted`: whether it was fitted, window_from_differences),
/// the window's end and how many output times it compared. `made` is false when the run holds fewer than least_times output times in the window
/// (the caller samples the window itself) or crosses a separatrix of its model after the window's
/// first half (engine.hpp: first_crossing; the caller measures the whole span); `failure` says why there is no estimate when the
/// companion's run stopped ("status: message").
struct WindowEstimate {
    bool made = false;
    std::vector<double> per_quantity;
    double k = 1.0;
    bool grown = false;
    bool fitted = true;
    double window_end = 0.0;
    std::size_t times = 0;
    std::string failure;
    integrate::Result companion;  ///< the companion's run (window_estimate)
    double companion_max_step = std::numeric_limits<double>::infinity();  ///< its steps' limit (companion_step_limit)
};

/// The window estimate of `answer`, a run of `model` from (t0, y0) toward t1 (ending at t_last,
/// the horizon): the companion runs with `companion` (the answer's options with tolerances ρ
/// times smaller; its output times are set here to the answer's in the window), the quantities'
/// differences over the window, each running maximum grown to the horizon and multiplied by the
/// safety factor (python/gyrostat/accuracy.py: window_estimates). With `whole_span`, the
/// companion runs to t_last at every output time of the answer and each quantity's estimate is its
/// largest difference there times the gain (accuracy.py: span_estimates; no separatrix check, no
/// least number of times). None (`made` false) for a run that measures itself (method splitting,
/// a closed form: python/gyrostat/accuracy.py takes their own measures).
WindowEstimate window_estimate(const AnyModel& model, const integrate::Result& answer, double t0,
                               const Eigen::Ref<const Eigen::VectorXd>& y0, double t1,
                               const integrate::Options& companion, const WindowRule& rule,
                               const integrate::Control* control = nullptr, bool whole_span = false);

/// A run and, where the engine makes it, its window estimate (with `whole_span`, its measurement
/// over every output time): what a single solve with its default estimate makes
/// (python/gyrostat/solve.py), in one call. No estimate (`estimate.made` false) for a failed or
/// interrupted run, a run over no span, a run that measures itself (method splitting: Richardson
/// over its step; a closed form: its rounding), or where window_estimate makes none. With
/// `measured_only`, a whole span's companion too records only the measured outputs (it is not to
/// become the answer: python/gyrostat/contract.py, meet_single).
struct MeasuredRun {
    integrate::Result answer;
    WindowEstimate estimate;
};
MeasuredRun solve_measured(const AnyModel& model, double t0, const Eigen::Ref<const Eigen::VectorXd>& y0, double t1,
                           const integrate::Options& options, const integrate::Options& companion,
                           const WindowRule& rule, const integrate::Control* control = nullptr, bool whole_span = false,
                           bool measured_only = false);

/// Each member's window_estimate (or whole-span measurement), the companions run as one ensemble
/// (engine.hpp: solve_ensemble, with `threads` and `batch` as the answers' own): member i is a
/// run of models[i] (or models[0] for all) from (t0, y0s[i]). A member is measured here when it is
/// measurable as window_estimate says and its compared output times are those of the first such
/// member (one companion ensemble at those times); the others are left unmade (`made` false).
std::vector<WindowEstimate> window_estimates(const std::vector<const AnyModel*>& models,
                                             const std::vector<const integrate::Result*>& answers, double t0,
                                             const std::vector<Eigen::VectorXd>& y0s, double t1,
                                             const integrate::Options& companion, const WindowRule& rule, int threads,
                                             const integrate::Control* control = nullptr, bool batch = true,
                                             bool whole_span = false);

/// The most steps below which an answer's steps are taken as set by its first step's rule and the
/// span's end rather than by its tolerance (companion_step_limit).
inline constexpr long kFewSteps = 4;

/// A companion of a Runge–Kutta pair of one order at a tighter tolerance whose steps are fewer than
/// this times the answer's did not have its steps set by its tolerance (ρ = 4 asks DOP853 for
/// 4^(1/8) ≈ 1.19 times as many; bench/accuracy_cost.py's scenes take 1.12–1.22).
inline constexpr double kStepsFollowTolerance = 1.05;

/// The largest step a companion measuring `answer` (a run from t0) may take: half the answer's mean
/// step where the answer's steps are not its tolerance's, infinity otherwise. Two such cases:
/// * the answer took fewer than kFewSteps steps (DOP853's first step, grown by its largest factor,
///   then clipped to the end), so a companion at a tighter tolerance took the same ones and the
///   difference read rounding where the error lives inside the long steps' interpolation (the
///   triaxial averaged model over 300 s in two steps: 1e-16 against a true error of 2.9e-9);
/// * `first`, the stats of a companion run without the limit, took fewer than kStepsFollowTolerance
///   times the answer's steps, for a Runge–Kutta pair of one order: the steps sit on the method's
///   stability boundary, where the error does not follow the tolerance (the orthogonal torque over
///   t = 90.5 at rtol 1e-5 and 2.5e-6: 129 and 130 steps, errors 4.3e-4 and 3.6e-4, an estimate
///   0.2 times the true error); half those steps are inside it.
/// bench/contract_sweep.py found both. One rule for every companion: the engine's (window_estimate,
/// window_estimates) and python/gyrostat/accuracy.py's.
double companion_step_limit(const integrate::Result& answer, double t0, const integrate::Stats* first = nullptr);

/// Each quantity's estimate from its differences over a window (`apart`: quantities × times, at
/// the output times `times`, which start the span at t0), grown to `horizon` when it lies past the
/// window (the safety factor applied), else the window's own largest difference; both times the
/// gain, floored. The Python window for a run with too few output times, or a model ladder's
/// comparison, takes its numbers here too.
/// `companion_steps`: the steps the companion took over the window. With fewer than
/// rule.fit_steps, the growth exponent is not fitted but k = 1 (grow's value where `half` is 0):
/// the differences of a run of a few steps are a staircase, one stair per step, and the ratio of
/// their running maxima at the window's middle and end says where the stairs fall, not how the
/// error grows. Measured (bench/contract_sweep.py --explicit, seeds 1–6: 510 window estimates of
/// random scenes of every family at rtol 1e-4 … 1e-10, against DOP853 at rtol 1e-13): the fit read
/// k = 2 on runs of 4–20 steps whose error had stopped growing (the averaged models, constant
/// torques), estimates 31–101 times their true error; with k = 1 below 8 companion steps, 53
/// estimates outside [0.5, 30] times the true error became 17 (the flat plateau spans 6–16).
WindowEstimate window_from_differences(const Eigen::Ref<const Eigen::MatrixXd>& apart, const std::vector<double>& times,
                                       double t0, double horizon, const WindowRule& rule, bool to_horizon = true,
                                       long companion_steps = std::numeric_limits<long>::max());

}  // namespace gyrostat
