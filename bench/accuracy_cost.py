"""The accuracy contract against brute force (issue 41, item 5).

Run:  .venv/bin/python bench/accuracy_cost.py [--quick] [--rounds N] [--out bench/results]
      (~15 s; --quick: ~5 s. Times the installed package: reinstall after changes.)

For each scene (six, across the families) and each accuracy A asked (1e-3 … 1e-9):

* **brute force**: plain runs (``error_estimate=False``) over a grid of rtol (1e-3 … 1e-13, quarter
  decades; atol = rtol · 1e-3 · max|y0|, the accuracy path's own rule), each one's true error
  measured against a reference (DOP853 at rtol 1e-14) at the same 201 output times, on the
  quantities :func:`gyrostat.accuracy.quantities` defines (ω and the quaternion as vectors, every
  other state component and |G|, T, ... as scalars, relative to their largest size; the largest
  over them). The cheapest run that meets A is the yardstick, in time and in right-hand-side
  evaluations;
* **the accuracy path**: ``gyrostat.solve(..., accuracy=A)`` (its probe, run, companion and any
  repeat included), its true error (delivered) and its reported ``error_estimate``;
* **explicit tolerances**: ``solve(..., rtol=R)`` with the default (window) estimate against the
  same with ``error_estimate=False``.

Goals (issue 41): accuracy-path cost ≤ 3× the cheapest meeting run; delivered error ≤ A;
estimate / true within [0.5, 30] (true above 1e-10; below it, estimate ≤ max(30 × true, 1e-10));
explicit rtol: cost with estimate ≤ 1.5× without.

Cost: time is the median of ``--rounds`` repeats, every timed job shuffled into one random order
per round (the machine is shared and noisy: all ratios come from one run, interleaved); a job is
called often enough in each round to take ~1 ms (timeit's practice: one call of a ~30 µs solve,
timed alone after another scene's, measured its cold caches more than its own work) and its mean
per call taken;
right-hand-side evaluations (every engine run a solve makes, summed; deterministic) are counted in
a first, untimed pass. The reference's own error is bounded by its distance to the run at rtol
1e-13; a true error below 10× that bound is marked ``~`` (the reference cannot judge it).

Only one model per scene is searched (the scene's own: ``solve`` takes the model given; the
ladder's choice of rung is bench/ladder.py's subject) and one integrator (DOP853; the moving
mass: ``method="auto"``).

Writes: the printed tables (also to OUT/accuracy_cost.txt), OUT/accuracy_delivered.png (delivered
error and estimate against the accuracy asked, the diagonal drawn) and OUT/accuracy_cost.png
(cost of the accuracy path over the cheapest meeting run, against the accuracy asked).
"""

from __future__ import annotations

import argparse
import math
import random
import statistics
import sys
import time
import warnings
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

import gyrostat as g
from gyrostat import _core
from gyrostat import accuracy as acc
from gyrostat import contract
from gyrostat import lagrange as lg

RESULTS = Path(__file__).resolve().parent / "results"
N_OUT = 201
CALLS_FOR = 1e-3
"""Each timed job is called in a loop of about this many seconds per round (its mean per call taken)."""
REFERENCE_RTOL, CHECK_RTOL = 1e-14, 1e-13
RATIO_GOAL, EXPLICIT_GOAL, LOW, HIGH, FLOOR = 3.0, 1.5, 0.5, 30.0, 1e-10


@dataclass
class Scene:
    name: str
    label: str
    model: object
    y0: np.ndarray
    t1: float
    kw: dict = field(default_factory=dict)
    reference: object = None
    ref_bound: float = 0.0

    @property
    def size(self) -> float:
        return float(np.max(np.abs(self.y0)))

    def solve(self, **kw):
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            return g.solve(self.model, self.y0, (0.0, self.t1), n_out=N_OUT, progress=False, check_validity=False,
                           **self.kw, **kw)

    def plain(self, rtol: float):
        return self.solve(rtol=rtol, atol=rtol * contract.ATOL_RATIO * self.size, error_estimate=False)

    def true_error(self, sol) -> float:
        if not sol.success or len(sol.t) != N_OUT:
            return math.nan
        d = acc.differences(self.reference._result, sol._result, self.model._core)
        return max(float(v.max()) for v in d.values())


