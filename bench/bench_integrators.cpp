// gyrostat_bench: times each integrator on standard problems across tolerances and prints
// machine-readable rows:
//   problem,method,rtol,error,steps,rhs_evals,seconds
// error is the max-norm error of the final state against the problem's reference; seconds is the
// best of several repetitions of one whole trajectory (the machine is shared and noisy).
// Usage: gyrostat_bench [--quick | --taylor [RTOLS] | --taylor-profile | --averaged-rhs] [--help]  (--help describes them)
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <string>
#include <vector>

#include "gyrostat/ensemble.hpp"
#include "gyrostat/solve_system.hpp"
#include "gyrostat/integrate/taylor.hpp"
#include "gyrostat/model/averaged.hpp"
#include "gyrostat/model/averaged_triaxial.hpp"
#include "gyrostat/model/gyrostat.hpp"
#include "gyrostat/model/moving_mass.hpp"
#include "gyrostat/model/torque_free.hpp"

using namespace gyrostat;
using integrate::Method;
using Clock = std::chrono::steady_clock;

namespace {

double seconds_of(const std::function<void()>& run, double budget = 0.3) {
    double best = 1e300, spent = 0.0;
    for (int k = 0; k < 50 && (k < 3 || spent < budget); ++k) {
        const auto start = Clock::now();
        run();
        const double s = std::chrono::duration<double>(Clock::now() - start).count();
        best = std::min(best, s);
        spent += s;
    }
    return best;
}

template <class System>
void sweep(const char* problem, const System& system, const typename System::State& y0, double t1,
           const typename System::State& reference, const std::vector<Method>& methods,
           const std::vector<double>& tolerances) {
    for (Method m : methods) {
        for (double rtol : tolerances) {
            integrate::Options o;
            o.n_out = 0;  // t0 and t1 only (the engine's default is 1001 outputs)
            o.method = m;
            o.rtol = rtol;
            o.atol = rtol * 1e-3;
            o.max_steps = 100'000'000;
            integrate::Result result;
            const double s = seconds_of([&] { result = integrate::solve(system, 0.0, y0, t1, o); });
            if (!result.success()) {
                std::printf("# %s %s rtol=%g failed: %s\n", problem, integrate::method_name(m), rtol, result.message.c_str());
                continue;
            }
            const auto n = result.size() - 1;
            double err = 0.0;
            for (int i = 0; i < System::dim; ++i) err = std::max(err, std::abs(result.y[n * System::dim + i] - reference[i]));
            std::printf("%s,%s,%.0e,%.6e,%ld,%ld,%.6e\n", problem, integrate::method_name(m), rtol, err, result.stats.steps,
                        result.stats.rhs_evals, s);
            std::fflush(stdout);
        }
    }
}

// The Taylor integrator against heyoka (bench/taylor_vs_heyoka.py): the torque-free body
// I = (2, 3, 4), omega0 = (0.4, 0.9, -0.3) (the long-horizon problem, bench/long_horizon.py), omega only,
// t = 0 -> 2000 with the final state as the only output; reference: the closed form.
const Body free_body(Vec3(2.0, 3.0, 4.0));
const Vec3 free_w0(0.4, 0.9, -0.3);
constexpr double free_t1 = 2000.0;

void taylor_rows(const std::vector<double>& tolerances) {
    const model::TorqueFreeSolution exact(free_body, free_w0);
    std::printf("problem,method,rtol,error,steps,rhs_evals,seconds\n");
    std::printf("# free_2000: I = (2, 3, 4), omega0 = (0.4, 0.9, -0.3), t1 = 2000, reference = closed form\n");
    std::printf("# reference_state free_2000 %.17g %.17g %.17g\n", exact.omega(free_t1)[0], exact.omega(free_t1)[1],
                exact.omega(free_t1)[2]);
    sweep("free_2000", model::Gyrostat<false>(free_body, TorqueSet{}), free_w0, free_t1, exact.omega(free_t1),
          {Method::Taylor}, tolerances);
}

/// The parts of one Taylor step of order P on free_2000, as chains of dependent steps (each step
/// starts from the previous step's result, as in the integrator, where the step is bound by the
/// latency of that chain, not by throughput): (a) the coefficient recursion alone (the next state
/// y + 0·c_P), (b) recursion and the new state at a fixed h (as the integrator: Estrin's scheme, or
/// y + Σ_{n≥1} c_n hⁿ below taylor_detail::compensate_below), (c) recursion, step size
/// and new state. Parts: recursion = (a), new state = (b) − (a), step size = (c) − (b), the rest
/// of the integrator's loop (bookkeeping, checks, outputs) = the whole step − (c), the whole step
/// being a trajectory's time / steps. Above rtol 1e-12 a single run takes a predicted step where
/// the allowed one is at least as large (taylor.hpp: OneTaylorRun::step_size), so the step size
/// is mostly off its chain and the whole step can be shorter than (c): the rest then reads
/// negative, the part of the step size's time that the prediction hides.
template <int P>
void taylor_profile_row(const model::Gyrostat<false>& system, double safety, double rtol, double step_ns, long steps) {
    constexpr int chain = 2000;
    auto per_step = [&](auto&& advance) {
        Vec3 y = free_w0;
        const double s = seconds_of([&] {
            y = free_w0;
            for (int i = 0; i < chain; ++i) y = advance(y);
        });
        if (!std::isfinite(y[0])) std::printf("# (non-finite chain)\n");
        return 1e9 * s / chain;
    };
    const double h_fixed = 0.8;
    // the integrator's new state (taylor.hpp): y + Σ_{n≥1} c_n hⁿ when compensated (its two-sum is
    // beside the chain), else Estrin's scheme over the whole polynomial
    auto new_state = [&](const Vec3* c, double h) -> Vec3 {
        if (rtol < integrate::taylor_detail::compensate_below) return c[0] + integrate::taylor_detail::increment<P>(c, h);
        return integrate::taylor_detail::evaluate_polynomial<P>(c, h);
    };
    const double recursion = per_step([&](const Vec3& y) {
        Vec3 c[P + 1];
        system.taylor_coefficients<P>(0.0, y, c);
        return Vec3(y + 0.0 * c[P]);
    });
    const double with_state = per_step([&](const Vec3& y) {
        Vec3 c[P + 1];
        system.taylor_coefficients<P>(0.0, y, c);
        return new_state(c, h_fixed);
    });
    const double with_step_size = per_step([&](const Vec3& y) {
        Vec3 c[P + 1];
        system.taylor_coefficients<P>(0.0, y, c);
        const double h = integrate::taylor_detail::step_size(y.cwiseAbs().maxCoeff(), c[P - 1].cwiseAbs().maxCoeff(),
                                                            c[P].cwiseAbs().maxCoeff(), P, safety);
        return new_state(c, h);
    });
    std::printf("# taylor_profile rtol=%.0e order=%d steps=%ld step_ns=%.1f recursion_ns=%.1f new_state_ns=%.1f "
                "step_size_ns=%.1f rest_ns=%.1f\n",
                rtol, P, steps, step_ns, recursion, with_state - recursion, with_step_size - with_state,
                step_ns - with_step_size);
}

/// ns per call of `rhs`: `chained` feeds each call's rate back into the next state (a Runge–Kutta
/// stage waits on its predecessor: the latency), otherwise the calls are independent (the throughput).
template <class System>
double rhs_ns(const System& system, typename System::State y, bool chained) {
    typename System::State dy = System::State::Zero();
    const double g0 = y[0];
    volatile double sink = 0.0;
    const int calls = 1'000'000;
    const double s = seconds_of([&] {
        for (int i = 0; i < calls; ++i) {
            y[0] = g0 * (1.0 + 1e-9 * (i & 7)) + (chained ? 1e-300 * dy[0] : 0.0);
            system.rhs(0.0, y, dy);
        }
        sink = sink + dy[0];
    });
    return 1e9 * s / calls;
}

/// The averaged models' right-hand sides under the damping M = −ε diag(1, 2, 3) ω, ε = 1e-4:
/// the triaxial A = (3, 2, 1) at k² = 0.3 (model/averaged_triaxial.hpp: the free motion's K and
/// ⟨sn²⟩ at every call) and the symmetric (3, 3, 1) at the same |ω| (model/averaged.hpp), and one
/// triaxial run over t = 1/ε at rtol 1e-10 (bench/triaxial_averaging.py's cost row, without Python).
void averaged_rhs() {
    const double eps = 1e-4;
    const TorqueSet damping({torque::LinearDamping(Mat3(eps * Vec3(1.0, 2.0, 3.0).asDiagonal()))});
    const model::AveragedTriaxial triaxial(Body(Vec3(3.0, 2.0, 1.0)), damping);
    Eigen::VectorXd omega(3);
    omega << 0.7161148740394329, 0.0, 0.6793662204867575;  // k² = 0.3 about the major axis (triaxial_averaging.py's start)
    const model::AveragedTriaxial::State y = triaxial.initial_state(omega);
    const model::AveragedSymmetric symmetric(Body(Vec3(3.0, 3.0, 1.0)), damping);
    const model::AveragedSymmetric::State ys = symmetric.initial_state(omega);
    std::printf("# averaged_rhs model,latency_ns,throughput_ns (k^2 = %.3f)\n", triaxial.motion(y).m());
    std::printf("averaged_rhs,triaxial,%.1f,%.1f\n", rhs_ns(triaxial, y, true), rhs_ns(triaxial, y, false));
    std::printf("averaged_rhs,symmetric,%.1f,%.1f\n", rhs_ns(symmetric, ys, true), rhs_ns(symmetric, ys, false));
    integrate::Options o;
    o.n_out = 0;
    o.rtol = 1e-10;
    o.atol = 1e-12;
    integrate::Result result;
    const double s = seconds_of([&] { result = solve_system(triaxial, 0.0, omega, 1.0 / eps, o, nullptr); });
    std::printf("# averaged_solve model,microseconds,steps,rhs_evals\naveraged_solve,triaxial,%.2f,%ld,%ld\n", 1e6 * s,
                static_cast<long>(result.stats.steps), static_cast<long>(result.stats.rhs_evals));
}

template <int... Orders>
void taylor_profile(std::integer_sequence<int, Orders...>) {
    const model::Gyrostat<false> system(free_body, TorqueSet{});
    integrate::Options o;
    o.n_out = 0;
    o.method = Method::Taylor;
    o.max_steps = 100'000'000;
    for (double rtol : {1e-6, 1e-8, 1e-10, 1e-12, 1e-14}) {
        o.rtol = rtol;
        o.atol = rtol * 1e-3;
        integrate::Result result;
        const double s = seconds_of([&] { result = integrate::solve(system, 0.0, free_w0, free_t1, o); });
        const int order = integrate::taylor_detail::single_run_order(rtol, model::Gyrostat<false>::max_taylor_order);
        const double safety = integrate::taylor_detail::safety_for(rtol, order);
        const double step_ns = 1e9 * s / result.stats.steps;
        ((Orders == order ? taylor_profile_row<(Orders < 2 ? 2 : Orders)>(system, safety, rtol, step_ns, result.stats.steps)
                          : void()),
         ...);
    }
}

}  // namespace

