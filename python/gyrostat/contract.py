"""The accuracy asked: a run given ``accuracy`` chooses its tolerances to meet it and is measured
over its whole span (:func:`meet`), with the measurements of :mod:`gyrostat.accuracy`.

* **The probe** (:func:`probe_rtol`): runs over the first :data:`PROBE` of the span at three
  tolerances measure the error per unit rtol at the horizon (grown as t^k, as the window's
  estimate is); with no method given, DOP853's and Taylor's probes are timed and the cheaper
  taken (:func:`choose_method`). rtol (and atol = rtol · :data:`ATOL_RATIO` · max|y0|) is chosen
  for :data:`MARGIN` of the accuracy. The probe's runs record only the measured outputs
  (``Options.only_measured_outputs``), which is all they compare.
* **The first run** and its tighter companion cover the whole span; their difference (× ρ/(ρ−1))
  at every output time is the estimate. Where the companion meets the accuracy by a bound of its
  own error (the difference itself), the companion is the answer, for the Runge–Kutta pairs of one
  order (:data:`SCALED`), its error also measured as a repeat's is (below) and the lesser kept
  (:func:`_checked_companion`); for the other methods, and where the bound misses, a companion tight
  enough by the measured ratio is the next round's answer, measured in turn.
* **A run repeated tighter** (by the measured ratio, up to :data:`ROUNDS` times) is measured
  without a second whole-span companion where it can be (:func:`scaled_estimates`): the first
  run's whole-span error, scaled by the ratio of the two runs' errors over the first
  :data:`gyrostat.accuracy.WINDOW` of the span, each measured against its own companion there
  (tolerance proportionality, measured: the error's course over the span keeps its shape when the
  tolerance changes, within :data:`SCALE_SAFETY`, by which it is multiplied), for the Runge–Kutta
  pairs of one order (:data:`SCALED`), a first run whose error is small against the quantities
  (:data:`SCALE_CEILING`) and below the probe's cap (:func:`_scales`); the other repeats are measured
  over the whole span again.
* **A short run** (fewer than :data:`CHEAP_EVALUATIONS` right-hand sides predicted from the probe's
  first run) is not probed further: its first run, at rtol = accuracy / 10, and the companion
  measure it directly; for a single solve in one engine call, the companion recording only the
  measured outputs (:func:`meet_single`).
* A run that still cannot meet it (rounding of doubles over a long span, ``max_steps``) warns
  (:class:`gyrostat.AccuracyWarning`) with the measured error and what would meet it.
"""

from __future__ import annotations

import functools
import math
import time

import numpy as np

from gyrostat import _core
from gyrostat.accuracy import (ENGINE_RTOL, FLOOR, WINDOW, Compared, Estimate, Runner, SingleRun, apart, companion_gain,
                               copy_options, estimate_runs, even_times, grow, ratio, running_maxima, solve_measured,
                               tighter, window_error, window_estimates)
from gyrostat.options import derived

PROBE = 1.0 / 16.0
"""The fraction of the span the accuracy's probe covers (to choose rtol)."""

MARGIN = 0.6
"""rtol is chosen for this fraction of the accuracy asked (bench/accuracy_cost.py's scenes against 0.5,
0.7 and 0.85: the fewest right-hand sides in geometric mean, 1.15 against 1.15–1.26, and the least
largest ratio to the cheapest run, 3.05 against 3.09–4.28; a miss costs a repeat)."""

PROBE_LEAST_GROWTH = 0.5
"""The probe grows its error to the horizon at least as t^0.5 (a damped error may level off: the
whole-span check catches a probe that was too hopeful, at the cost of one more run)."""

ROUNDS = 3
"""The most runs tighter than the first that :func:`meet` makes before it warns."""

ATOL_RATIO = 1e-3
"""With ``accuracy``: atol = rtol · ATOL_RATIO · max|y0| (the state's size)."""