def scenes() -> list[Scene]:
    A, eps = [1.0, 1.4, 2.1], 1e-4
    D = [eps * x for x in (1.0, 2.5, 0.7)]
    w0 = np.array([0.15, 0.3, 1.0])
    q0 = np.array([0.9, 0.1, -0.3, 0.2]) / np.linalg.norm([0.9, 0.1, -0.3, 0.2])
    mm = g.MovingMassModel(g.Body([4.0, 4.0, 2.0]), mass=1.0, arm=1.0, frequency=10.0, damping=98.0)
    return [
        Scene("triaxial", "triaxial damped, ε = 1e-4, t = 1/ε (ω)",
              g.Model(g.Body(A), [g.LinearDamping(diagonal=D)]), w0, 1.0 / eps),
        Scene("attitude", "the same with attitude (ω, q)",
              g.Model(g.Body(A), [g.LinearDamping(diagonal=D)], attitude=True), np.r_[w0, q0], 1.0 / eps),
        Scene("cavity", "triaxial (1, 1.6, 2.1), viscous cavity κ = 1e-3, t = 5000",
              g.Model(g.Body([1.0, 1.6, 2.1]), [g.ViscousCavity(1.0, 1000.0, 1.0)]),
              np.array([1.0, 0.5, -0.3]), 5000.0),
        Scene("top", "Lagrange top, paper 003 case 2 (ε = 0.002, τ = 4, t = 2000)",
              lg.LagrangeTop(1.5, 1.0, 0.5, [lg.paper_torque(0.002)]),
              lg.initial_state([0.0, 0.0, math.sqrt(3.0)], math.radians(60.0)), 2000.0),
        Scene("moving_mass", "moving mass, paper 001 explicit (λ = 98, Ω = 10), t = 40, method auto",
              mm, mm.quasi_static_state([1.0, 0.0, 1.0]), 40.0, {"method": "auto"}),
        Scene("averaged", "averaged (a, r), paper 000 (cavity + axial torque), t = 60",
              g.AveragedModel(g.Body([8.0, 8.0, 4.0]), [g.ViscousCavity(1260, 1000, 0.48),
                                                        g.ConstantTorque([0.0, 0.0, -0.01])]),
              np.array([1.0, 1.0]), 60.0),
    ]


# ------------------------------------------------------------------------------------ counting work
class Counter:
    """Wraps the engine's solve to sum the right-hand-side evaluations and steps of every run."""

    def __init__(self):
        self.rhs = self.steps = self.runs = 0
        self._engine, self._window, self._both = _core.solve, _core.window_estimate, _core.solve_measured

    def _count(self, stats) -> None:
        self.rhs += stats.rhs_evals
        self.steps += stats.steps
        self.runs += 1

    def __enter__(self):
        def counted(*args, **kwargs):
            result = self._engine(*args, **kwargs)
            self._count(result.stats)
            return result

        def counted_window(*args, **kwargs):  # (one run's estimate in one engine call: its companion counted,
            made = self._window(*args, **kwargs)  # a whole span's Result or a window's statistics)
            if made is not None:
                self._count(getattr(made[6], "stats", made[6]))
            return made
        def counted_both(*args, **kwargs):  # (a run and its window estimate in one engine call: both counted)
            answer, made = self._both(*args, **kwargs)
            self._count(answer.stats)
            if made is not None:
                self._count(getattr(made[6], "stats", made[6]))
            return answer, made
        _core.solve, _core.window_estimate, _core.solve_measured = counted, counted_window, counted_both
        return self

    def __exit__(self, *exc):
        _core.solve, _core.window_estimate, _core.solve_measured = self._engine, self._window, self._both


def work(job) -> tuple[object, int, int, str]:
    """(solution or None, rhs evaluations, engine runs, error text) of one untimed job."""
    with Counter() as c:
        try:
            sol = job()
        except Exception as error:  # noqa: BLE001 (a failing path is a result: reported)
            return None, c.rhs, c.runs, f"{type(error).__name__}: {error}"
    return sol, c.rhs, c.runs, ""


