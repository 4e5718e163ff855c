"""The accuracy contract: every answer carries a measured estimate of its global error, and a run
given ``accuracy`` chooses its tolerances to meet it (:func:`estimate_runs`, :func:`meet`).

The error is measured on the quantities a run reports (:func:`quantities`): ω as a vector
(``omega``), the attitude quaternion (``quaternion``), a moving mass's displacement and velocity
(``displacement``, ``velocity``), every other state component on its own (the averaged models'
``a``, ``r``, ``G2``, ``pb``, ``phase``, the top's ``G_z``, ``H``, the orthogonal model's ``tau``),
and the outputs |G| (``angular_momentum_norm``), T (``kinetic_energy``), the moving mass's
``energy`` and the top's ``G_z`` and ``H``: each quantity's largest difference over the output
times, relative to its largest size (a vector's norm). The estimate is the largest over the
quantities; ``Solution.error_estimates`` holds each one. Which states form a vector, which are
labels and which outputs are measured, each model declares in C++ (``model::Quantity::vector``,
``label``, ``model::OutputInfo::measured``; ``_core.Model.measured_quantities``).

How it is measured (the basis, in words, is ``Solution.error_basis`` and a line of ``notes``):

* **tolerances given (or defaulted)**: the run is repeated over the first :data:`WINDOW` of its
  span at its own tolerances and at tolerances :data:`TIGHTER` times smaller, compared at
  :data:`SAMPLES` times: their difference is the run's error there (times ρ/(ρ−1): the tighter
  run's own error, under tolerance proportionality). Its running maximum, grown to the end of the
  span as t^k with k fitted over the window's second half (between 1 and 2: linear drift of the
  invariants, quadratic growth of a phase error whose frequency error itself drifts), is the
  estimate. Cost: ~0.3× the run (dop853), ``error_estimate=False`` turns it off. A run that
  crosses a separatrix of its model after the first half of the window (the sign of the model's
  ``separatrix``, declared in C++, changes: the body's rotation moves to another axis) is measured
  over the whole span instead, as with ``"full"``: the error jumps at the crossing, which the
  window's growth cannot foresee (it read 0.007–0.024× the true error on a viscous cavity that
  crosses at 57 % of its span).
* ``error_estimate="full"``: the companion run at the tighter tolerances covers the whole span,
  compared at every output time (cost: one more run, a little dearer than the run itself).
* **accuracy given** (:func:`meet`): a probe over the first :data:`PROBE` of the span at three
  tolerances measures the error per unit rtol at the horizon (grown as above; with no method
  given, DOP853's and Taylor's probes are timed and the cheaper taken, :func:`choose_method`); rtol (and atol =
  rtol · :data:`ATOL_RATIO` · max|y0|) is chosen for half the accuracy; the run and its tighter
  companion then cover the whole span, and their difference (× ρ/(ρ−1)) is the estimate,
  measured at every output time. When it exceeds the accuracy, the run is repeated tighter (by
  the measured ratio) up to :data:`ROUNDS` times; a run that still cannot meet it (rounding of
  doubles over a long span, ``max_steps``) warns (:class:`gyrostat.AccuracyWarning`) with the
  measured error and what would meet it.
* method ``splitting``: its own estimate (steps of h against h/2 along the run, relative to
  max|y_i|: ``docs/integrators.md``); a companion, where one runs (``"full"``, ``accuracy``), halves a
  given step (Richardson: the difference times 2^p/(2^p − 1), p the composition's order).
* a closed form (:class:`gyrostat.TorqueFreeModel`): no integration error; rounding only
  (:data:`CLOSED_FORM_ERROR`, the largest measured against mpmath in tests/test_torque_free.py).
"""

from __future__ import annotations

import copy
import math
import time
from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np

from gyrostat import _core

