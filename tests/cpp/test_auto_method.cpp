// C++ tests of method 'auto' (integrate/auto_switch.hpp): DOP853 while the problem is not stiff,
// CVODE BDF while it is, the segments chained into one Result.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "gyrostat/engine.hpp"
#include "gyrostat/ensemble.hpp"
#include "gyrostat/solve_system.hpp"
#include "gyrostat/model/gyrostat.hpp"
#include "gyrostat/model/moving_mass.hpp"

#include "check.hpp"
#include "families.hpp"

using namespace gyrostat;
using integrate::Method;
using integrate::Options;
using integrate::Result;


static Options with(Method m, double rtol, double atol) {
    Options o;
    o.method = m;
    o.rtol = rtol;
    o.atol = atol;
    return o;
}

/// The largest |a − b| over the rows both results recorded (same output grid).
static double max_difference(const Result& a, const Result& b) {
    double err = 0.0;
    for (std::size_t i = 0; i < std::min(a.y.size(), b.y.size()); ++i) err = std::max(err, std::abs(a.y[i] - b.y[i]));
    return err;
}

static int count_to(const Result& r, const char* method) {
    return static_cast<int>(std::count_if(r.switches.begin(), r.switches.end(), [&](const auto& s) { return s.to == method; }));
}

/// The gyrostat whose stiffness changes along the run: a resistive medium D(t) = c t (T − t) I
/// (zero at both ends, c T²/4 at T/2) under a constant torque M that keeps ω away from zero
/// (ω ≈ D⁻¹ M where D is large). The Jacobian's dominant eigenvalue ≈ −D(t)/A1: DOP853's step
/// meets its stability limit h|λ| ≈ 6.1 in the middle of the span and not near its ends.
static model::Gyrostat<false> changing_stiffness(double c, double T) {
    const Body body(Vec3(1.0, 2.0, 3.0));
    const Mat3 I = Mat3::Identity();
    return model::Gyrostat<false>(
        body, TorqueSet({torque::Constant(Vec3(0.5, -0.3, 1.0)), torque::ResistiveMedium({0.0 * I, c * T * I, -c * I})}));
}