def fmt(x: float, spec: str = ".2e") -> str:
    return "—" if x is None or not math.isfinite(x) else format(x, spec)


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="half decades, 3 accuracies, 2 rounds")
    parser.add_argument("--rounds", type=int, default=None, help="timed repeats (default 7; quick 2)")
    parser.add_argument("--out", type=Path, default=RESULTS)
    args = parser.parse_args()
    rounds = args.rounds or (2 if args.quick else 7)
    per_decade = 2 if args.quick else 4
    grid = [10.0 ** (-3 - k / per_decade) for k in range(10 * per_decade + 1)]  # 1e-3 … 1e-13
    accuracies = [1e-3, 1e-6, 1e-9] if args.quick else [1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9]
    explicit = [1e-6, 1e-8, 1e-10]
    lines: list[str] = []

    def say(text: str = "") -> None:
        print(text, flush=True)
        lines.append(text)

    started = time.perf_counter()
    all_scenes = scenes()
    say(f"gyrostat {getattr(g, '__version__', '?')}, {len(all_scenes)} scenes, {len(grid)} rtols, "
        f"accuracies {accuracies}, {rounds} timed rounds, {time.strftime('%Y-%m-%d %H:%M')}")
    # ---- references and the untimed pass (errors, estimates, work)
    jobs: dict[tuple, object] = {}
    info: dict[tuple, dict] = {}
    for s in all_scenes:
        s.reference = s.plain(REFERENCE_RTOL)
        assert s.reference.success, (s.name, s.reference.message)
        s.ref_bound = s.true_error(s.plain(CHECK_RTOL))
        for r in grid:
            jobs[(s.name, "plain", r)] = (lambda s=s, r=r: s.plain(r))
        for a in accuracies:
            jobs[(s.name, "accuracy", a)] = (lambda s=s, a=a: s.solve(accuracy=a))
        for r in explicit:
            atol = r * contract.ATOL_RATIO * s.size
            jobs[(s.name, "explicit_off", r)] = (lambda s=s, r=r, atol=atol: s.solve(rtol=r, atol=atol,
                                                                                     error_estimate=False))
            jobs[(s.name, "explicit_on", r)] = (lambda s=s, r=r, atol=atol: s.solve(rtol=r, atol=atol))
    for key, job in jobs.items():
        sol, rhs, runs, error = work(job)
        entry = {"rhs": rhs, "runs": runs, "error": error, "true": math.nan, "estimate": math.nan, "warnings": (),
                 "rtol": math.nan}
        if sol is not None:
            scene = next(s for s in all_scenes if s.name == key[0])
            entry.update(true=scene.true_error(sol), estimate=sol.error_estimate,
                         warnings=tuple(sol.accuracy_warnings), ok=sol.success,
                         rtol=float(sol._result.options.rtol) if hasattr(sol._result, "options") else math.nan)
        info[key] = entry
    # ---- timed rounds, interleaved in a random order each round; each job called CALLS_FOR seconds' worth
    times: dict[tuple, list[float]] = {key: [] for key in jobs}
    timed = [key for key in jobs if not info[key]["error"]]
    calls = {}
    for key in timed:  # (calibrated on a second, warm call)
        t = time.perf_counter()
        jobs[key]()
        calls[key] = max(1, min(200, int(CALLS_FOR / max(time.perf_counter() - t, 1e-9))))
    rng = random.Random(41)
    for _ in range(rounds):
        rng.shuffle(timed)
        for key in timed:
            job, n = jobs[key], calls[key]
            t = time.perf_counter()
            for _ in range(n):
                job()
            times[key].append((time.perf_counter() - t) / n)
    for key in jobs:
        info[key]["time"] = statistics.median(times[key]) if times[key] else math.nan

    # ---- the accuracy table
    say()
    say("Accuracy path against the cheapest plain run meeting the accuracy (brute force over rtol)")
    say()
    say("| scene | A | cheapest meeting: rtol, time [s] | accuracy path: time [s] (runs) | time ratio (≤ 3) | "
        "rhs ratio | delivered (≤ A) | estimate | estimate / true ([0.5, 30]) | goals |")
    say("| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |")
    rows, failures, notes = [], [], []
    for s in all_scenes:
        for a in accuracies:
            path = info[(s.name, "accuracy", a)]
            meeting = [r for r in grid if info[(s.name, "plain", r)]["true"] <= a]
            if meeting:
                cheapest = min(meeting, key=lambda r: info[(s.name, "plain", r)]["time"])
                fewest = min(info[(s.name, "plain", r)]["rhs"] for r in meeting)
                best = info[(s.name, "plain", cheapest)]["time"]
            else:
                cheapest, fewest, best = math.nan, math.nan, math.nan
            true, estimate = path["true"], path["estimate"]
            ratio = path["time"] / best if meeting and not path["error"] else math.nan
            rhs_ratio = path["rhs"] / fewest if meeting and not path["error"] else math.nan
            est_ratio = estimate / true if true > 0 else math.nan
            judged = true >= 10 * s.ref_bound
            problems = []
            if path["error"]:
                problems.append(f"raised {path['error']}")
            else:
                unattainable = not meeting and bool(path["warnings"])
                if meeting and not ratio <= RATIO_GOAL:
                    problems.append(f"cost {ratio:.2f}x > 3")
                if not true <= a and not unattainable:
                    problems.append(f"delivered {true:.2e} > {a:g}"
                                    + (f" (brute force meets it at rtol {cheapest:.2g})" if meeting else ""))
                if true > FLOOR and judged and not LOW <= est_ratio <= HIGH:
                    problems.append(f"estimate/true {est_ratio:.3g} outside [0.5, 30]")
                if true <= FLOOR and not estimate <= max(HIGH * true, FLOOR):
                    problems.append(f"estimate {estimate:.2e} > max(30 x true, 1e-10) near rounding")
                if path["warnings"] and not unattainable:
                    problems.append("warned: " + "; ".join(path["warnings"]))
                if unattainable:
                    notes.append(f"{s.name}, A = {a:g}: no rtol of the grid meets it (brute force's best "
                                 f"{min(info[(s.name, 'plain', r)]['true'] for r in grid):.2e}); the path delivered "
                                 f"{true:.2e} and warned (the contract's 'says so'): " + "; ".join(path["warnings"]))
            if problems:
                failures.append(f"{s.name}, A = {a:g}: " + "; ".join(problems))
            verdict = ("**" + ", ".join(p.split(":")[0].split(" (")[0] for p in problems) + "**" if problems
                       else "unattainable, warned" if not path["error"] and unattainable else "ok")
            rows.append(dict(scene=s.name, accuracy=a, ratio=ratio, rhs_ratio=rhs_ratio, true=true,
                             estimate=estimate, error=path["error"], warned=bool(path["warnings"])))
            say(f"| {s.name} | {a:g} | {fmt(cheapest, '.2g')}, {fmt(best, '.3g')} | "
                f"{fmt(path['time'], '.3g')} ({path['runs']}) | {fmt(ratio, '.2f')} | {fmt(rhs_ratio, '.2f')} | "
                f"{fmt(true)}{'' if judged else ' ~'} | {fmt(estimate)} | {fmt(est_ratio, '.3g')} | "
                f"{verdict} |")

    # ---- explicit tolerances
    say()
    say("Explicit rtol: the default (window) estimate's cost, and its quality")
    say()
    say("| scene | rtol | time, error_estimate=False [s] | time, default estimate [s] | time ratio (≤ 1.5) | "
        "rhs ratio | true error | estimate / true | goals |")
    say("| --- | --- | --- | --- | --- | --- | --- | --- | --- |")
    explicit_rows = []
    for s in all_scenes:
        for r in explicit:
            off, on = info[(s.name, "explicit_off", r)], info[(s.name, "explicit_on", r)]
            ratio = on["time"] / off["time"]
            rhs_ratio = on["rhs"] / off["rhs"] if off["rhs"] else math.nan
            est_ratio = on["estimate"] / on["true"] if on["true"] > 0 else math.nan
            explicit_rows.append(dict(scene=s.name, rtol=r, ratio=ratio, rhs_ratio=rhs_ratio))
            problems = []
            if on["error"]:
                problems.append(f"raised {on['error']}")
            if not ratio <= EXPLICIT_GOAL:
                problems.append(f"estimate costs {ratio:.2f}x > 1.5")
            if on["true"] > FLOOR and on["true"] >= 10 * s.ref_bound and not LOW <= est_ratio <= HIGH:
                problems.append(f"window estimate/true {est_ratio:.3g} outside [0.5, 30]")
            if on["true"] <= FLOOR and not on["estimate"] <= max(HIGH * on["true"], FLOOR):
                problems.append(f"window estimate {on['estimate']:.2e} > max(30 x true {on['true']:.2e}, 1e-10) "
                                f"near rounding")
            if problems:
                failures.append(f"{s.name}, explicit rtol {r:g}: " + "; ".join(problems))
            say(f"| {s.name} | {r:g} | {fmt(off['time'], '.3g')} | {fmt(on['time'], '.3g')} | {fmt(ratio, '.2f')} | "
                f"{fmt(rhs_ratio, '.2f')} | {fmt(on['true'])}{'' if on['true'] >= 10 * s.ref_bound else ' ~'} | "
                f"{fmt(est_ratio, '.3g')} | "
                f"{'ok' if not problems else '**' + ', '.join(p.split(' ')[0] + ' ' + p.split(' ')[1] for p in problems) + '**'} |")

    say()
    say("Scenes (reference: DOP853 at rtol 1e-14; its error bound = distance to the run at 1e-13):")
    for s in all_scenes:
        say(f"  {s.name}: {s.label}; states {', '.join(s.model._core.state_names)}; reference bound "
            f"{s.ref_bound:.1e}")
    say()
    say(f"Goals not met ({len(failures)}):" if failures else "Every goal met.")
    for f in failures:
        say(f"  - {f}")
    if notes:
        say("Accuracies no tolerance reaches (not counted as failures: the path warned):")
        for n in notes:
            say(f"  - {n}")
    say(f"\n(bench time {time.perf_counter() - started:.0f} s)")
    args.out.mkdir(parents=True, exist_ok=True)
    (args.out / "accuracy_cost.txt").write_text("\n".join(lines) + "\n")
    charts(rows, all_scenes, accuracies, args.out)
    return 0