PROBE_LEAST_ALPHA = 1.0
"""The probe's exponent α of error ∝ rtol^α is taken at least this: DOP853's global error follows its
tolerance as rtol^1.1 to rtol^1.4 once the error is small (bench/accuracy_cost.py's scenes), and a probe
whose loosest run is not yet there measured α = 0.7 on the damped body with attitude and chose an rtol
80 times tighter than needed; a probe too hopeful costs one more run, measured cheaply
(:func:`scaled_estimates`)."""

CHEAP_EVALUATIONS = 2000
"""A run predicted (from the probe's first run) to take fewer right-hand sides than this over the
whole span is not probed further: its first run, at rtol = accuracy / 10, and the companion measure
it directly. Such a run (the averaged models: ~100 evaluations, ~20 µs) costs less than the probe's
own Python (~0.3 ms for three runs and their comparisons)."""

SHORT = "short"
"""What :func:`choose_method` says of a run too short to probe (:data:`CHEAP_EVALUATIONS`)."""

PROBE_SAMPLES = 41
"""The probe compares its runs at this many evenly spaced times (each one an interpolation of
every run: at 201 the probe's runs, a few steps each, spent most of their time there)."""

LOOSEST_RTOL, TIGHTEST_RTOL = 1e-3, 1e-13
"""The range of rtol :func:`meet` chooses from."""

LOOSEST_PROBED_RTOL = 1e-5
"""A probed run's rtol is at most this: looser, DOP853's global error over a long span is erratic in
rtol (the orthogonal torque over t = 195: 1.8e-3 at rtol 1e-4, 2.7e-3 at 5e-5, 2.9e-4 at 2.5e-5) and
a companion at rtol/4 misreads it (the probe's choice there, 2.8e-4 at accuracy 1e-3, delivered
2.7e-3 with an estimate 0.23× that; ``bench/contract_sweep.py``). The probed rtols of
``bench/accuracy_cost.py``'s scenes lie below it already. A short run (not probed) keeps
accuracy/10: held to this too, the orthogonal torque over t = 90.3 at accuracy 1e-3 went from an
estimate 0.43× its true error (rtol 1e-4) to 0.59× (1e-5), but a constant torque over t = 270 from
3.6× to 0.42× (its error 1.8e-4, 2.1e-4, 1.3e-4 at rtol 1e-5, 5e-6, 2.5e-6), at ~1.3× the cost
(``bench/contract_sweep.py`` seeds 2 and 5)."""


def with_tolerances(opts, rtol: float, atol: float):
    """A copy of the options (events and dense output included) at these tolerances."""
    made = copy_options(opts)
    made.every_step = opts.every_step
    made.events, made.dense_output = opts.events, opts.dense_output
    made.rtol, made.atol = float(rtol), float(atol)
    return made