constexpr const char* usage =
    "usage: gyrostat_bench [--quick | --taylor [RTOLS] | --taylor-profile | --averaged-rhs] [--help]\n"
    "\n"
    "Times every integrator on the standard problems (torque_free, forced, stiff, moving_mass)\n"
    "across tolerances and prints one CSV row per run to stdout:\n"
    "  problem,method,rtol,error,steps,rhs_evals,seconds\n"
    "error is the max-norm error of the final state against the problem's reference; seconds is\n"
    "the best of several repetitions of one whole trajectory. Lines starting with '#' are comments\n"
    "(failed runs, ensemble timings). bench/work_precision.py runs it and draws the charts.\n"
    "\n"
    "options:\n"
    "  --quick   two tolerances only (1e-6, 1e-10): a smoke run\n"
    "  --taylor [RTOLS]  only the Taylor integrator on the torque-free body I = (2, 3, 4),\n"
    "            omega0 = (0.4, 0.9, -0.3), t = 0 -> 2000 (problem free_2000; bench/taylor_vs_heyoka.py),\n"
    "            at the comma-separated RTOLS (default 1e-6,...,1e-14); atol = rtol * 1e-3\n"
    "  --taylor-profile  the parts of one Taylor step on free_2000 (recursion, step size, Horner,\n"
    "            the rest: loop, checks, outputs) in ns, as '# taylor_profile' lines\n"
    "  --averaged-rhs  ns per right-hand side of the averaged triaxial and symmetric models (latency:\n"
    "            each call waiting on the last; throughput: independent calls) and one triaxial run\n"
    "            over t = 1/eps (eps = 1e-4, rtol 1e-10) in microseconds\n"
    "  --help    print this help and exit\n";

