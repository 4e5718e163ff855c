// Events: zero crossings of g(t, y) located on each integrator's own continuous extension.
#pragma once

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "gyrostat/integrate/options.hpp"
#include "gyrostat/integrate/recorder.hpp"
#include "gyrostat/model/system.hpp"

namespace gyrostat::integrate {

/// Watches the events of a run: after every accepted step it evaluates g at the step's end,
/// and where g changed sign (in the event's direction) it finds the root on the step's
/// continuous extension with the Illinois method to a few ulps of t, and records (t*, y(t*)).
template <class System>
class EventLocator {
public:
    using State = typename System::State;
    static constexpr int n_outputs = model::system::n_outputs<System>();

    EventLocator(const System& system, const std::vector<Event>& events, Result& result)
        : system_(system), events_(events), result_(result), previous_(events.size()), current_(events.size()),
          sampled_at_(events.size()), due_(events.size(), 1), count_(events.size(), 0) {
        for (const Event& e : events_) {
            if (e.quantity == Event::Quantity::State && (e.index < 0 || e.index >= System::dim))
                throw std::invalid_argument("event '" + e.name + "': state component " + std::to_string(e.index) +
                                            " does not exist (the state has " + std::to_string(System::dim) + ")");
            if (e.quantity == Event::Quantity::Output && (e.index < 0 || e.index >= n_outputs))
                throw std::invalid_argument("event '" + e.name + "': output " + std::to_string(e.index) +
                                            " does not exist (the model records " + std::to_string(n_outputs) + ")");
            if (e.quantity == Event::Quantity::Function && !e.function)
                throw std::invalid_argument("event '" + e.name + "' has no function");
            if (e.direction < -1 || e.direction > 1 || e.terminal < 0)
                throw std::invalid_argument("event '" + e.name + "': direction must be -1, 0 or 1 and terminal >= 0");
            if (!(e.sample_interval >= 0.0) || !std::isfinite(e.sample_interval))
                throw std::invalid_argument("event '" + e.name + "': sample_interval must be finite and >= 0");
        }
        result_.event_names.clear();
        for (const Event& e : events_) result_.event_names.push_back(e.name);
        result_.t_events.assign(events_.size(), {});
        result_.y_events.assign(events_.size(), {});
    }

    bool active() const { return !events_.empty(); }

    /// g of every event at the start of the run.
    void start(double t, const State& y) {
        if (!active()) return;
        std::fill(sampled_at_.begin(), sampled_at_.end(), t);
        values(t, y, previous_, true);
    }

    /// After an accepted step from t0 to (t1, y1), with `dense(t)` the step's continuous
    /// extension: records the crossings inside (t0, t1] in time order and returns the time of
    /// the crossing that ends the run (a terminal event's n-th), or NaN when the run goes on.
    template <class Dense>
    double step(double t0, double t1, const State& y1, Dense&& dense) {
        if (!active()) return std::numeric_limits<double>::quiet_NaN();
        values(t1, y1, current_, false);
        std::vector<std::pair<double, std::size_t>> roots;
        for (std::size_t i = 0; i < events_.size(); ++i) {
            const double a = previous_[i], b = current_[i];
            const bool up = a < 0.0 && b >= 0.0, down = a > 0.0 && b <= 0.0;
            const int direction = events_[i].direction;
            if (!((up && direction >= 0) || (down && direction <= 0))) continue;
            roots.emplace_back(events_[i].sample_interval > 0.0 ? t1 : root(i, t0, a, t1, b, dense), i);
        }
        std::swap(previous_, current_);
        const double direction = t1 >= t0 ? 1.0 : -1.0;
        std::sort(roots.begin(), roots.end(),
                  [&](const auto& x, const auto& y) { return direction * x.first < direction * y.first; });
        for (const auto& [t, i] : roots) {
            State y = dense(t);
            model::system::project(system_, y);
            result_.t_events[i].push_back(t);
            result_.y_events[i].insert(result_.y_events[i].end(), y.data(), y.data() + System::dim);
            if (events_[i].terminal > 0 && ++count_[i] >= events_[i].terminal) {
                result_.terminal_event = static_cast<int>(i);
                return t;
            }
        }
        return std::numeric_limits<double>::quiet_NaN();
    }

private:
    double g(std::size_t i, double t, const State& y, const double* outputs) const {
        const Event& e = events_[i];
        switch (e.quantity) {
            case Event::Quantity::State: return y[e.index] - e.value;
            case Event::Quantity::Output: return outputs[e.index] - e.value;
            default: return e.function(t, y.data(), System::dim) - e.value;
        }
    }