def probe_rtol(run: Runner, cores: list, opts, t0: float, t1: float, accuracy: float, first: float,
               atol_of, seconds: list | None = None, first_run: tuple | None = None) -> tuple[float, dict | None]:
    """The rtol predicted to give MARGIN · accuracy at the horizon: runs at ``first``, first/ρ and
    first/ρ² over the first :data:`PROBE` of the span; the errors of the first two (against the
    third) give the exponent α of error ∝ rtol^α, the first's error grown to the horizon
    (:func:`gyrostat.accuracy.grow`) its size there. The tightest rtol any member needs, and each member's α (the
    probe's runs' (rtol, seconds) appended to ``seconds`` when given); (``first``, None) when the
    first run predicts a whole run cheaper than the probe (:data:`CHEAP_EVALUATIONS`). ``first_run``:
    (the first run's results, its seconds) made already (:func:`meet_single`)."""
    window = t0 + PROBE * (t1 - t0)
    grid = even_times(t0, window, PROBE_SAMPLES)
    members = list(range(len(cores)))
    rho = ratio(opts.method)
    first = max(first, ENGINE_RTOL * rho * rho)
    tolerances = (first, first / rho, first / rho**2)
    measured_only = not any(isinstance(core, Compared) for core in cores)  # (they compare only the quantities)
    runs = []
    for r in tolerances:
        started = time.perf_counter()
        if first_run is not None and not runs:
            runs.append(first_run[0])
            started -= first_run[1]
        else:
            probing = copy_options(opts, grid)  # (its events, dense output and every_step off)
            probing.rtol, probing.atol = float(r), float(atol_of(r))
            probing.only_measured_outputs = measured_only
            runs.append(run(probing, window, members))
        if seconds is not None:
            seconds.append((r, time.perf_counter() - started))
        if len(runs) == 1 and all(r.success for r in runs[0]) and \
                0 < max(r.stats.rhs_evals for r in runs[0]) < CHEAP_EVALUATIONS * PROBE:
            return first, None
    wanted, alphas = [], {}
    for i, core in enumerate(cores):
        loose, middle, reference = (r[i] for r in runs)
        if not all(r.success and len(r.t) == PROBE_SAMPLES for r in (loose, middle, reference)):
            continue
        (loose_end, tight_end), (loose_half, _) = running_maxima(
            np.vstack([apart(reference, r, core)[1].max(axis=0) for r in (loose, middle)]))
        at_horizon, _ = grow(loose_end, loose_half, abs(grid[-1] - t0), abs(grid[len(grid) // 2] - t0), abs(t1 - t0),
                             least=PROBE_LEAST_GROWTH)
        if not at_horizon > 0:
            continue
        measured = math.log(loose_end / tight_end) / math.log(rho) if tight_end > 0 else 1.0
        alpha = min(2.0, max(PROBE_LEAST_ALPHA, measured))
        alphas[i] = alpha
        wanted.append(first * (MARGIN * accuracy / at_horizon) ** (1.0 / alpha))
    return (min(LOOSEST_PROBED_RTOL, max(TIGHTEST_RTOL, min(wanted))) if wanted else first), alphas


TAYLOR_BELOW = 1e-5
"""With no method given, an accuracy at or below this has Taylor's probe timed against DOP853's
(measured on the damped triaxial body, t = 1e4: Taylor 2.5x cheaper at 1e-6, 3-5x at 1e-8 to 1e-10)."""


def choose_method(run: Runner, cores: list, opts, t0: float, t1: float, accuracy: float, first: float,
                  atol_of, first_run: tuple | None = None) -> tuple[object, float, str]:
    """The cheaper of DOP853 and Taylor for this accuracy (the options with it, its rtol, why in
    words): each one's probe (:func:`probe_rtol`) gives its rtol and the time of its three runs, whose
    log-log slope in rtol predicts the whole run's time at that rtol. Taylor is tried only for
    accuracies at or below :data:`TAYLOR_BELOW` (where its high order pays) and models it covers
    (constant and linear torques: a ValueError otherwise). ``first_run``: DOP853's first probe run, made
    already (:func:`probe_rtol`)."""
    trials = []
    for method in ("dop853", "taylor") if accuracy <= TAYLOR_BELOW else ("dop853",):
        trial = copy_options(opts)
        trial.every_step, trial.events, trial.dense_output = opts.every_step, opts.events, opts.dense_output
        trial.method = method
        seconds: list = []
        try:
            rtol, probed = probe_rtol(run, cores, trial, t0, t1, accuracy, first, atol_of, seconds,
                                      first_run if method == "dop853" else None)
        except ValueError:  # the method does not cover this model (a single run raises)
            continue
        if probed is None:  # a short run: no probe (and no other method) pays
            return trial, rtol, SHORT
        if method != "dop853" and len(probed) < len(cores):  # ... or a member's probe failed (an ensemble's runs
            continue                                          # say invalid_input): not a candidate
        (loose, s_loose), (tight, s_tight) = seconds[0], seconds[-1]
        slope = math.log(s_tight / s_loose) / math.log(tight / loose) if s_loose > 0 and s_tight > 0 else 0.0
        trials.append((s_tight * (rtol / tight) ** slope / PROBE, method, trial, rtol))
    cost, method, trial, rtol = min(trials, key=lambda entry: entry[0])
    why = "" if len(trials) == 1 else ("method " + method + " chosen: predicted " + ", ".join(
        f"{m} {c:.3g} s" for c, m, _, _ in trials) + " from the probes; ")
    return trial, rtol, why


def meet(run: Runner, cores: list, opts, t0: float, t1: float, accuracy: float, size: float,
         choose: bool = False, first_run: tuple | None = None) -> tuple[list, list]:
    """Every member run at tolerances chosen for ``accuracy`` and measured over the whole span
    (module doc); ``size`` is the largest |y0| component (atol = rtol · ATOL_RATIO · size).
    ``opts`` holds the run's other options (output times, events, method, max_steps). Returns
    each member's answer (the engine's Result) and its :class:`Estimate` (None when the answer
    estimates nothing: a failed run; then a warning stands in an Estimate of NaN). With ``choose``
    (no method was given), the method too (:func:`choose_method`). ``first_run``: the probe's first
    run, made already (:func:`meet_single`)."""
    count = len(cores)
    atol_of = functools.partial(_atol_of, size)
    first = _first_rtol(accuracy)
    why = ""
    if choose and t1 != t0:
        opts, rtol, why = choose_method(run, cores, opts, t0, t1, accuracy, first, atol_of, first_run)
    elif t1 != t0:
        rtol, probed = probe_rtol(run, cores, opts, t0, t1, accuracy, first, atol_of, None, first_run)
        why = SHORT if probed is None else ""
    else:
        rtol = first
    how = _NO_PROBE if why == SHORT else _PROBED
    why = "" if why == SHORT else why
    swappable = not opts.events and not opts.dense_output and not opts.every_step
    made: list = [None] * count
    estimates: list = [None] * count
    members, previous, carried, bases = list(range(count)), {}, {}, {}
    for round_ in range(ROUNDS + 1):
        tried = with_tolerances(opts, rtol, atol_of(rtol))
        if carried:  # the last round's companions, run at this rtol: not run again
            answers, carried = carried, {}
        else:
            answers = dict(zip(members, run(tried, t1, members)))
        if any(a.status == "interrupted" for a in answers.values()):  # Ctrl-C: what was computed, no more runs
            for i, answer in answers.items():
                made[i] = answer
            break
        results = [answers.get(i) for i in range(count)]
        companions: dict = {}
        measured = _measure(run, cores, tried, t0, t1, results, members, bases, companions)
        again, tighter_rtol = [], []
        for i in members:
            answer, estimate = answers[i], measured[i]
            if estimate is not None:
                estimate.accuracy = accuracy
                estimate.prefix(functools.partial(_chosen, why, rtol, atol_of(rtol), accuracy, how))
            made[i], estimates[i] = answer, estimate
            if estimate is not None and math.isnan(estimate.value) and not estimate.warning:
                estimate.warning = (f"the error could not be measured ({estimate.basis.rsplit('; ', 1)[-1]}): the "
                                    f"accuracy {accuracy:g} is not shown to be met; ask for a looser accuracy")
            if estimate is None or not math.isfinite(estimate.value) or estimate.met:
                continue
            value = estimate.value
            taken = _companion_answer(estimate, companions.get(i), answer, tried, accuracy) \
                if swappable and tried.method in SCALED else None
            if taken is not None:
                base = bases[i]() if callable(bases.get(i)) else bases.get(i)
                made[i], estimates[i] = _checked_companion(lambda o, t, ms, i=i: run(o, t, [i for _ in ms]),
                                                           cores[i], tried, t0, t1, taken, base)
                continue
            # the rounding floor: the measured error (a scaled estimate's without its safety factor, which
            # a whole-span measurement before it does not carry) did not halve for rtol 4 times smaller
            measurement = value / estimate.safety
            floor = i in previous and measurement > 0.5 * previous[i][0] and rtol < 0.25 * previous[i][1]
            if floor:
                estimate.warning = (f"the measured error {value:.3g} exceeds the accuracy {accuracy:g} and does not "
                                    f"fall with rtol ({rtol:.3g}): the rounding of doubles over this span; the least "
                                    f"error reachable is about {value:.2g}: ask for an accuracy above it")
                continue
            if rtol <= TIGHTEST_RTOL:
                estimate.warning = (f"the measured error {value:.3g} exceeds the accuracy {accuracy:g} at the least "
                                    f"rtol the contract takes ({TIGHTEST_RTOL:g}): ask for an accuracy above "
                                    f"{value:.2g}, or give rtol down to 1e-14 yourself")
                continue
            previous[i] = (measurement, rtol)
            again.append(i)
            scaled_next = tried.method in SCALED and _scales(bases.get(i))  # (its next estimate is scaled)
            tighter_rtol.append(max(TIGHTEST_RTOL, rtol * MARGIN * accuracy / value /
                                    (SCALE_SAFETY if scaled_next else 1.0)))
        if not again:
            break
        rho = min(ratio(tried.method), tried.rtol / ENGINE_RTOL)
        reuse = swappable and rho >= 2.0 and min(tighter_rtol) >= tried.rtol / rho and \
            tried.rtol / rho >= 2.0 * ENGINE_RTOL and \
            all(i in companions and companions[i].success for i in again)  # (and the new answer can be measured)
        if reuse and round_ < ROUNDS:  # the companion is tight enough by the measured ratio: it is the next answer
            members, rtol = again, tried.rtol / rho
            carried = {i: companions[i] for i in again}
            continue
        if round_ == ROUNDS:
            for i in again:
                estimates[i].warning = (f"the measured error {estimates[i].value:.3g} exceeds the accuracy "
                                   f"{accuracy:g} after {ROUNDS + 1} runs (last rtol {rtol:.3g}); rtol about "
                                   f"{min(tighter_rtol):.2g} would meet it")
            break
        members, rtol = again, min(tighter_rtol)
    for i, answer in enumerate(made):
        if answer is not None and not answer.success and answer.status != "interrupted":
            estimates[i] = Estimate(math.nan, {}, "no estimate: the run stopped", accuracy,
                                    f"the run stopped ({answer.status}: {answer.message}): the accuracy {accuracy:g} "
                                    f"is not met over the span" + (", raise max_steps" if answer.status ==
                                                                    "max_steps_reached" else ""))
    return made, estimates


def _atol_of(size: float, rtol: float) -> float:
    """atol for this rtol: rtol · :data:`ATOL_RATIO` · the state's size (1 for a zero state)."""
    return rtol * ATOL_RATIO * (size if size > 0 else 1.0)


def _first_rtol(accuracy: float) -> float:
    """The probe's first (loosest) rtol, and a short run's own: accuracy / 10 within the range."""
    return min(LOOSEST_RTOL, max(TIGHTEST_RTOL, 0.1 * accuracy))


def meet_single(core, y0, t0: float, t1: float, opts, accuracy: float, size: float, report=None,
                choose: bool = False) -> tuple:
    """:func:`meet` of one run (:func:`gyrostat.solve`): (the answer, its Estimate). The probe's first
    run comes first; a run it predicts short (:data:`CHEAP_EVALUATIONS`) is run and measured over
    the whole span in one engine call (:func:`gyrostat.accuracy.solve_measured`: the same runs and
    numbers as :func:`meet`'s, without its rounds' Python), its Options made once for each cached
    Options (:func:`gyrostat.options.derived`). Any other run, or a short one whose estimate does not
    meet the accuracy, goes on to :func:`meet`, given that first run."""
    probing, window, tried, companion = derived(opts, ("meet", t0, t1, accuracy, size, choose),
                                                functools.partial(_single_plan, t0, t1, accuracy, size, choose))
    started = time.perf_counter()
    first_run = [_core.solve(core, y0, t0, window, probing, report)]
    seconds = time.perf_counter() - started
    stats = first_run[0].stats
    if first_run[0].success and 0 < stats.rhs_evals < CHEAP_EVALUATIONS * PROBE:
        answer, estimate = solve_measured(core, y0, t0, t1, tried, report, True, companion)
        if answer.status == "interrupted":  # Ctrl-C: what was computed, no more runs
            return answer, None
        if answer.success and estimate is not None and estimate.value <= accuracy:  # (NaN is not)
            estimate.accuracy = accuracy
            estimate.prefix(functools.partial(_chosen, "", tried.rtol, tried.atol, accuracy, _NO_PROBE))
            return answer, estimate
    made, estimates = meet(SingleRun(core, y0, t0, report), [core], opts, t0, t1, accuracy, size, choose,
                           (first_run, seconds))
    return made[0], estimates[0]


def _single_plan(t0: float, t1: float, accuracy: float, size: float, choose: bool, opts) -> tuple:
    """:func:`meet_single`'s Options: the probe's first run's (as :func:`probe_rtol` makes them), the
    end of its window, a short run's (as :func:`meet` makes them) and its companion's
    (:func:`gyrostat.accuracy.tighter`)."""
    method = "dop853" if choose else opts.method
    first = max(_first_rtol(accuracy), ENGINE_RTOL * ratio(method) ** 2)
    window = t0 + PROBE * (t1 - t0)
    probing = copy_options(opts, even_times(t0, window, PROBE_SAMPLES))
    probing.method, probing.rtol, probing.atol = method, float(first), float(_atol_of(size, first))
    probing.only_measured_outputs = True
    tried = with_tolerances(opts, first, _atol_of(size, first))
    tried.method = method
    return probing, window, tried, tighter(copy_options(tried), fresh=True)


_NO_PROBE = (f"no probe: a short run, fewer than {CHEAP_EVALUATIONS} right-hand sides predicted from the probe's first "
             f"run")
_PROBED = f"probe at three tolerances over the first {PROBE:.1%} of the span"


def _chosen(why: str, rtol: float, atol: float, accuracy: float, how: str) -> str:
    """How a contract run's tolerances were chosen, in words (before its measurement's basis)."""
    return why + f"rtol {rtol:.3g}, atol {atol:.3g} chosen for the accuracy {accuracy:g} ({how}); "


SCALED = ("dop853", "arkode_verner6", "arkode_fehlberg8")
"""Methods whose repeated runs are measured by scaling (:func:`scaled_estimates`): Runge–Kutta pairs
of one order, whose error keeps its course over the span when the tolerance changes. Taylor and
CVODE change their order with the tolerance (measured: a Taylor repeat on the damped body scaled
to 0.13 of its true error), ``auto`` may switch integrators between two tolerances, ``splitting``
measures its own error: their repeats are measured over the whole span again."""
SCALE_SAFETY = 2.0
"""A scaled estimate is multiplied by this: the ratio of the window's errors read the whole span's
ratio to within 0.41–2.3 (the damped triaxial body's ω at accuracy 1e-5, whose phase error falls
less than the window's between rtol 1.5e-7 and 1.8e-8; the cavity crossing the separatrix): doubled,
the estimate reads 0.8–4.6× the true error there. A repeat's rtol is chosen with it counted."""
SCALE_FLOOR = 100.0 * ENGINE_RTOL
"""A first run's error over the window must exceed this to scale from (below it, rounding)."""
SCALE_CEILING = 0.1
"""A first run's whole-span error must be at most this to scale from: a relative error of order one
no longer follows the tolerance (it cannot grow past the quantities' own size). Measured on the cavity
crossing the separatrix (bench/accuracy_cost.py's scene, a probe over the first 1/32 of the span): a
first run at rtol 1e-4 measured 0.66 over the whole span, and the repeat at rtol 4.6e-8 scaled from it
read 1.9e-4 where its true error was 4.0e-3 (0.048×). The whole span's own errors there follow rtol as
rtol^1.3 up to ~0.01 and as rtol^0.7 at ~0.1, within what the scaled estimate's safety factor covers
(the scene's first run at accuracy 1e-3 measures 0.07 and its scaled repeat reads 2.3× its true error)."""


def _measure(run: Runner, cores: list, tried, t0: float, t1: float, results: list, members: list[int],
             bases: dict, companions: dict) -> list:
    """Each member's estimate this round: scaled from its base (its last whole-span measurement) where
    it has one and the method allows (:func:`scaled_estimates`), else measured over the whole span
    (the base then recorded, the companions kept in ``companions``)."""
    measured: list = [None] * len(results)
    for i in [i for i in members if callable(bases.get(i))]:  # the window's error of a base, measured when first needed
        bases[i] = bases[i]()
        if bases[i] is None:
            del bases[i]
    scaled = [i for i in members if _scales(bases.get(i)) and results[i] is not None] if tried.method in SCALED \
        else []
    if scaled:
        sub = lambda o, t, ms: run(o, t, [scaled[j] for j in ms])  # noqa: E731  (members renumbered)
        for i, e in zip(scaled, scaled_estimates(sub, [cores[i] for i in scaled], tried, t0, t1,
                                                 [results[i] for i in scaled], [bases[i] for i in scaled])):
            measured[i] = e
    spanned = [i for i in members if measured[i] is None]
    if spanned:
        over = estimate_runs(run, cores, tried, t0, t1, [results[i] if i in spanned and results[i] is not None
                                                        else _EMPTY for i in range(len(results))],
                             full=True, companions=companions)
        gain = companion_gain(tried)
        for i in spanned:
            measured[i] = over[i]
            if over[i] is not None and math.isfinite(over[i].value) and math.isfinite(gain):
                bases[i] = functools.partial(_base, tried.rtol, over[i], results[i], companions.get(i), cores[i],
                                             t0, t1, gain)
    return measured


def _scales(base) -> bool:
    """Whether a repeat is scaled from this base (:func:`_base`, or the partial that makes it): one whose
    run lay below :data:`LOOSEST_PROBED_RTOL`. A first run at that cap (its probe wanted looser, or a
    short run's accuracy/10) lies where DOP853's error can be erratic in rtol, and the window's ratio
    misread a repeat's whole-span error there: 0.16× on a damped body over t = 1047 (the repeat at rtol
    8.6e-7 from 1e-5: the window's error fell 40×, the whole span's 5.7×) and 0.21× on a cavity over
    t = 2498, which delivered 2.2e-3 at accuracy 1e-3 (``bench/contract_sweep.py`` seeds 2 and 6). Such a
    repeat is measured over the whole span; the base still checks a companion taken as the answer."""
    if base is None:
        return False
    rtol = base.args[0] if isinstance(base, functools.partial) else base[0]
    return rtol < LOOSEST_PROBED_RTOL


def _base(rtol: float, spanned: Estimate, answer, companion, core, t0: float, t1: float, gain: float):
    """(rtol, whole-span Estimate, error over the window) of a run measured over the whole span, or None
    where its error over the window cannot be measured (too few output times there, or rounding) or its
    whole-span error is too large to scale from (:data:`SCALE_CEILING`)."""
    if not spanned.value <= SCALE_CEILING:
        return None
    early = window_error(answer, companion, core, t0, t1, gain)
    return (rtol, spanned, early) if early is not None and early > SCALE_FLOOR else None


def scaled_estimates(run: Runner, cores: list, opts, t0: float, t1: float, answers: list,
                     bases: list) -> list:
    """Each answer's estimate from its base, (rtol, whole-span Estimate, error over the window) of an
    earlier run of the same member: that run's whole-span error times the ratio of this answer's
    error over the first :data:`gyrostat.accuracy.WINDOW` of the span (against a companion there,
    the only run made) to that run's there. None where the ratio cannot be measured (a failed
    companion, an error that did not fall): that member is measured over the whole span instead."""
    windows = window_estimates(run, cores, opts, t0, t1, [float(a.t_last) for a in answers], answers=answers,
                               to_horizon=False)
    made: list = []
    for answer, window, (rtol, spanned, before) in zip(answers, windows, bases):
        now = window.value
        if not (answer.success and math.isfinite(now) and 0.0 < now < before):
            made.append(None)
            continue
        scale = SCALE_SAFETY * now / before
        per = {name: max(v * scale, FLOOR) for name, v in spanned.per_quantity.items()}
        made.append(Estimate(max(per.values()), per,
                             f"the whole-span error measured at rtol {rtol:.3g} ({spanned.value:.3g}) scaled by this "
                             f"run's error over the first {WINDOW:.0%} of the span over that run's there ({now:.3g} / "
                             f"{before:.3g}; each against a run with tolerances {ratio(opts.method):g} times "
                             f"tighter), times {SCALE_SAFETY:g}: the error keeps its course over the span when the "
                             f"tolerance changes, within that factor", safety=SCALE_SAFETY))
    return made


def _companion_answer(estimate: Estimate, companion, answer, tried, accuracy: float):
    """(The companion's result, its estimate) when the companion run (ρ ≥ 2 times tighter, its
    output times the answer's) meets the accuracy by a bound of its own error: the difference of
    the two runs (the companion's error is the difference over ρ^α − 1, at most the difference
    wherever α ≥ log 2 / log ρ; the probe's α proved too uncertain to divide by). For the
    Runge–Kutta pairs of one order (:data:`SCALED`) alone: Taylor and CVODE change their order with
    the tolerance, ``auto`` may change integrators. None otherwise. The bound can lie far above the
    companion's error (:func:`_checked_companion` measures it)."""
    if companion is None or not companion.success or len(companion.t) != len(answer.t):
        return None
    rho = min(ratio(tried.method), tried.rtol / ENGINE_RTOL)
    if rho < 2.0:
        return None
    shrink = (rho - 1.0) / rho  # back from the answer's estimate (difference x rho/(rho-1)) to the difference
    value = estimate.value * shrink
    if value > accuracy:
        return None
    per = {name: v * shrink for name, v in estimate.per_quantity.items()}
    return companion, Estimate(value, per, f"the companion run (rtol {tried.rtol / rho:.3g}) taken as the answer: "
                                             f"its error is at most the difference of the two runs; "
                                             f"{estimate.basis}", accuracy)


def _checked_companion(run: Runner, core, tried, t0: float, t1: float, taken: tuple, base) -> tuple:
    """A companion taken as the answer (:func:`_companion_answer`) with its own error measured as a
    repeat's is (:func:`scaled_estimates`: the answer's whole-span error scaled by the two runs'
    errors over the window, times :data:`SCALE_SAFETY`; one run over the window), the lesser of that
    and the bound kept: DOP853 on the moving mass (λ = 63, t = 19.8, accuracy 1e-3) ran the answer
    in a regime where its error fell 350× for a 4× tighter rtol, and the bound read 430× the
    companion's true error, outside the contract's band."""
    companion, bound = taken
    if base is None:
        return taken
    rho = min(ratio(tried.method), tried.rtol / ENGINE_RTOL)
    its_options = with_tolerances(tried, tried.rtol / rho, tried.atol / rho)
    measured = scaled_estimates(run, [core], its_options, t0, t1, [companion], [base])[0]
    if measured is None or not measured.value < bound.value:
        return taken
    measured.accuracy = accuracy = bound.accuracy
    measured.basis = (f"the companion run (rtol {its_options.rtol:.3g}) taken as the answer (the difference of the two "
                      f"runs, {bound.value:.3g}, bounds its error): {measured.basis}")
    return companion, measured if measured.value <= accuracy else bound


class _Empty:
    """A stand-in result for members not run this round."""

    success, t, t_last, method = False, np.zeros(0), math.nan, ""


_EMPTY = _Empty()