def charts(rows: list[dict], all_scenes: list[Scene], accuracies: list[float], out: Path) -> None:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    markers = dict(zip([s.name for s in all_scenes], "osD^vP"))
    colours = dict(zip([s.name for s in all_scenes], plt.rcParams["axes.prop_cycle"].by_key()["color"]))
    lo, hi = min(accuracies) / 30, max(accuracies) * 3
    fig, ax = plt.subplots(figsize=(6.4, 5.2))
    ax.plot([lo, hi], [lo, hi], "k-", lw=1, label="delivered = asked")
    for s in all_scenes:
        mine = [r for r in rows if r["scene"] == s.name and not r["error"]]
        jitter = 1 + 0.06 * (list(markers).index(s.name) - 2.5)
        xs = [r["accuracy"] * jitter for r in mine]
        ax.plot(xs, [max(r["true"], 1e-14) for r in mine], markers[s.name], color=colours[s.name], ms=6,
                label=f"{s.name}: delivered")
        ax.plot(xs, [r["estimate"] for r in mine], markers[s.name], color=colours[s.name], ms=8, mfc="none",
                alpha=0.7)
        warned = [r for r in mine if r["warned"]]
        ax.plot([r["accuracy"] * jitter for r in warned], [max(r["true"], 1e-14) for r in warned], "x", color="k",
                ms=5)
        failed = [r for r in rows if r["scene"] == s.name and r["error"]]
        for r in failed:
            ax.annotate("raised", (r["accuracy"], r["accuracy"]), color=colours[s.name], fontsize=7,
                        xytext=(4, -12), textcoords="offset points")
            ax.plot([r["accuracy"]], [r["accuracy"]], "x", color=colours[s.name], ms=9)
    ax.plot([], [], "o", color="0.4", mfc="none", ms=8, label="reported estimate (open)")
    ax.plot([], [], "x", color="k", ms=5, label="AccuracyWarning raised")
    ax.set(xscale="log", yscale="log", xlim=(lo, hi), ylim=(1e-13, 1e-2), xlabel="accuracy asked",
           ylabel="relative error (true, against a reference at rtol 1e-14)",
           title="solve(..., accuracy=A): error delivered and reported")
    ax.legend(fontsize=7, loc="upper left")
    ax.grid(True, which="major", alpha=0.3)
    fig.tight_layout()
    fig.savefig(out / "accuracy_delivered.png", dpi=120)
    plt.close(fig)

    fig, ax = plt.subplots(figsize=(6.4, 4.4))
    for s in all_scenes:
        mine = [r for r in rows if r["scene"] == s.name and not r["error"] and math.isfinite(r["ratio"])]
        ax.plot([r["accuracy"] for r in mine], [r["ratio"] for r in mine], "-" + markers[s.name],
                color=colours[s.name], label=f"{s.name} (time)")
        ax.plot([r["accuracy"] for r in mine], [r["rhs_ratio"] for r in mine], ":" + markers[s.name],
                color=colours[s.name], mfc="none", alpha=0.7)
    ax.plot([], [], ":o", color="0.4", mfc="none", label="right-hand-side evaluations (dotted)")
    ax.axhline(RATIO_GOAL, color="k", lw=1, ls="--", label="goal: 3x")
    ax.set(xscale="log", yscale="log", xlabel="accuracy asked",
           ylabel="accuracy path / cheapest plain run meeting it",
           title="The accuracy's cost (probe, run, companion) over brute force")
    ax.legend(fontsize=7, ncol=2)
    ax.grid(True, which="both", alpha=0.3)
    fig.tight_layout()
    fig.savefig(out / "accuracy_cost.png", dpi=120)
    plt.close(fig)


if __name__ == "__main__":
    sys.exit(main())