int main(int argc, char** argv) {
    bool quick = false;
    for (int i = 1; i < argc; ++i) {
        if (std::strcmp(argv[i], "--help") == 0 || std::strcmp(argv[i], "-h") == 0) {
            std::fputs(usage, stdout);
            return 0;
        }
        if (std::strcmp(argv[i], "--quick") == 0) {
            quick = true;
        } else if (std::strcmp(argv[i], "--taylor") == 0) {
            std::vector<double> tolerances;
            if (i + 1 < argc && argv[i + 1][0] != '-')
                for (char* p = argv[i + 1]; *p != '\0'; p += (*p == ',')) tolerances.push_back(std::strtod(p, &p));
            else
                tolerances = {1e-6, 1e-7, 1e-8, 1e-9, 1e-10, 1e-11, 1e-12, 1e-13, 1e-14};
            taylor_rows(tolerances);
            return 0;
        } else if (std::strcmp(argv[i], "--taylor-profile") == 0) {
            taylor_profile(std::make_integer_sequence<int, model::Gyrostat<false>::max_taylor_order + 1>{});
            return 0;
        } else if (std::strcmp(argv[i], "--averaged-rhs") == 0) {
            averaged_rhs();
            return 0;
        } else {
            std::fprintf(stderr, "gyrostat_bench: unknown option '%s'\n%s", argv[i], usage);
            return 2;
        }
    }
    const std::vector<double> tolerances =
        quick ? std::vector<double>{1e-6, 1e-10} : std::vector<double>{1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10, 1e-11, 1e-12, 1e-13};
    const std::vector<Method> all = {Method::Taylor, Method::Dop853, Method::CvodeAdams, Method::CvodeBdf, Method::ArkodeFehlberg8,
                                     Method::ArkodeVerner6};
    std::printf("problem,method,rtol,error,steps,rhs_evals,seconds\n");

    // 1. Torque-free triaxial body over 100 periods of ω; reference: the closed form.
    {
        const Body body(Vec3(1.0, 2.0, 3.0));
        const Vec3 w0(1.0, 0.5, -0.3);
        const model::TorqueFreeSolution exact(body, w0);
        const double t1 = 100.0 * exact.period();
        std::printf("# torque_free: A = (1, 2, 3), omega0 = (1, 0.5, -0.3), t1 = %.17g (100 periods), reference = closed form\n", t1);
        std::printf("# reference_state torque_free %.17g %.17g %.17g\n", exact.omega(t1)[0], exact.omega(t1)[1], exact.omega(t1)[2]);
        sweep("torque_free", model::Gyrostat<false>(body, TorqueSet{}), w0, t1, exact.omega(t1), all, tolerances);
    }

    // 2. Forced, damped gyrostat with attitude over t = 200; reference: DOP853 at rtol 1e-14
    //    (agrees with Fehlberg 8 at 1e-14 to the printed difference).
    {
        const Body body(Vec3(1.0, 2.0, 2.5), Vec3(0.1, -0.2, 0.3));
        Mat3 d;
        d << 0.05, 0.01, 0.0, 0.0, 0.04, 0.005, 0.0, 0.0, 0.03;
        const model::Gyrostat<true> system(body, TorqueSet({torque::Constant(Vec3(0.02, -0.01, 0.05)), torque::LinearDamping(d)}));
        model::Gyrostat<true>::State y0;
        y0 << 1.0, 0.5, -0.3, 1.0, 0.0, 0.0, 0.0;
        integrate::Options tight;
        tight.n_out = 0;  // t0 and t1 only (the engine's default is 1001 outputs)
        tight.rtol = 1e-14;
        tight.atol = 1e-16;
        const auto ref = integrate::solve(system, 0.0, y0, 200.0, tight);
        tight.method = Method::ArkodeFehlberg8;
        const auto check = integrate::solve(system, 0.0, y0, 200.0, tight);
        model::Gyrostat<true>::State reference = Eigen::Map<const model::Gyrostat<true>::State>(&ref.y[7]);
        double spread = 0.0;
        for (int i = 0; i < 7; ++i) spread = std::max(spread, std::abs(ref.y[7 + i] - check.y[7 + i]));
        std::printf("# forced: A = (1, 2, 2.5), k = (0.1, -0.2, 0.3), constant + damping, attitude, t1 = 200; reference spread %.2e\n", spread);
        std::printf("# reference_state forced");
        for (int i = 0; i < 7; ++i) std::printf(" %.17g", reference[i]);
        std::printf("\n");
        sweep("forced", system, y0, 200.0, reference, all, tolerances);
    }

    // 3. Stiff: the same body with damping 1e3·I over t = 10 (decay time 1e-3): BDF against the rest.
    {
        const Body body(Vec3(1.0, 2.0, 3.0));
        const model::Gyrostat<false> system(body, TorqueSet({torque::LinearDamping(1e3 * Mat3::Identity()),
                                                            torque::Constant(Vec3(1.0, 2.0, 3.0))}));
        const Vec3 w0(1.0, 0.5, -0.3);
        integrate::Options tight;
        tight.n_out = 0;  // t0 and t1 only (the engine's default is 1001 outputs)
        tight.method = Method::CvodeBdf;
        tight.rtol = 1e-13;
        tight.atol = 1e-16;
        const auto ref = integrate::solve(system, 0.0, w0, 10.0, tight);
        const Vec3 reference(ref.y[3], ref.y[4], ref.y[5]);
        std::printf("# stiff: A = (1, 2, 3), D = 1e3 I, M = (1, 2, 3), t1 = 10; reference = cvode_bdf at 1e-13\n");
        sweep("stiff", system, w0, 10.0, reference, {Method::CvodeBdf, Method::Dop853, Method::ArkodeFehlberg8},
              quick ? std::vector<double>{1e-6} : std::vector<double>{1e-4, 1e-6, 1e-8, 1e-10});
    }

    // 4. The library's standard stiff case: the explicit moving-mass model (paper 001) with a
    //    strong damper (Ω² = 2000, λ = 400) over t = 20; reference: CVODE BDF at rtol 1e-12.
    {
        const model::MovingMass system(Body(Vec3(1.0, 1.0, 1.6)), 0.18, 1.0, std::sqrt(2000.0), 400.0, TorqueSet{});
        const auto y0 = system.quasi_static_state(Vec3(0.8, 0.0, 1.0));
        integrate::Options tight;
        tight.n_out = 0;  // t0 and t1 only (the engine's default is 1001 outputs)
        tight.method = Method::CvodeBdf;
        tight.rtol = 1e-12;
        tight.atol = 1e-15;
        const auto ref = integrate::solve(system, 0.0, y0, 20.0, tight);
        const model::MovingMass::State reference = Eigen::Map<const model::MovingMass::State>(&ref.y[9]);
        std::printf("# moving_mass: explicit model, A = (1, 1, 1.6), mu rho^2 = 0.18, Omega^2 = 2000, lambda = 400, t1 = 20\n");
        sweep("moving_mass", system, y0, 20.0, reference, {Method::CvodeBdf, Method::Dop853},
              quick ? std::vector<double>{1e-6} : std::vector<double>{1e-4, 1e-6, 1e-8});
    }

    // 5. Averaged against full over long horizons: oblate body (1, 1, 1.8) with a cavity of
    //    strength κ = 0.4 ε and a damping ε·diag(1, 1, 0.5), t1 = 3/ε, both with DOP853 at rtol 1e-10;
    //    the cost of the full model grows like 1/ε (it follows every fast rotation), the
    //    averaged one's does not.
    {
        const Body body(Vec3(1.0, 1.0, 1.8));
        for (double eps : quick ? std::vector<double>{1e-2} : std::vector<double>{1e-2, 1e-3, 1e-4}) {
            const TorqueSet set({torque::ViscousCavity(1.0, 1.0 / eps, 0.4), torque::LinearDamping(eps * Vec3(1.0, 1.0, 0.5).asDiagonal().toDenseMatrix())});
            const model::Gyrostat<false> full(body, set);
            const model::AveragedSymmetric averaged(body, set);
            integrate::Options o;
            o.n_out = 0;  // t0 and t1 only (the engine's default is 1001 outputs)
            o.rtol = 1e-10;
            o.atol = 1e-12;
            o.max_steps = 100'000'000;
            const double t1 = 3.0 / eps;
            integrate::Result rf, ra;
            const double sf = seconds_of([&] { rf = integrate::solve(full, 0.0, Vec3(1.0, 0.0, 1.0), t1, o); });
            const double sa = seconds_of([&] { ra = integrate::solve(averaged, 0.0, Eigen::Vector2d(1.0, 1.0), t1, o); });
            const double a_full = std::hypot(rf.y[3], rf.y[4]);
            std::printf("# averaged eps=%.0e t1=%.0f full: %ld steps %.4e s; averaged: %ld steps %.4e s; ratio %.0f; "
                        "|a_full - a_avg|(t1) = %.2e, |r_full - r_avg|(t1) = %.2e\n",
                        eps, t1, rf.stats.steps, sf, ra.stats.steps, sa, sf / sa, std::abs(a_full - ra.y[2]),
                        std::abs(rf.y[5] - ra.y[3]));
        }
    }

    // 6. Ensemble scaling: 512 torque-free trajectories (50 periods each, dop853, rtol 1e-10) on 1 and 2 threads.
    {
        const Body body(Vec3(1.0, 2.0, 3.0));
        const std::vector<model::Gyrostat<false>> systems{model::Gyrostat<false>(body, TorqueSet{})};
        std::vector<Vec3> starts;
        for (int i = 0; i < (quick ? 64 : 512); ++i) starts.emplace_back(1.0 + 0.001 * i, 0.5, -0.3);
        integrate::Options o;
        o.n_out = 0;  // t0 and t1 only (the engine's default is 1001 outputs)
        o.rtol = 1e-10;
        o.atol = 1e-13;
        double base = 0.0;
        for (int threads : {1, 2}) {
            const double s = seconds_of([&] { solve_ensemble(systems, starts, 0.0, 500.0, o, threads); }, 1.0);
            if (threads == 1) base = s;
            std::printf("# ensemble n=%zu threads=%d seconds=%.4e speedup=%.2f\n", starts.size(), threads, s, base / s);
        }
    }
    return 0;
}
