// C++ tests of the core, independent of Python: every integrator against the closed form,
// invariants, failure statuses, ensembles, input validation.
#include <cmath>
#include <cstdio>
#include <functional>
#include <utility>
#include <stdexcept>
#include <string>

#include "gyrostat/ensemble.hpp"
#include "gyrostat/integrate/solve.hpp"
#include "gyrostat/model/gyrostat.hpp"
#include "gyrostat/model/torque_free.hpp"

using namespace gyrostat;
using integrate::Method;

static int failures = 0, passes = 0;
#define CHECK(cond, what)                                                          \
    do {                                                                           \
        if (cond) {                                                                \
            ++passes;                                                              \
        } else {                                                                   \
            ++failures;                                                            \
            std::printf("FAIL %s:%d: %s  [%s]\n", __FILE__, __LINE__, what, #cond); \
        }                                                                          \
    } while (0)

template <class F>
static bool throws_invalid(F f) {
    try {
        f();
    } catch (const std::invalid_argument&) {
        return true;
    }
    return false;
}

int main() {
    const Body body(Vec3(1.0, 2.0, 3.0));
    const Vec3 w0(1.0, 0.5, -0.3);
    const model::Gyrostat<false> free_body(body, TorqueSet{});
    const model::TorqueFreeSolution exact(body, w0);

    // Every integrator against the closed form over 20 periods at rtol 1e-10. Bounds: the global
    // error measured on this problem (dop853 4.1e-9, cvode_bdf 2.3e-7, cvode_adams 3.5e-7,
    // arkode_verner6 1.1e-5 — its SUNDIALS 6.4 table converges at order 3 —, fehlberg 7.9e-10,
    // taylor 1.2e-9)
    // times 10: a regression of one order of magnitude fails.
    const std::pair<Method, double> bounds[] = {{Method::Dop853, 4e-8},        {Method::CvodeBdf, 2.3e-6},
                                                {Method::CvodeAdams, 3.5e-6},   {Method::ArkodeVerner6, 1.1e-4},
                                                {Method::ArkodeFehlberg8, 8e-9},  {Method::Taylor, 1.3e-8}};
    for (const auto& [m, bound] : bounds) {
        integrate::Options o;
        o.method = m;
        o.rtol = 1e-10;
        o.atol = 1e-12;
        const double t1 = 20.0 * exact.period();
        for (int i = 0; i <= 50; ++i) o.t_eval.push_back(t1 * i / 50.0);
        const auto r = integrate::solve(free_body, 0.0, w0, t1, o);
        CHECK(r.success(), integrate::method_name(m));
        double err = 0.0;
        for (std::size_t i = 0; i < r.size(); ++i) {
            const Vec3 ref = exact.omega(r.t[i]);
            err = std::max(err, (Vec3(r.y[3 * i], r.y[3 * i + 1], r.y[3 * i + 2]) - ref).norm());
        }
        std::printf("%-18s max |ω − ω_exact| = %.3e over %zu outputs, %ld steps\n", integrate::method_name(m), err, r.size(),
                    r.stats.steps);
        CHECK(err < bound, integrate::method_name(m));
        // |G| and T conserved to the tolerance level
        const double g0 = r.invariants[0], e0 = r.invariants[1];
        double drift = 0.0;
        for (std::size_t i = 0; i < r.size(); ++i)
            drift = std::max({drift, std::abs(r.invariants[2 * i] - g0) / g0, std::abs(r.invariants[2 * i + 1] - e0) / e0});
        CHECK(drift < bound, "invariant drift");  // |G|, T ~ 1: same size as the state error
    }

    // Quaternion norm stays 1 to rounding at every output.
    {
        const model::Gyrostat<true> with_attitude(body, TorqueSet{});
        model::Gyrostat<true>::State y0;
        y0 << w0, 1.0, 0.0, 0.0, 0.0;
        integrate::Options o;
        o.rtol = 1e-9;
        for (int i = 0; i <= 100; ++i) o.t_eval.push_back(i);
        const auto r = integrate::solve(with_attitude, 0.0, y0, 100.0, o);
        double worst = 0.0;
        for (std::size_t i = 0; i < r.size(); ++i) {
            Eigen::Map<const Eigen::Vector4d> q(&r.y[7 * i + 3]);
            worst = std::max(worst, std::abs(q.norm() - 1.0));
        }
        CHECK(worst < 4e-16, "quaternion norm");
    }

    // A stiff damping makes the explicit method run out of steps and say why.
    {
        const model::Gyrostat<false> stiff(body, TorqueSet({torque::LinearDamping(1e6 * Mat3::Identity())}));
        integrate::Options o;
        o.max_steps = 2000;
        const auto r = integrate::solve(stiff, 0.0, w0, 10.0, o);
        CHECK(r.status == integrate::Status::MaxStepsReached, "stiff: max steps");
        CHECK(r.message.find("cvode_bdf") != std::string::npos, "stiff: suggestion");
        o.method = Method::CvodeBdf;
        const auto rb = integrate::solve(stiff, 0.0, w0, 10.0, o);
        CHECK(rb.success(), "stiff: BDF succeeds");
    }

    // Validation.
    CHECK(throws_invalid([] { Body(Vec3(-1.0, 2.0, 2.0)); }), "negative moment");
    CHECK(throws_invalid([] { Body(Vec3(1.0, 1.0, 3.0)); }), "triangle inequality");
    CHECK(throws_invalid([&] {
              integrate::Options o;
              o.rtol = 0.0;
              integrate::solve(free_body, 0.0, w0, 1.0, o);
          }),
          "rtol <= 0");

    // Ensemble: identical to single runs; a bad member does not spoil the others.
    {
        std::vector<model::Gyrostat<false>::State> starts;
        for (int i = 0; i < 8; ++i) starts.emplace_back(1.0 + 0.1 * i, 0.5, -0.3);
        starts[3][1] = std::nan("");
        integrate::Options o;
        o.t_eval = {0.0, 5.0, 10.0};
        const auto results = solve_ensemble(std::vector<model::Gyrostat<false>>{free_body}, starts, 0.0, 10.0, o, 2);
        CHECK(results[3].status == integrate::Status::InvalidInput, "bad member flagged");
        for (int i = 0; i < 8; ++i) {
            if (i == 3) continue;
            const auto single = integrate::solve(free_body, 0.0, starts[i], 10.0, o);
            CHECK(single.y == results[i].y, "ensemble equals single run");
        }
    }

    std::printf("%d passed, %d failed\n", passes, failures);
    return failures == 0 ? 0 : 1;
}