TIGHTER = 4.0
"""ρ: the companion run's tolerances are this many times smaller than the run's (:data:`TIGHTER_BY_METHOD`)."""
TIGHTER_BY_METHOD = {"taylor": 100.0, "cvode_bdf": 10.0, "cvode_adams": 10.0}
"""ρ where the error does not follow the tolerance closely: Taylor's order changes with it (its error
can stay put over a factor 4), BDF's and Adams' order and step vary; a wider ratio keeps the companion
much more accurate than the run."""
def _least_rtol() -> float:
    """The least rtol the engine accepts, found from its own rule (C++ ``Options::check``), not restated."""
    accepted, refused = 1e-8, 1e-30
    for _ in range(60):  # bisection in log10(rtol): to a few parts in 1e3
        middle = math.sqrt(accepted * refused)
        try:
            _core.Options.check("rtol", middle)
            accepted = middle
        except ValueError:
            refused = middle
    return accepted


ENGINE_RTOL = _least_rtol()
"""The engine's least rtol (``Options.check``; 1e-14 today)."""
WINDOW = 0.2
"""The fraction of the span the estimate of a run at given tolerances covers."""
WINDOW_SAFETY = 3.0
"""The window's estimate, grown to the horizon, is multiplied by this: a phase error can grow
faster than the window shows (measured: up to 3× under the t^k growth on long spans)."""
PROBE = 1.0 / 16.0
"""The fraction of the span the accuracy's probe covers (to choose rtol)."""
SAMPLES = 201
"""Window and probe compare their runs at this many evenly spaced times."""
WINDOW_TIMES = 16
"""The window compares the run's own output times when it holds at least this many of them."""
MARGIN = 0.6
"""rtol is chosen for this fraction of the accuracy asked."""
PROBE_LEAST_GROWTH = 0.5
"""The probe grows its error to the horizon at least as t^0.5 (a damped error may level off: the
whole-span check catches a probe that was too hopeful, at the cost of one more run)."""
ROUNDS = 3
"""The most runs tighter than the first that :func:`meet` makes before it warns."""
ATOL_RATIO = 1e-3
"""With ``accuracy``: atol = rtol · ATOL_RATIO · max|y0| (the state's size)."""
LOOSEST_RTOL, TIGHTEST_RTOL = 1e-3, 1e-13
"""The range of rtol :func:`meet` chooses from."""
CLOSED_FORM_ERROR = 1e-14
"""The closed form's error estimate: rounding in its elliptic functions."""
FLOOR = 1e-16
"""An estimate is never below this (one rounding of the largest component)."""

@dataclass(frozen=True)
class Quantity:
    """A compared quantity: its name, and the columns of the state (``role == "state"``) or of
    the outputs that make it."""

    name: str
    role: str
    columns: np.ndarray


@dataclass
class Estimate:
    """A run's measured global error: the largest relative error over the compared quantities
    (``value``), each quantity's (``per_quantity``), what it rests on (``basis``) and, for a run
    given an accuracy, whether the estimate meets it."""

    value: float
    per_quantity: dict[str, float] = field(default_factory=dict)
    basis: str = ""
    accuracy: float | None = None
    warning: str = ""
    """Why the accuracy asked is not met, with the measured error and what would meet it ("" when it is)."""

    @property
    def met(self) -> bool | None:
        """Whether the estimate is within the accuracy asked (None: none was asked)."""
        if self.accuracy is None:
            return None
        return bool(self.value <= self.accuracy)

    def as_dict(self) -> dict:
        return {"value": self.value, "per_quantity": dict(self.per_quantity), "basis": self.basis,
                "accuracy": self.accuracy, "met": self.met, "warning": self.warning}


class Compared:
    """A model's run measured on the quantities ``compare`` gives (solution → (n, m): one quantity,
    ``"compared"``, relative to its largest row norm) instead of :func:`quantities`: what the model
    ladder compares (|G| and T, (a, r), ...) when a scene needs no more."""

    __slots__ = ("core", "compare", "model")

    def __init__(self, core, compare: Callable, model=None):
        self.core, self.compare, self.model = core, compare, model


_QUANTITIES: dict[tuple, list] = {}


