#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "gyrostat/body.hpp"
#include "gyrostat/integrate/options.hpp"

namespace gyrostat::integrate {

namespace {
struct NamedMethod {
    const char* name;
    Method method;
};
constexpr NamedMethod kMethods[] = {
    {"dop853", Method::Dop853},
    {"cvode_bdf", Method::CvodeBdf},
    {"cvode_adams", Method::CvodeAdams},
    {"arkode_verner6", Method::ArkodeVerner6},
    {"arkode_fehlberg8", Method::ArkodeFehlberg8},
    {"taylor", Method::Taylor},
    {"splitting", Method::Splitting},
    {"auto", Method::Auto},
};

}  // namespace

Method method_from_name(const std::string& name) {
    std::string known;
    for (const auto& m : kMethods) {
        if (name == m.name) return m.method;
        known += std::string(known.empty() ? "" : ", ") + m.name;
    }
    throw std::invalid_argument("unknown method '" + name + "'; known methods: " + known);
}

const char* method_name(Method method) {
    for (const auto& m : kMethods)
        if (m.method == method) return m.name;
    return "unknown";
}

std::vector<std::string> method_names() {
    std::vector<std::string> names;
    for (const auto& m : kMethods) names.emplace_back(m.name);
    return names;
}

const char* status_name(Status s) {
    switch (s) {
        case Status::Success: return "success";
        case Status::MaxStepsReached: return "max_steps_reached";
        case Status::StepSizeUnderflow: return "step_size_underflow";
        case Status::NonFiniteState: return "non_finite_state";
        case Status::SolverFailure: return "solver_failure";
        case Status::InvalidInput: return "invalid_input";
        case Status::Interrupted: return "interrupted";
    }
    return "unknown";
}

void validate(const Options& o, double t0, double t1) {
    // Below ~50 machine epsilons no double-precision integrator can honour a relative tolerance.
    constexpr double kSmallestRtol = 1e-14;
    if (!std::isfinite(o.rtol) || !(o.rtol > 0.0))
        throw std::invalid_argument("rtol = " + format_value(o.rtol) + " must be a finite positive number");
    if (o.rtol < kSmallestRtol)
        throw std::invalid_argument("rtol = " + format_value(o.rtol) +
                                    " is below 1e-14 (about 50 machine epsilons): not attainable in double precision");
    if (o.rtol >= 1.0) throw std::invalid_argument("rtol = " + format_value(o.rtol) + " must be below 1");
    if (!std::isfinite(o.atol) || o.atol < 0.0)
        throw std::invalid_argument("atol = " + format_value(o.atol) + " must be finite and non-negative");
    if (!std::isfinite(t0)) throw std::invalid_argument("t0 = " + format_value(t0) + " is not finite");
    if (!std::isfinite(t1)) throw std::invalid_argument("t1 = " + format_value(t1) + " is not finite");
    // Each output row holds t and at least two state components: n_out·24 bytes at the least.
    if (static_cast<double>(o.n_out) * 24.0 > kMaxOutputBytes)
        throw std::invalid_argument("n_out = " + std::to_string(o.n_out) + " output times would take at least " +
                                    format_value(static_cast<double>(o.n_out) * 24.0 / (1024.0 * 1024 * 1024)) +
                                    " GiB (limit 2 GiB for one run): ask for fewer outputs");
    if (o.n_out < 0 || o.n_out == 1)
        throw std::invalid_argument("n_out = " + std::to_string(o.n_out) + " must be at least 2 (or 0: t0 and t1 only)");
    if (o.max_steps <= 0) throw std::invalid_argument("max_steps = " + std::to_string(o.max_steps) + " must be positive");
    if (!std::isfinite(o.first_step) || o.first_step < 0.0)
        throw std::invalid_argument("first_step = " + format_value(o.first_step) + " must be finite and >= 0 (0: automatic)");
    if (std::isnan(o.max_step) || !(o.max_step > 0.0))
        throw std::invalid_argument("max_step = " + format_value(o.max_step) + " must be positive");
    if (!std::isfinite(o.step) || o.step < 0.0)
        throw std::invalid_argument("step = " + format_value(o.step) + " must be finite and >= 0 (the splitting step; 0: not set)");
    if (o.splitting_order != 2 && o.splitting_order != 4 && o.splitting_order != 6)
        throw std::invalid_argument("splitting_order = " + std::to_string(o.splitting_order) + " must be 2, 4 or 6");
    const double direction = t1 >= t0 ? 1.0 : -1.0;
    for (std::size_t i = 0; i < o.t_eval.size(); ++i) {
        const double t = o.t_eval[i];
        if (!std::isfinite(t)) throw std::invalid_argument("t_eval[" + std::to_string(i) + "] = " + format_value(t) + " is not finite");
        if ((t - t0) * direction < 0.0 || (t - t1) * direction > 0.0)
            throw std::invalid_argument("t_eval[" + std::to_string(i) + "] = " + format_value(t) + " lies outside [" +
                                        format_value(std::min(t0, t1)) + ", " + format_value(std::max(t0, t1)) + "]");
        if (i > 0 && (t - o.t_eval[i - 1]) * direction < 0.0)
            throw std::invalid_argument("t_eval[" + std::to_string(i) + "] = " + format_value(t) +
                                        " is out of order: t_eval must be monotone in the direction of integration");
    }
}

std::vector<double> output_times(const Options& o, double t0, double t1) {
    if (!o.t_eval.empty()) return o.t_eval;
    if (o.n_out >= 2) {  // as numpy.linspace: t0 + i·(t1 − t0)/(n − 1), the last one exactly t1
        std::vector<double> times(static_cast<std::size_t>(o.n_out));
        const double step = (t1 - t0) / static_cast<double>(o.n_out - 1);
        for (long i = 0; i + 1 < o.n_out; ++i) times[static_cast<std::size_t>(i)] = t0 + static_cast<double>(i) * step;
        times.back() = t1;
        return times;
    }
    if (t0 == t1) return {t0};
    return {t0, t1};
}

}  // namespace gyrostat::integrate