int main(int argc, char**) {
    const bool verbose = argc > 1;

    // 1. Explorer-1-like prolate body with the explicit moving-mass damper (issue 15's case):
    // moments (10, 10, 2), m = 0.1, ρ = 1, Ω = 5, λ = 1, ω0 = (0.05, 0, 2) on the quasi-static
    // motion, t = 2e4 (2e3 under the sanitizers), rtol 1e-8. Its eigenvalues (≈ −0.5 ± 5i and the
    // rotation) keep DOP853's steps accuracy-limited (h·|λ| ≈ 1.5): auto must stay on DOP853 (at
    // most one short visit to BDF) and take at most 1.5× DOP853's steps.
    {
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
        const double t_explorer = 2e3;  // at -O0 under the sanitizers: 6 900 steps a run, the same paths and checks
#else
        const double t_explorer = 2e4;  // 69 103 steps a run (~90 % of this test under ASan: 20 of 24 s)
#endif
        const model::MovingMass explorer(Body(Vec3(10.0, 10.0, 2.0)), 0.1, 1.0, 5.0, 1.0, TorqueSet{});
        const auto y0 = explorer.quasi_static_state(Vec3(0.05, 0.0, 2.0));
        const Result dop = integrate::solve(explorer, 0.0, y0, t_explorer, with(Method::Dop853, 1e-8, 1e-10));
        const Result aut = integrate::solve(explorer, 0.0, y0, t_explorer, with(Method::Auto, 1e-8, 1e-10));
        if (verbose)
            std::printf("explorer: dop853 %ld steps, auto %ld steps, %zu switches\n", dop.stats.steps, aut.stats.steps,
                        aut.switches.size());
        CHECK(aut.success() && aut.method == "auto", "explorer: auto succeeds");
        CHECK(aut.switches.size() <= 2, "explorer: auto stays on DOP853 (or leaves BDF at once)");
        CHECK(aut.stats.steps <= 1.5 * dop.stats.steps, "explorer: auto within 1.5x DOP853's steps");
        if (aut.switches.empty())
            CHECK(aut.y == dop.y && aut.stats.steps == dop.stats.steps && aut.methods_used == std::vector<std::string>{"dop853"},
                  "explorer: without a switch auto is DOP853 step for step");
    }

    // 2. The stiff moving mass (paper 001, bench/stiff_radau.py): moments (4, 4, 2), m = 1,
    // ρ = 1, Ω = 100, λ = 2e4 (eigenvalue ≈ −2e4), t = 0..20. Auto must hand over to BDF within
    // the first 1% of the span and agree with cvode_bdf: both at rtol 1e-8 against a cvode_bdf
    // run at rtol 1e-12; bound 5e-6 = 500 rtol (the global errors measured here: cvode_bdf
    // 8.5e-7, auto 4.3e-7; BDF's error grows with the span's 20 / 0.5 = 40 slow time constants).
    {
        const model::MovingMass stiff(Body(Vec3(4.0, 4.0, 2.0)), 1.0, 1.0, 100.0, 2e4, TorqueSet{});
        const auto y0 = stiff.quasi_static_state(Vec3(1.0, 0.0, 1.0));
        Options tight = with(Method::CvodeBdf, 1e-12, 1e-14);
        tight.n_out = 201;
        Options o = with(Method::Auto, 1e-8, 1e-10);
        o.n_out = 201;
        const Result reference = integrate::solve(stiff, 0.0, y0, 20.0, tight);
        const Result aut = integrate::solve(stiff, 0.0, y0, 20.0, o);
        o.method = Method::CvodeBdf;
        const Result bdf = integrate::solve(stiff, 0.0, y0, 20.0, o);
        if (verbose)
            std::printf("stiff: auto %ld steps, first switch at %g (%s), error %.3g; bdf %ld steps error %.3g\n",
                        aut.stats.steps, aut.switches.empty() ? -1.0 : aut.switches[0].t,
                        aut.switches.empty() ? "" : aut.switches[0].reason.c_str(), max_difference(aut, reference),
                        bdf.stats.steps, max_difference(bdf, reference));
        CHECK(aut.success() && !aut.switches.empty() && aut.switches[0].to == "cvode_bdf" && aut.switches[0].t < 0.2,
              "stiff moving mass: auto switches to BDF early");
        CHECK(aut.switches.size() == 1, "stiff moving mass: and stays there");
        CHECK(aut.switches[0].reason.find("h·|λ|") != std::string::npos, "the reason gives h·|λ|");
        CHECK(max_difference(aut, reference) < 5e-6 && max_difference(bdf, reference) < 5e-6,
              "stiff moving mass: auto agrees with cvode_bdf to the tolerance");
        CHECK(aut.t == reference.t, "stiff moving mass: every output once, in order");
        CHECK((aut.methods_used == std::vector<std::string>{"dop853", "cvode_bdf"}), "methods used");
    }

    // 3. Stiffness that changes along the run: DOP853 → BDF → DOP853, against a tight DOP853
    // reference (rtol 1e-12: stability-limited in the middle, but accurate). Bound 1e-7 = 10 rtol:
    // the error measured is 6e-9 (on the stiff part ω ≈ D⁻¹M is slaved to D(t): BDF's error
    // decays there instead of accumulating).
    const double c = 40.0, T = 10.0;
    const auto gyro = changing_stiffness(c, T);
    const Vec3 w0(1.0, 0.5, -0.3);
    Options tight = with(Method::Dop853, 1e-12, 1e-14);
    tight.n_out = 401;
    const Result reference = integrate::solve(gyro, 0.0, w0, T, tight);
    {
        Options o = with(Method::Auto, 1e-8, 1e-10);
        o.n_out = 401;
        const Result aut = integrate::solve(gyro, 0.0, w0, T, o);
        if (verbose) {
            std::printf("changing: auto %ld steps, %ld f evals, error %.3g\n", aut.stats.steps, aut.stats.rhs_evals,
                        max_difference(aut, reference));
            for (const auto& s : aut.switches) std::printf("  t = %g -> %s: %s\n", s.t, s.to.c_str(), s.reason.c_str());
        }
        CHECK(aut.success(), "changing stiffness: auto succeeds");
        CHECK(aut.switches.size() >= 2 && aut.switches[0].to == "cvode_bdf" && aut.switches[1].to == "dop853",
              "changing stiffness: DOP853 → BDF → DOP853");
        CHECK(aut.switches.size() >= 2 && aut.switches[0].t > 0.1 && aut.switches[0].t < 0.5 * T &&
                  aut.switches[1].t > 0.5 * T && aut.switches[1].t < T,
              "changing stiffness: the switches sit on either side of the peak");
        CHECK(max_difference(aut, reference) < 1e-7, "changing stiffness: auto matches the tight reference");
        CHECK(aut.t == reference.t, "changing stiffness: every output once, in order");
        CHECK(aut.stats.jacobian_evals > 0 && aut.stats.steps > 0, "statistics summed over the segments");
    }

    // 4. Events and outputs across the switches. An event g = t − t_s at each switch time t_s
    // (found by a first run; events do not change the steps) and one on ω3 crossing a value:
    // each crossing recorded once, where the reference has it. A terminal event whose n-th
    // crossing comes after a switch stops the run there (the counts carry over). Dense output
    // covers the whole span.
    {
        Options o = with(Method::Auto, 1e-8, 1e-10);
        o.n_out = 401;
        const Result plain = integrate::solve(gyro, 0.0, w0, T, o);
        std::vector<double> switch_times;
        for (const auto& s : plain.switches) switch_times.push_back(s.t);
        for (double ts : switch_times) {
            integrate::Event at;
            at.quantity = integrate::Event::Quantity::Function;
            at.function = [ts](double t, const double*, int) { return t - ts; };
            at.name = "at_switch";
            o.events.push_back(at);
        }
        integrate::Event r_crossing;
        r_crossing.index = 2;
        r_crossing.value = 0.0;  // ω3 (r) changes sign where the torque wins over the medium and back
        r_crossing.name = "r";
        o.events.push_back(r_crossing);
        o.dense_output = true;
        Options te = tight;
        te.events = {r_crossing};
        const Result ref = integrate::solve(gyro, 0.0, w0, T, te);
        const Result aut = integrate::solve(gyro, 0.0, w0, T, o);
        bool once = aut.switches.size() == switch_times.size() && aut.y == plain.y;
        for (std::size_t i = 0; i < switch_times.size() && once; ++i)
            once = aut.t_events[i].size() == 1 && std::abs(aut.t_events[i][0] - switch_times[i]) < 1e-12 * T;
        CHECK(once, "an event at a switch is located once, at the switch");
        const auto& crossings = aut.t_events.back();
        bool same = crossings.size() == ref.t_events[0].size();
        for (std::size_t i = 0; i < crossings.size() && same; ++i) same = std::abs(crossings[i] - ref.t_events[0][i]) < 1e-6;
        if (verbose) std::printf("r crossings: auto %zu, reference %zu\n", crossings.size(), ref.t_events[0].size());
        CHECK(same, "events across the switches: the reference's crossings, each once");
        // the reference's 401 times fall between the steps of every segment; bound 1e-7 = 10
        // rtol, as for the outputs (measured 6e-9: the interpolants are as good as the steps)
        double dense_error = aut.dense && !aut.dense->empty() ? 0.0 : 1.0;
        for (std::size_t i = 0; i < reference.t.size() && dense_error < 1.0; ++i) {
            const Eigen::VectorXd y = (*aut.dense)(reference.t[i]);
            for (int k = 0; k < 3; ++k) dense_error = std::max(dense_error, std::abs(y[k] - reference.y[3 * i + k]));
        }
        if (verbose) std::printf("dense error %.3g\n", dense_error);
        CHECK(dense_error < 1e-7, "dense output across the segments matches the reference");

        // terminal: g = sin(πt) crosses zero at every integer; stop at the n-th, after the first switch
        if (!switch_times.empty()) {
            const int n = static_cast<int>(std::ceil(switch_times[0])) + 1;
            integrate::Event integer;
            integer.quantity = integrate::Event::Quantity::Function;
            integer.function = [](double t, const double*, int) { return std::sin(M_PI * t); };
            integer.terminal = n;
            integer.name = "integer";
            Options ot = with(Method::Auto, 1e-8, 1e-10);
            ot.events = {integer};
            const Result stopped = integrate::solve(gyro, 0.0, w0, T, ot);
            CHECK(stopped.success() && stopped.terminal_event == 0 && stopped.t_events[0].size() == static_cast<std::size_t>(n) &&
                      std::abs(stopped.t_last - n) < 1e-9 && !stopped.switches.empty(),
                  "a terminal event's n-th crossing counted across a switch");
        }
    }

    // 5. max_steps over the whole run, the failing segment named; Control interrupts any segment.
    {
        Options o = with(Method::Auto, 1e-8, 1e-10);
        const Result full = integrate::solve(gyro, 0.0, w0, T, o);
        o.max_steps = full.stats.steps - 5;
        const Result cut = integrate::solve(gyro, 0.0, w0, T, o);
        if (verbose) std::printf("cut: %s\n", cut.message.c_str());
        CHECK(cut.status == integrate::Status::MaxStepsReached && cut.stats.steps == o.max_steps,
              "max_steps counts the steps of every segment");
        CHECK(cut.message.rfind("method 'auto', dop853 segment", 0) == 0, "the failure names the segment's method");
        integrate::Control control;
        control.interval = 0.0;
        control.poll = [](double fraction) { return fraction < 0.6; };
        const Result stopped = integrate::solve(gyro, 0.0, w0, T, with(Method::Auto, 1e-8, 1e-10), &control);
        CHECK(stopped.status == integrate::Status::Interrupted && stopped.t_last >= 0.6 * T && stopped.t_last < T,
              "Control interrupts an auto run");
    }

    // 6. Ensemble: each member its own switches, each equal to its single run; every family runs.
    {
        const model::MovingMass stiff(Body(Vec3(4.0, 4.0, 2.0)), 1.0, 1.0, 100.0, 2e4, TorqueSet{});
        const model::MovingMass soft(Body(Vec3(4.0, 4.0, 2.0)), 1.0, 1.0, 10.0, 1.0, TorqueSet{});
        const std::vector<AnyModel> models{stiff, soft, gyro};
        std::vector<Eigen::VectorXd> starts{stiff.quasi_static_state(Vec3(1.0, 0.0, 1.0)),
                                            soft.quasi_static_state(Vec3(1.0, 0.0, 1.0)), Eigen::Vector3d(w0)};
        std::vector<const AnyModel*> pointers;
        for (const auto& m : models) pointers.push_back(&m);
        Options o = with(Method::Auto, 1e-8, 1e-10);
        o.n_out = 51;
        const auto ensemble = solve_ensemble(pointers, starts, 0.0, T, o, 2);
        bool same = ensemble.size() == 3;
        for (std::size_t i = 0; i < 3 && same; ++i) {
            const Result single = solve(models[i], 0.0, starts[i], T, o);
            same = single.y == ensemble[i].y && single.switches.size() == ensemble[i].switches.size();
        }
        CHECK(same, "ensemble members equal their single runs");
        CHECK(count_to(ensemble[0], "cvode_bdf") == 1 && ensemble[1].switches.empty() && count_to(ensemble[2], "dop853") >= 1,
              "each member its own switches");
    }

    // 7. Every family accepts method 'auto' (the closed form stays closed form); on these
    // non-stiff cases it is DOP853 step for step.
    {
        const auto [models, starts] = every_family();
        Options o = with(Method::Auto, 1e-9, 1e-12);
        o.n_out = 21;
        Options d = o;
        d.method = Method::Dop853;
        bool all = true;
        for (std::size_t i = 0; i < models.size(); ++i) {
            const Result a = solve(models[i], 0.0, starts[i], 5.0, o), b = solve(models[i], 0.0, starts[i], 5.0, d);
            const bool closed = i + 1 == models.size();
            const bool ok = a.success() && a.y == b.y && a.switches.empty() &&
                            a.method == (closed ? "closed_form" : "auto") && a.methods_used.size() == 1;
            if (!ok) std::printf("family %zu: %s %s\n", i, a.method.c_str(), a.message.c_str());
            all = all && ok;
        }
        CHECK(all, "every family runs with method auto");
    }

    std::printf("%d passed, %d failed\n", passes, failures);
    return failures == 0 ? 0 : 1;
}