def quantities(core) -> list[Quantity]:
    """The quantities the error of a run of the model ``core`` is measured on: what its C++
    declarations say (``core.measured_quantities``: a vector's components as one quantity, labels
    left out, the measured outputs), or ``compared`` for a :class:`Compared` model."""
    if isinstance(core, Compared):
        return [Quantity("compared", "compare", np.zeros(0, int))]
    key = (tuple(core.state_names), tuple(core.output_names))
    known = _QUANTITIES.get(key)
    if known is None:
        known = _QUANTITIES[key] = [Quantity(name, role, np.asarray(columns, int))
                                    for name, role, columns in core.measured_quantities]
    return known


def _rows(result, quantity: Quantity, keep=slice(None), core=None) -> np.ndarray:
    """A compared quantity's rows: what ``core.compare`` gives of the result."""
    from gyrostat.solution import Solution  # (a results-floor neighbour: the compare functions read Solutions)

    return np.asarray(core.compare(Solution(result, core.model)), float).reshape(len(result.t), -1)[keep]


def _rows_kept(keep, count: int) -> np.ndarray:
    """The row numbers a keep (a slice or a boolean mask) selects."""
    return np.arange(count)[keep] if isinstance(keep, slice) else np.flatnonzero(keep)


def differences(reference, other, core, keep_reference=slice(None), keep_other=slice(None)) -> dict[str, np.ndarray]:
    """Each quantity's difference between two results at the same times, relative to its largest
    size in ``reference``: {name: (n,)} (the engine's ``measured_differences``; a :class:`Compared`
    model's on its ``compare``)."""
    wanted = quantities(core)
    if not isinstance(core, Compared):
        rows = [_rows_kept(keep, len(r.t)) for keep, r in ((keep_reference, reference), (keep_other, other))]
        if not (len(rows[0]) == len(reference.t) and len(rows[1]) == len(other.t)):  # (every row: nothing to pass)
            apart = core.measured_differences(reference, other, rows[0], rows[1])
        else:
            apart = core.measured_differences(reference, other)
        return {quantity.name: apart[i] for i, quantity in enumerate(wanted)}
    a, b = _rows(reference, wanted[0], keep_reference, core), _rows(other, wanted[0], keep_other, core)
    with np.errstate(all="ignore"):  # huge or non-finite values: scaled first, NaN stays NaN
        unit = float(np.abs(a).max()) if a.size else 0.0
        unit = unit if 0 < unit < math.inf else 1.0
        a, apart = a / unit, (a - b) / unit
        scale = math.sqrt(float(np.einsum("ij,ij->i", a, a).max())) if a.size else 0.0
        distance = np.sqrt(np.einsum("ij,ij->i", apart, apart))
    return {"compared": distance / (scale if scale > 0 else 1.0)}


# ------------------------------------------------------------------------------------ companions
def ratio(method: str) -> float:
    """ρ for this method (:data:`TIGHTER_BY_METHOD`, else :data:`TIGHTER`)."""
    return TIGHTER_BY_METHOD.get(method, TIGHTER)


def tighter(opts) -> tuple[object, float, str]:
    """The companion's Options (tolerances ρ times smaller, at least the engine's least rtol, or a
    given splitting step halved), the factor turning the difference into the run's own error, and
    what was tightened (words)."""
    made = _copy(opts)
    if opts.method == "splitting" and opts.step > 0:
        made.step = opts.step / 2.0
        gain = 2.0 ** opts.splitting_order
        return made, gain / (gain - 1.0), f"the step halved (Richardson, order {opts.splitting_order})"
    rho = min(ratio(opts.method), opts.rtol / ENGINE_RTOL)
    if rho < 2.0:  # the run is at the engine's least tolerance: nothing tighter to compare with
        return made, math.inf, "nothing: the run's rtol is the engine's least"
    made.rtol, made.atol = opts.rtol / rho, opts.atol / rho
    return made, rho / (rho - 1.0), f"rtol and atol / {rho:g}"


def _copy(opts, t_eval=None):
    """A copy of the options without events, dense output or every step (a companion records only
    its output times), at ``t_eval`` when given."""
    made = copy.copy(opts)
    if made.events:
        made.events = []
    made.every_step = made.dense_output = False
    if t_eval is not None:
        made.t_eval = np.asarray(t_eval, float)
    return made


