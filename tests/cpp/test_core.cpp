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
#include "gyrostat/model/averaged.hpp"
#include "gyrostat/model/gyrostat.hpp"
#include "gyrostat/model/lagrange_top.hpp"
#include "gyrostat/model/moving_mass.hpp"
#include "gyrostat/model/orthogonal.hpp"
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

    // Paper 000 symmetric scene: cavity + axial torque make the (a, r) reduction exact, so the
    // averaged model equals the full one to the integration tolerance (rtol 1e-10 over 30 s).
    {
        const Body sym(Vec3(8.0, 8.0, 4.0));
        const TorqueSet set({torque::ViscousCavity(1260.0, 1000.0, 0.48), torque::Constant(Vec3(0.0, 0.0, -0.01))});
        integrate::Options o;
        o.rtol = 1e-10;
        o.atol = 1e-12;
        o.t_eval = {0.0, 10.0, 20.0, 30.0};
        const auto full = integrate::solve(model::Gyrostat<false>(sym, set), 0.0, Vec3(1.0, 0.0, 1.0), 30.0, o);
        const auto avg = integrate::solve(model::AveragedSymmetric(sym, set), 0.0, Eigen::Vector2d(1.0, 1.0), 30.0, o);
        double err = 0.0;
        for (std::size_t i = 0; i < full.size(); ++i)
            err = std::max({err, std::abs(std::hypot(full.y[3 * i], full.y[3 * i + 1]) - avg.y[2 * i]),
                            std::abs(full.y[3 * i + 2] - avg.y[2 * i + 1])});
        CHECK(full.success() && avg.success() && err < 1e-8, "averaged = full for the exact symmetric reduction");
    }

    // Explicit moving mass, stiff damper: |K| conserved by BDF (rtol 1e-10: drift < 1e-8).
    {
        const model::MovingMass mm(Body(Vec3(1.0, 1.0, 1.6)), 0.18, 1.0, std::sqrt(2000.0), 400.0, TorqueSet{});
        integrate::Options o;
        o.method = Method::CvodeBdf;
        o.rtol = 1e-10;
        o.atol = 1e-13;
        const auto r = integrate::solve(mm, 0.0, mm.quasi_static_state(Vec3(0.8, 0.0, 1.0)), 20.0, o);
        CHECK(r.success(), "moving mass BDF");
        CHECK(std::abs(r.invariants[2] / r.invariants[0] - 1.0) < 1e-8, "moving mass |K| conserved");
        CHECK(r.invariants[3] < r.invariants[1], "moving mass energy dissipated");
    }

    // Lagrange top without perturbation: G_z, H, r conserved (rtol 1e-11 over 60 s: 1e-9).
    {
        const model::LagrangeTop top(Body(Vec3(1.5, 1.5, 1.0)), 0.5, TorqueSet{});
        model::LagrangeTop::State y0;
        const double half = 0.5 * 60.0 * M_PI / 180.0;  // tilt 60° about the body x axis
        y0 << 0.0, 0.0, std::sqrt(3.0), std::cos(half), std::sin(half), 0.0, 0.0;
        integrate::Options o;
        o.rtol = 1e-11;
        o.atol = 1e-13;
        const auto r = integrate::solve(top, 0.0, y0, 60.0, o);
        double drift = 0.0;
        for (int k = 0; k < 3; ++k) drift = std::max(drift, std::abs(r.invariants[3 + k] - r.invariants[k]));
        CHECK(r.success() && drift < 1e-9, "Lagrange top first integrals");
    }

    // Orthogonal torque: |G| and h = ω·Jω conserved (the torque is along ω × G).
    {
        const model::OrthogonalTorque<false> servo(Body(Vec3(2.0, 3.0, 4.0), Vec3(0.3, -0.2, 0.5)),
                                                   model::MagnitudeLaw::constant(0.15));
        model::OrthogonalTorque<false>::State y0;
        y0 << 1.0, 0.5, -0.8, 0.0;
        integrate::Options o;
        o.rtol = 1e-11;
        o.atol = 1e-13;
        const auto r = integrate::solve(servo, 0.0, y0, 60.0, o);
        const std::size_t last = r.size() - 1;
        CHECK(r.success(), "orthogonal torque run");
        CHECK(std::abs(r.invariants[2 * last] / r.invariants[0] - 1.0) < 1e-9, "orthogonal |G|");
        CHECK(std::abs(r.invariants[2 * last + 1] / r.invariants[1] - 1.0) < 1e-9, "orthogonal h");
        CHECK(r.y[4 * last + 3] > 0.0 && r.y[4 * last + 3] < 60.0, "tau advances slower than t");
    }

    std::printf("%d passed, %d failed\n", passes, failures);
    return failures == 0 ? 0 : 1;
}
