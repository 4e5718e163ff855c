// Collects outputs (time, state, named outputs) into a Result; shared by every integrator.
#pragma once

#include <cmath>
#include <memory>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "gyrostat/body.hpp"
#include "gyrostat/integrate/dense.hpp"
#include "gyrostat/integrate/options.hpp"
#include "gyrostat/model/system.hpp"

namespace gyrostat::integrate {

/// The declarations of `System` (options.hpp: Declarations), made on first use and kept.
template <class System>
const std::shared_ptr<const Declarations>& declarations() {
    static const std::shared_ptr<const Declarations> made = [] {
        auto d = std::make_shared<Declarations>();
        d->state_names.reserve(System::dim), d->state_units.reserve(System::dim);
        d->state_descriptions.reserve(System::dim);
        for (const auto& q : System::states) {
            d->state_names.emplace_back(q.name);
            d->state_units.emplace_back(q.unit);
            d->state_descriptions.emplace_back(q.description);
        }
        if constexpr (model::system::has_outputs<System>::value) {
            for (const auto& info : System::outputs_info) {
                d->output_names.emplace_back(info.name);
                d->output_units.emplace_back(info.unit);
                d->output_descriptions.emplace_back(info.description);
                d->output_conserved.push_back(info.conserved);
            }
        }
        return std::shared_ptr<const Declarations>(std::move(d));
    }();
    return made;
}

/// Names the state and the outputs of `System` in a Result (also for a run that fails before
/// its first output, so that an empty Result still says what it would hold). With the `system`,
/// output_kept says which conserved outputs its torques keep (model/system.hpp: keeps);
/// without it, every conserved output.
template <class System>
void describe(Result& result, const System* system = nullptr) {
    namespace sys = model::system;
    result.dim = System::dim;
    result.declared = declarations<System>();
    result.output_kept.clear();
    if constexpr (sys::has_outputs<System>::value) {
        result.output_kept.reserve(System::outputs_info.size());
        for (const auto& info : System::outputs_info) {
            bool kept = info.conserved;
            if constexpr (sys::has_keeps<System>::value)
                kept = kept && (system == nullptr || system->keeps(result.output_kept.size()));
            result.output_kept.push_back(kept);
        }
    }
}

/// An empty dense output for `System` when the options ask for one (the quaternion, where the
/// state has one, normalised on evaluation).
template <class System>
std::shared_ptr<DenseOutput> make_dense(const Options& options) {
    if (!options.dense_output) return nullptr;
    int quaternion = -1;
    for (int i = 0; i < System::dim; ++i)
        if (std::string(System::states[i].name) == "q_w") quaternion = i;
    return std::make_shared<DenseOutput>(System::dim, quaternion);
}

template <class System>
class Recorder {
public:
    using State = typename System::State;
    static constexpr int n_outputs = model::system::n_outputs<System>();

    /// `only_measured`: the outputs a run's error is measured on alone (Options::only_measured_outputs).
    Recorder(const System& system, Result& result, std::size_t expected, bool only_measured = false)
        : system_(system), result_(result), only_measured_(only_measured) {
        describe<System>(result_, &system_);
        const double bytes = static_cast<double>(expected) * (1 + System::dim + n_outputs) * sizeof(double);
        if (bytes > kMaxOutputBytes)
            throw std::invalid_argument(std::to_string(expected) + " output times would take " +
                                        format_value(bytes / (1024.0 * 1024 * 1024)) + " GiB for this model's " +
                                        std::to_string(System::dim) + " state components and " +
                                        std::to_string(n_outputs) + " outputs (limit 2 GiB for one run): ask for "
                                        "fewer outputs");
        result_.t.reserve(expected);
        result_.y.reserve(expected * System::dim);
        result_.outputs.reserve(expected * n_outputs);
    }

    /// Records y(t) and the model's named outputs there; constrained parts (a quaternion) are
    /// projected back onto their manifold first.
    void push(double t, State y) {
        model::system::project(system_, y);
        result_.t.push_back(t);
        result_.y.insert(result_.y.end(), y.data(), y.data() + System::dim);
        if constexpr (n_outputs > 0) {
            double out[n_outputs];
            if (only_measured_)
                model::system::measured_outputs(system_, t, y, out);
            else
                model::system::outputs(system_, t, y, out);
            result_.outputs.insert(result_.outputs.end(), out, out + n_outputs);
        }
    }

private:
    const System& system_;
    Result& result_;
    bool only_measured_;
};

/// The output grid of a stepping integrator and the next time to record: what every step does
/// with it after it is accepted (outputs inside the step from its continuous extension, those at
/// a terminal event, those at the step's end).
template <class System>
class OutputCursor {
public:
    using State = typename System::State;
    OutputCursor(Recorder<System>& record, std::vector<double> times, double direction)
        : record_(record), times_(std::move(times)), direction_(direction) {}

    /// Whether an output time is still to be recorded, and which.
    bool pending() const { return next_ < times_.size(); }
    double next_time() const { return times_[next_]; }

    /// Records the outputs at t0 (the initial state).
    void start(double t0, const State& y0) {
        while (next_ < times_.size() && times_[next_] == t0) record_.push(t0, y0), ++next_;
    }
    /// Records the outputs strictly inside the step ending at t_new from `dense(t)`; when the run
    /// ends at a terminal event t_stop (not NaN), those up to and at t_stop instead. Returns
    /// whether the run ended there.
    template <class Dense>
    bool inside(double t_new, double t_stop, Dense&& dense) {
        const bool terminated = !std::isnan(t_stop);
        while (next_ < times_.size() && direction_ * (times_[next_] - t_new) < 0.0 &&
               (!terminated || direction_ * (times_[next_] - t_stop) <= 0.0)) {
            record_.push(times_[next_], dense(times_[next_]));
            ++next_;
        }
        if (terminated)
            while (next_ < times_.size() && times_[next_] == t_stop) record_.push(t_stop, dense(t_stop)), ++next_;
        return terminated;
    }
    /// Records the outputs at the step's end t, or the step itself with `every_step`.
    void at_end(double t, const State& y, bool every_step) {
        bool recorded = false;
        while (next_ < times_.size() && times_[next_] == t) {
            record_.push(t, y);
            ++next_;
            recorded = true;
        }
        if (every_step && !recorded) record_.push(t, y);
    }

private:
    Recorder<System>& record_;
    std::vector<double> times_;
    double direction_;
    std::size_t next_ = 0;
};

inline std::string format_number(double x, int precision = 6) {
    std::ostringstream s;
    s.precision(precision);
    s << x;
    return s.str();
}

template <class State>
bool all_finite(const State& y) {
    for (Eigen::Index i = 0; i < y.size(); ++i)
        if (!std::isfinite(y[i])) return false;
    return true;
}

/// Notes where a run stopped (Result::t_last, y_last, h_next), for continuing it.
template <class State>
void keep_last(Result& result, double t, const State& y, double h_next) {
    result.t_last = t;
    result.y_last.assign(y.data(), y.data() + y.size());
    result.h_next = h_next;
}

/// Ends a run that was asked to stop: status Interrupted, and where.
inline void mark_interrupted(Result& result, double t) {
    result.status = Status::Interrupted;
    result.message = "interrupted at t = " + format_number(t, 17) + " on request; the outputs up to there are kept";
}

}  // namespace gyrostat::integrate