Runner = Callable[[object, float, list], list]
"""run(options, t_end, members) -> the engine's Result of each member (in that order)."""


def _grow(running: np.ndarray, times: np.ndarray, t0: float, horizon: float,
          least: float = 1.0) -> tuple[float, float]:
    """The running maximum of a difference over a window grown to ``horizon`` as t^k, k fitted over
    the window's second half and kept within [least, 2]; (value, k). (Distances from t0: a backward
    run grows the same way.)"""
    last = float(running[-1])
    end, middle, far = abs(times[-1] - t0), abs(times[len(times) // 2] - t0), abs(horizon - t0)
    if far <= end or last == 0.0:
        return last, 1.0
    half = float(running[len(running) // 2])
    k = 1.0 if half <= 0 else min(2.0, max(least, math.log(last / half) / math.log(end / middle)))
    return last * (far / end) ** k, k


def window_estimates(run: Runner, cores: list, opts, t0: float, t1: float, horizons: list[float],
                     fraction: float = WINDOW, answers: list | None = None) -> list[Estimate]:
    """The estimate of each member's run at ``opts`` (ending at its horizon) from runs at ``opts``
    and at :func:`tighter` ones over the first ``fraction`` of the span (module doc). With the
    members' ``answers`` (engine results sharing their output times, at least :data:`WINDOW_TIMES`
    of them in the window), the answers themselves stand for the runs at ``opts``: only the
    companion runs."""
    members = list(range(len(cores)))
    window = t0 + fraction * (t1 - t0)
    upper, inside = None, slice(None)
    if answers:
        times = np.asarray(answers[0].t, float)
        within = (times - t0) * (1.0 if t1 >= t0 else -1.0) <= fraction * abs(t1 - t0)
        if within.sum() >= WINDOW_TIMES and all(np.array_equal(np.asarray(a.t, float), times) for a in answers[1:]):
            upper, inside = answers, within
            grid = times[within]
            window = float(grid[-1])
    if upper is None:
        grid = np.linspace(t0, window, SAMPLES)
        upper = run(_copy(opts, grid), window, members)
    companion, gain, what = tighter(_copy(opts, grid))
    if not math.isfinite(gain):
        return [Estimate(math.nan, {}, f"no estimate: compared with {what}") for _ in cores]
    lower = run(companion, window, members)
    made = []
    for i, core in enumerate(cores):
        a, b = upper[i], lower[i]
        rows = int(np.count_nonzero(inside)) if isinstance(inside, np.ndarray) else len(a.t)
        if not (a.success or isinstance(inside, np.ndarray)) or not b.success or rows != len(grid) \
                or len(b.t) != len(grid):
            failed = b if not b.success else a
            made.append(Estimate(math.nan, {}, f"no estimate: the window's run stopped ({failed.status}: "
                                                f"{failed.message})"))
            continue
        per, ks = {}, []
        grows = abs(horizons[i] - t0) > abs(window - t0)
        for name, d in differences(b, a, core, slice(None), inside).items():
            value, k = _grow(np.maximum.accumulate(d * gain), grid, t0, horizons[i])
            per[name] = max(value * (WINDOW_SAFETY if grows else 1.0), FLOOR)
            ks.append(k)
        growth = (f"grown as t^{max(ks):.2g} to t = {horizons[i]:.6g}, times {WINDOW_SAFETY:g}" if grows
                  else "over the whole run")
        made.append(Estimate(max(per.values()), per,
                             f"measured over the first {fraction:.0%} of the span ([{t0:.6g}, {window:.6g}], "
                             f"{len(grid)} times) against a run with {what} (difference x {gain:.3g}), {growth}"))
    return made


def span_estimates(run: Runner, cores: list, opts, answers: list, members: list[int],
                   companions: dict | None = None) -> list[Estimate]:
    """The estimate of each member's answer from a companion run with :func:`tighter` options over
    the whole span, compared at every output time of the answer (the companions' results kept in
    ``companions`` by member, when given)."""
    if not members:
        return []
    times = np.asarray(answers[members[0]].t, float)
    shared = all(np.array_equal(np.asarray(answers[m].t, float), times) for m in members)
    grid = times if shared else np.unique(np.concatenate([np.asarray(answers[m].t, float) for m in members]))
    companion, gain, what = tighter(_copy(opts, grid))
    if not math.isfinite(gain):
        return [Estimate(math.nan, {}, f"no estimate: compared with {what}") for _ in members]
    t_end = float(max(answers[m].t_last for m in members)) if len(grid) else float(opts.t_eval[-1])
    results = run(companion, t_end, members)
    made = []
    for m, other in zip(members, results):
        if companions is not None:
            companions[m] = other
        answer = answers[m]
        mine = np.asarray(answer.t, float)
        if not other.success or not len(mine):
            made.append(Estimate(math.nan, {}, f"no estimate: the companion run stopped ({other.status}: "
                                               f"{other.message})"))
            continue
        theirs = np.asarray(other.t, float)
        if np.array_equal(mine, theirs):  # the companion records the answer's own times (as a rule)
            keep_mine = keep_theirs = np.ones(len(mine), bool)
        else:
            keep_mine, keep_theirs = np.isin(mine, theirs), np.isin(theirs, mine)
        per = {name: max(float(d.max()) * gain, FLOOR) if d.size else math.nan
               for name, d in differences(answer, other, cores[m], keep_mine, keep_theirs).items()}
        made.append(Estimate(max(per.values()), per,
                             f"measured at {int(keep_mine.sum())} output times over the whole run against a run "
                             f"with {what} (difference x {gain:.3g})"))
    return made


def closed_form_estimate(core) -> Estimate:
    """A closed form's estimate: rounding only."""
    per = {q.name: CLOSED_FORM_ERROR for q in quantities(core)}
    return Estimate(CLOSED_FORM_ERROR, per, "closed form (no integration): rounding in the elliptic functions, at most "
                                            f"{CLOSED_FORM_ERROR:g} against mpmath")


def crossing(core, answer, after: float) -> float | None:
    """The first time past ``after`` (in the direction of the run) at which the answer crosses a
    separatrix of its model (the sign of ``core.separatrix`` changes between two output times; a
    model that declares none never crosses), or None."""
    model = core.core if isinstance(core, Compared) else core
    times = np.asarray(answer.t, float)
    if len(times) < 2 or not hasattr(model, "separatrix"):
        return None
    side = np.sign(np.asarray(model.separatrix(np.asarray(answer.y, float)), float))
    forward = 1.0 if times[-1] >= times[0] else -1.0
    changed = np.flatnonzero((side[:-1] * side[1:] < 0) & ((times[1:] - after) * forward > 0))
    return float(times[changed[0] + 1]) if changed.size else None


def estimate_runs(run: Runner, cores: list, opts, t0: float, t1: float, answers: list, full: bool = False,
                  companions: dict | None = None) -> list:
    """Each answer's :class:`Estimate` (None for a failed or empty run, which estimates nothing):
    over a window (``full=False``) or the whole span (``full=True``)."""
    made: list = [None] * len(answers)
    if any(getattr(a, "status", "") == "interrupted" for a in answers):  # Ctrl-C: no more runs
        return made
    closed = [i for i, a in enumerate(answers) if a.method == "closed_form" and len(a.t)]
    for i in closed:
        made[i] = closed_form_estimate(cores[i])
    for i, a in enumerate(answers):  # the splitting measures its own (Richardson over the whole run)
        if a.method == "splitting" and len(a.t) and math.isfinite(a.error_estimate):
            made[i] = Estimate(max(float(a.error_estimate), FLOOR), {"state": max(float(a.error_estimate), FLOOR)},
                               "the splitting's own: steps of h against h/2 along the run (notes)")
            closed.append(i)
    members = [i for i, a in enumerate(answers) if a.success and len(a.t) and a.t_last != t0 and i not in closed]
    if not members or t1 == t0:
        return made
    crossings = {} if full else {m: t for m in members
                                 if (t := crossing(cores[m], answers[m], t0 + 0.5 * WINDOW * (t1 - t0))) is not None}
    if full or crossings:  # the whole span: asked, or where the window cannot see a separatrix crossing
        spanned = members if full else list(crossings)
        for m, e in zip(spanned, span_estimates(run, cores, opts, answers, spanned, companions)):
            if m in crossings:
                e.basis = (f"the run crosses a separatrix at t = {crossings[m]:.6g}, after the first half of the window, "
                           f"where its error grows faster than the window shows: {e.basis}")
            made[m] = e
        members = [m for m in members if m not in spanned]
        if not members:
            return made
    sub = lambda o, t, ms: run(o, t, [members[j] for j in ms])  # noqa: E731  (members renumbered)
    estimates = window_estimates(sub, [cores[m] for m in members], opts, t0, t1,
                                 [float(answers[m].t_last) for m in members],
                                 answers=[answers[m] for m in members])
    for m, e in zip(members, estimates):
        made[m] = e
    return made


# ------------------------------------------------------------------------------------ the accuracy asked
def with_tolerances(opts, rtol: float, atol: float):
    """A copy of the options (events and dense output included) at these tolerances."""
    made = _copy(opts)
    made.every_step = opts.every_step
    made.events, made.dense_output = opts.events, opts.dense_output
    made.rtol, made.atol = float(rtol), float(atol)
    return made


def probe_rtol(run: Runner, cores: list, opts, t0: float, t1: float, accuracy: float, first: float,
               atol_of, seconds: list | None = None) -> tuple[float, dict]:
    """The rtol predicted to give MARGIN · accuracy at the horizon: runs at ``first``, first/ρ and
    first/ρ² over the first :data:`PROBE` of the span; the errors of the first two (against the
    third) give the exponent α of error ∝ rtol^α, the first's error grown to the horizon
    (:func:`_grow`) its size there. The tightest rtol any member needs, and each member's α (the
    probe's runs' (rtol, seconds) appended to ``seconds`` when given)."""
    window = t0 + PROBE * (t1 - t0)
    grid = np.linspace(t0, window, SAMPLES)
    members = list(range(len(cores)))
    rho = ratio(opts.method)
    first = max(first, ENGINE_RTOL * rho * rho)
    tolerances = (first, first / rho, first / rho**2)
    runs = []
    for r in tolerances:
        started = time.perf_counter()
        runs.append(run(_copy(with_tolerances(opts, r, atol_of(r)), grid), window, members))
        if seconds is not None:
            seconds.append((r, time.perf_counter() - started))
    wanted, alphas = [], {}
    for i, core in enumerate(cores):
        loose, middle, reference = (r[i] for r in runs)
        if not all(r.success and len(r.t) == SAMPLES for r in (loose, middle, reference)):
            continue
        curves = [np.maximum.accumulate(np.max(list(differences(reference, r, core).values()), axis=0))
                  for r in (loose, middle)]
        at_horizon, _ = _grow(curves[0], grid, t0, t1, least=PROBE_LEAST_GROWTH)
        if not at_horizon > 0:
            continue
        alpha = 1.0 if not curves[1][-1] > 0 else min(2.0, max(0.7, math.log(curves[0][-1] / curves[1][-1]) /
                                                                   math.log(rho)))
        alphas[i] = alpha
        wanted.append(first * (MARGIN * accuracy / at_horizon) ** (1.0 / alpha))
    return (min(LOOSEST_RTOL, max(TIGHTEST_RTOL, min(wanted))) if wanted else first), alphas


TAYLOR_BELOW = 1e-5
"""With no method given, an accuracy at or below this has Taylor's probe timed against DOP853's
(measured on the damped triaxial body, t = 1e4: Taylor 2.5x cheaper at 1e-6, 3-5x at 1e-8 to 1e-10)."""


def choose_method(run: Runner, cores: list, opts, t0: float, t1: float, accuracy: float, first: float,
                  atol_of) -> tuple[object, float, str]:
    """The cheaper of DOP853 and Taylor for this accuracy (the options with it, its rtol, why in
    words): each one's probe (:func:`probe_rtol`) gives its rtol and the time of its three runs, whose
    log-log slope in rtol predicts the whole run's time at that rtol. Taylor is tried only for
    accuracies at or below :data:`TAYLOR_BELOW` (where its high order pays) and models it covers
    (constant and linear torques: a ValueError otherwise)."""
    trials = []
    for method in ("dop853", "taylor") if accuracy <= TAYLOR_BELOW else ("dop853",):
        trial = _copy(opts)
        trial.every_step, trial.events, trial.dense_output = opts.every_step, opts.events, opts.dense_output
        trial.method = method
        seconds: list = []
        try:
            rtol, probed = probe_rtol(run, cores, trial, t0, t1, accuracy, first, atol_of, seconds)
        except ValueError:  # the method does not cover this model (a single run raises)
            continue
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
         choose: bool = False) -> tuple[list, list]:
    """Every member run at tolerances chosen for ``accuracy`` and measured over the whole span
    (module doc); ``size`` is the largest |y0| component (atol = rtol · ATOL_RATIO · size).
    ``opts`` holds the run's other options (output times, events, method, max_steps). Returns
    each member's answer (the engine's Result) and its :class:`Estimate` (None when the answer
    estimates nothing: a failed run; then a warning stands in an Estimate of NaN). With ``choose``
    (no method was given), the method too (:func:`choose_method`)."""
    count = len(cores)
    atol_of = lambda r: r * ATOL_RATIO * (size if size > 0 else 1.0)  # noqa: E731
    first = min(LOOSEST_RTOL, max(TIGHTEST_RTOL, 0.1 * accuracy))
    why = ""
    if choose and t1 != t0:
        opts, rtol, why = choose_method(run, cores, opts, t0, t1, accuracy, first, atol_of)
    else:
        rtol, _ = probe_rtol(run, cores, opts, t0, t1, accuracy, first, atol_of) if t1 != t0 else (first, {})
    swappable = not opts.events and not opts.dense_output and not opts.every_step
    made: list = [None] * count
    estimates: list = [None] * count
    members, previous, carried = list(range(count)), {}, {}
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
        measured = estimate_runs(run, cores, tried, t0, t1, [r if r is not None else _EMPTY for r in results],
                                 full=True, companions=companions)
        again, tighter_rtol = [], []
        for i in members:
            answer, estimate = answers[i], measured[i]
            if estimate is not None:
                estimate.accuracy = accuracy
                estimate.basis = (why + f"rtol {rtol:.3g}, atol {atol_of(rtol):.3g} chosen for the accuracy {accuracy:g} "
                                  f"(probe at three tolerances over the first {PROBE:.1%} of the span); "
                                  + estimate.basis)
            made[i], estimates[i] = answer, estimate
            if estimate is not None and math.isnan(estimate.value) and not estimate.warning:
                estimate.warning = (f"the error could not be measured ({estimate.basis.rsplit('; ', 1)[-1]}): the "
                                    f"accuracy {accuracy:g} is not shown to be met; ask for a looser accuracy")
            if estimate is None or not math.isfinite(estimate.value) or estimate.met:
                continue
            value = estimate.value
            taken = _companion_answer(estimate, companions.get(i), answer, tried, accuracy) if swappable else None
            if taken is not None:
                made[i], estimates[i] = taken
                continue
            floor = i in previous and value > 0.5 * previous[i][0] and rtol < 0.25 * previous[i][1]
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
            previous[i] = (value, rtol)
            again.append(i)
            tighter_rtol.append(max(TIGHTEST_RTOL, rtol * MARGIN * accuracy / value))
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


def _companion_answer(estimate: Estimate, companion, answer, tried, accuracy: float):
    """(The companion's result, its estimate) when the companion run (ρ ≥ 2 times tighter, its
    output times the answer's) meets the accuracy by a bound of its own error: the difference of
    the two runs (the companion's error is the difference over ρ^α − 1, at most the difference
    wherever α ≥ log 2 / log ρ; the probe's α proved too uncertain to divide by). None otherwise."""
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


class _Empty:
    """A stand-in result for members not run this round."""

    success, t, t_last, method = False, np.zeros(0), math.nan, ""


_EMPTY = _Empty()