    /// g of every event at (t, y) into `out`; a sampled event (Event::sample_interval) keeps its
    /// last value (previous_) until t is that far from its last evaluation (`all`: every event).
    void values(double t, const State& y, std::vector<double>& out, bool all) {
        bool need_outputs = false;
        for (std::size_t i = 0; i < events_.size(); ++i) {
            const double interval = events_[i].sample_interval;
            due_[i] = all || interval == 0.0 || std::abs(t - sampled_at_[i]) >= interval;
            if (due_[i] && interval > 0.0) sampled_at_[i] = t;
            need_outputs |= due_[i] && events_[i].quantity == Event::Quantity::Output;
        }
        double outputs[n_outputs > 0 ? n_outputs : 1];
        if constexpr (n_outputs > 0) {
            if (need_outputs) model::system::outputs(system_, t, y, outputs);
        }
        for (std::size_t i = 0; i < events_.size(); ++i) out[i] = due_[i] ? g(i, t, y, outputs) : previous_[i];
    }

    double value_at(std::size_t i, double t, const State& y) const {
        double outputs[n_outputs > 0 ? n_outputs : 1];
        if constexpr (n_outputs > 0) {
            if (events_[i].quantity == Event::Quantity::Output) model::system::outputs(system_, t, y, outputs);
        }
        return g(i, t, y, outputs);
    }

    /// The root of g_i on [ta, tb] (g(ta) = ga, g(tb) = gb of opposite signs or gb = 0) by the
    /// Illinois variant of regula falsi: superlinear, and the bracket always shrinks; it stops
    /// when the bracket is a few ulps of t wide or g is exactly zero.
    template <class Dense>
    double root(std::size_t i, double ta, double ga, double tb, double gb, Dense& dense) const {
        if (gb == 0.0) return tb;
        const double tolerance = 4.0 * std::numeric_limits<double>::epsilon() * std::max(std::abs(ta), std::abs(tb));
        int side = 0;
        for (int iteration = 0; iteration < 200 && std::abs(tb - ta) > tolerance; ++iteration) {
            double t = (ta * gb - tb * ga) / (gb - ga);
            if (!(t > std::min(ta, tb) && t < std::max(ta, tb))) t = 0.5 * (ta + tb);
            const double gt = value_at(i, t, dense(t));
            if (gt == 0.0) return t;
            if ((gt > 0.0) == (gb > 0.0)) {
                tb = t, gb = gt;
                if (side == -1) ga *= 0.5;
                side = -1;
            } else {
                ta = t, ga = gt;
                if (side == 1) gb *= 0.5;
                side = 1;
            }
        }
        return std::abs(gb) <= std::abs(ga) ? tb : ta;
    }

    const System& system_;
    const std::vector<Event>& events_;
    Result& result_;
    std::vector<double> previous_, current_;
    std::vector<double> sampled_at_;  ///< the time each event's g was last evaluated (sampled events)
    std::vector<char> due_;           ///< whether each event's g is evaluated at this step end
    std::vector<int> count_;
};

/// Ends a run at a terminal event: success, and which event stopped it where.
inline void mark_terminated(Result& result, double t) {
    result.message = "terminal event " + std::to_string(result.terminal_event) + " ('" +
                     result.event_names[static_cast<std::size_t>(result.terminal_event)] + "') at t = " +
                     format_number(t, 17);
}

}  // namespace gyrostat::integrate
