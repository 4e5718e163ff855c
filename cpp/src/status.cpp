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
    const char* description;  ///< one line (docs/integrators.md has the details)
};
constexpr NamedMethod kMethods[] = {
    {"dop853", Method::Dop853, "Dormand-Prince 8(5,3) explicit Runge-Kutta, 7th-order dense output: non-stiff problems"},
    {"cvode_bdf", Method::CvodeBdf, "SUNDIALS CVODE, variable-order BDF (1-5) with Newton iterations: stiff problems"},
    {"cvode_adams", Method::CvodeAdams, "SUNDIALS CVODE, variable-order Adams-Moulton (1-12): smooth non-stiff problems"},
    {"arkode_verner6", Method::ArkodeVerner6, "SUNDIALS ARKODE Verner 6(5) explicit Runge-Kutta, 8 stages: cross-checks (converges at order 3 in SUNDIALS 6.4)"},
    {"arkode_fehlberg8", Method::ArkodeFehlberg8, "SUNDIALS ARKODE Fehlberg 8(7) explicit Runge-Kutta, 13 stages: cross-checks"},
    {"taylor", Method::Taylor, "Taylor series of adaptive order by automatic differentiation: gyrostat with constant and linear torques, tight tolerances"},
    {"splitting", Method::Splitting, "the exact free-body flow composed with the perturbation's flow, fixed step, order 2, 4 or 6"},
    {"auto", Method::Auto, "dop853 while the problem is not stiff, cvode_bdf while it is, switched along the run"},
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

std::vector<std::string> method_descriptions() {
    std::vector<std::string> lines;
    for (const auto& m : kMethods) lines.emplace_back(m.description);
    return lines;
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

namespace {

/// The scalar options check_option knows, in the order of its message.
enum class Scalar { Rtol, Atol, NOut, MaxSteps, FirstStep, MaxStep, Step, SplittingOrder };

/// The rule of one scalar option, named `name` in the message: nothing is formatted unless it
/// throws (validate() runs these on every solve).
void check_scalar(Scalar option, const char* name, double x) {
    const auto fail = [&](const std::string& why) {
        const bool count = option == Scalar::NOut || option == Scalar::MaxSteps || option == Scalar::SplittingOrder;
        const bool whole = count && std::isfinite(x) && x == std::floor(x) && std::abs(x) < 9e18;
        throw std::invalid_argument(std::string(name) + " = " +
                                    (whole ? std::to_string(static_cast<long long>(x)) : format_value(x)) + why);
    };
    switch (option) {
        case Scalar::Rtol: {
            // Below ~50 machine epsilons no double-precision integrator can honour a relative tolerance.
            constexpr double kSmallestRtol = 1e-14;
            if (!std::isfinite(x) || !(x > 0.0)) fail(" must be a finite positive number");
            if (x < kSmallestRtol) fail(" is below 1e-14 (about 50 machine epsilons): not attainable in double precision");
            if (x >= 1.0) fail(" must be below 1");
            return;
        }
        case Scalar::Atol:
            if (!std::isfinite(x) || x < 0.0) fail(" must be finite and non-negative");
            return;
        case Scalar::NOut:
            // Each output row holds t and at least two state components: n_out·24 bytes at the least.
            if (x * 24.0 > kMaxOutputBytes)
                fail(" output times would take at least " + format_value(x * 24.0 / (1024.0 * 1024 * 1024)) +
                     " GiB (limit 2 GiB for one run): ask for fewer outputs");
            if (!(x >= 0.0) || x == 1.0 || x != std::floor(x)) fail(" must be at least 2 (or 0: t0 and t1 only)");
            return;
        case Scalar::MaxSteps:
            if (!(x > 0.0) || x != std::floor(x)) fail(" must be positive");
            return;
        case Scalar::FirstStep:
            if (!std::isfinite(x) || x < 0.0) fail(" must be finite and >= 0 (0: automatic)");
            return;
        case Scalar::MaxStep:
            if (std::isnan(x) || !(x > 0.0)) fail(" must be positive");
            return;
        case Scalar::Step:
            if (!std::isfinite(x) || x < 0.0) fail(" must be finite and >= 0 (the splitting step; 0: not set)");
            return;
        case Scalar::SplittingOrder:
            if (x != 2 && x != 4 && x != 6) fail(" must be 2, 4 or 6");
            return;
    }
}

}  // namespace

void check_option(const std::string& name, double x) {
    static const std::pair<const char*, Scalar> known[] = {
        {"rtol", Scalar::Rtol},           {"atol", Scalar::Atol},         {"n_out", Scalar::NOut},
        {"max_steps", Scalar::MaxSteps},  {"first_step", Scalar::FirstStep}, {"max_step", Scalar::MaxStep},
        {"step", Scalar::Step},           {"splitting_order", Scalar::SplittingOrder}};
    for (const auto& [known_name, option] : known)
        if (name == known_name) return check_scalar(option, known_name, x);
    throw std::invalid_argument("no option '" + name + "' (rtol, atol, n_out, max_steps, first_step, max_step, step, splitting_order)");
}

void validate(const Options& o, double t0, double t1) {
    check_scalar(Scalar::Rtol, "rtol", o.rtol);
    check_scalar(Scalar::Atol, "atol", o.atol);
    if (!std::isfinite(t0)) throw std::invalid_argument("t0 = " + format_value(t0) + " is not finite");
    if (!std::isfinite(t1)) throw std::invalid_argument("t1 = " + format_value(t1) + " is not finite");
    check_scalar(Scalar::NOut, "n_out", static_cast<double>(o.n_out));
    check_scalar(Scalar::MaxSteps, "max_steps", static_cast<double>(o.max_steps));
    check_scalar(Scalar::FirstStep, "first_step", o.first_step);
    check_scalar(Scalar::MaxStep, "max_step", o.max_step);
    check_scalar(Scalar::Step, "step", o.step);
    check_scalar(Scalar::SplittingOrder, "splitting_order", o.splitting_order);
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

namespace gyrostat::integrate {
Options recorded(const Options& o) {
    Options r;
    r.method = o.method, r.rtol = o.rtol, r.atol = o.atol, r.n_out = o.n_out, r.every_step = o.every_step;
    r.max_steps = o.max_steps, r.first_step = o.first_step, r.max_step = o.max_step, r.dense_output = o.dense_output;
    r.step = o.step, r.splitting_order = o.splitting_order;
    return r;
}
}  // namespace gyrostat::integrate
