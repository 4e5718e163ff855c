"""The accuracy contract's measurement: every answer carries a measured estimate of its global error
(:func:`estimate_runs`); a run given ``accuracy`` chooses its tolerances to meet it with these
measurements (:mod:`gyrostat.contract`).

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
  invariants, quadratic growth of a phase error whose frequency error itself drifts; k = 1 where the
  companion took fewer than :data:`WINDOW_FIT_STEPS` steps over the window), is the estimate.
  Cost: ~0.3× the run (dop853), ``error_estimate=False`` turns it off. A run that
  crosses a separatrix of its model after the first half of the window (the sign of the model's
  ``separatrix``, declared in C++, changes: the body's rotation moves to another axis) is measured
  over the whole span instead, as with ``"full"``: the error jumps at the crossing, which the
  window's growth cannot foresee (it read 0.007–0.024× the true error on a viscous cavity that
  crosses at 57 % of its span).
* ``error_estimate="full"``: the companion run at the tighter tolerances covers the whole span,
  compared at every output time (cost: one more run, a little dearer than the run itself).
* **accuracy given**: :mod:`gyrostat.contract` chooses the tolerances and measures the answer with
  the functions here.
* **where it runs**: a run of :func:`gyrostat.solve` (:class:`SingleRun`) and the members of
  :func:`gyrostat.solve_ensemble` (:class:`EnsembleRun`, the companions as one ensemble, threads
  and SIMD batches as the answers') are measured in one engine call (``_core.window_estimate`` and
  ``window_estimates``, ``gyrostat/measure.hpp``: the separatrix check, the companion, the
  comparison at the answer's own output times and the growth), window or whole span alike. The
  rest (a run with fewer than :data:`WINDOW_TIMES` output times in the window, which is sampled at
  :data:`SAMPLES` times; a model ladder's comparison, :class:`Compared`; a crossing; the probe) is
  measured here, on the same engine rule (``_core.window_from_differences``, ``grow``). Both give
  the same numbers (tests/test_measurement_primitives.py); the engine's saves the Python around
  each run: on the averaged (a, r) scene (t = 60, 201 outputs, a ~20 µs run) 42 → 21 µs per
  estimate, on an ensemble of 500 such members 31 → 14 µs per member (bench/README.md).
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
from functools import partial

import numpy as np

from gyrostat import _core
from gyrostat.estimate import Compared, Estimate, Quantity, quantities, quantity_names
from gyrostat.options import derived

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
SAMPLES = 201
"""Window and probe compare their runs at this many evenly spaced times."""
WINDOW_TIMES = 16
"""The window compares the run's own output times when it holds at least this many of them."""
WINDOW_FIT_STEPS = 8
"""The growth exponent k is fitted over the window only where its companion took at least this many
steps there; with fewer, k = 1: a few steps' differences are a staircase, whose running maxima say where
its stairs fall, not how the error grows (gyrostat/measure.hpp, window_from_differences: the fit read
k = 2 on runs of 4–20 steps whose error had stopped growing, estimates up to 100 times their true error;
``bench/contract_sweep.py --explicit``, seeds 1–6: 53 of 510 window estimates outside [0.5, 30] times the
true error with the fit everywhere, 17 with this rule, the same from 6 to 16 steps)."""
CLOSED_FORM_ERROR = 1e-14
"""The closed form's error estimate: rounding in its elliptic functions."""
FLOOR = 1e-16
"""An estimate is never below this (one rounding of the largest component)."""

def _rows(result, quantity: Quantity, keep=slice(None), core=None) -> np.ndarray:
    """A compared quantity's rows: what ``core.compare`` gives of the result."""
    from gyrostat.solution import Solution  # (a results-floor neighbour: the compare functions read Solutions)

    return np.asarray(core.compare(Solution(result, core.model)), float).reshape(len(result.t), -1)[keep]


def _rows_kept(keep, count: int):
    """The row numbers a keep (a slice or a boolean mask) selects; None for every row."""
    if isinstance(keep, slice):
        return None if keep == slice(None) or keep == slice(0, count) else np.arange(count)[keep]
    return None if keep.all() and len(keep) == count else np.flatnonzero(keep)


def apart(reference, other, core, keep_reference=slice(None), keep_other=slice(None)) -> tuple[list[str], np.ndarray]:
    """The quantities' names and how far the two results are apart on each at each compared pair
    of rows ((quantities, n): :func:`differences` as one array)."""
    wanted = quantities(core)
    if not isinstance(core, Compared):
        return [q.name for q in wanted], core.measured_differences(
            reference, other, _rows_kept(keep_reference, len(reference.t)), _rows_kept(keep_other, len(other.t)))
    a, b = _rows(reference, wanted[0], keep_reference, core), _rows(other, wanted[0], keep_other, core)
    with np.errstate(all="ignore"):  # huge or non-finite values: scaled first, NaN stays NaN
        unit = float(np.abs(a).max()) if a.size else 0.0
        unit = unit if 0 < unit < math.inf else 1.0
        a, distance = a / unit, (a - b) / unit
        scale = math.sqrt(float(np.einsum("ij,ij->i", a, a).max())) if a.size else 0.0
        distance = np.sqrt(np.einsum("ij,ij->i", distance, distance))
    return ["compared"], (distance / (scale if scale > 0 else 1.0))[np.newaxis, :]


def differences(reference, other, core, keep_reference=slice(None), keep_other=slice(None)) -> dict[str, np.ndarray]:
    """Each quantity's difference between two results at the same times, relative to its largest
    size in ``reference``: {name: (n,)} (the engine's ``measured_differences``; a :class:`Compared`
    model's on its ``compare``)."""
    names, made = apart(reference, other, core, keep_reference, keep_other)
    return {name: made[i] for i, name in enumerate(names)}


# ------------------------------------------------------------------------------------ companions
def ratio(method: str) -> float:
    """ρ for this method (:data:`TIGHTER_BY_METHOD`, else :data:`TIGHTER`)."""
    return TIGHTER_BY_METHOD.get(method, TIGHTER)


def tighter(opts, fresh: bool = False) -> tuple[object, float, str]:
    """The companion's Options (tolerances ρ times smaller, at least the engine's least rtol, or a
    given splitting step halved), the factor turning the difference into the run's own error, and
    what was tightened (words). ``fresh``: ``opts`` is a copy of the caller's own, tightened in place."""
    made = opts if fresh else copy_options(opts)
    gain = companion_gain(opts)
    if opts.method == "splitting" and opts.step > 0:
        made.step = opts.step / 2.0
        return made, gain, f"the step halved (Richardson, order {opts.splitting_order})"
    if not math.isfinite(gain):  # the run is at the engine's least tolerance: nothing tighter to compare with
        return made, gain, "nothing: the run's rtol is the engine's least"
    rho = min(ratio(opts.method), opts.rtol / ENGINE_RTOL)
    made.rtol, made.atol = max(opts.rtol / rho, ENGINE_RTOL), opts.atol / rho  # (no rounding below the least)
    return made, gain, f"rtol and atol / {rho:g}"


def companion_of(opts) -> tuple[object, float, str]:
    """:func:`tighter` of a copy of ``opts``, made once for each of the options cache's shared Options
    (:func:`gyrostat.options.derived`; ~4 µs a run saved): not to be modified."""
    return derived(opts, "companion", _companion)


def _companion(opts) -> tuple[object, float, str]:
    return tighter(copy_options(opts), fresh=True)


def companion_gain(opts) -> float:
    """The factor :func:`tighter`'s companion turns a difference into the run's own error by
    (ρ/(ρ−1), or 2^p/(2^p−1) for a halved splitting step; ∞ where nothing tighter can run)."""
    if opts.method == "splitting" and opts.step > 0:
        gain = 2.0 ** opts.splitting_order
        return gain / (gain - 1.0)
    rho = min(ratio(opts.method), opts.rtol / ENGINE_RTOL)
    return rho / (rho - 1.0) if rho >= 2.0 else math.inf


def copy_options(opts, t_eval=None):
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


grow = _core.grow
"""grow(last, half, end, middle, far, least=1.0) -> (value, k): a difference's running maximum over
a window grown to the horizon as t^k (the engine's rule, gyrostat/measure.hpp)."""


class SingleRun:
    """The :data:`Runner` of one model's run from (t0, y0) (:func:`gyrostat.solve`): the engine's
    solve, and its window estimate made in one engine call (:func:`window_estimates`)."""

    __slots__ = ("core", "y0", "t0", "report")

    def __init__(self, core, y0, t0: float, report=None):
        self.core, self.y0, self.t0, self.report = core, y0, t0, report

    def __call__(self, opts, t_end: float, members: list) -> list:
        return [_core.solve(self.core, self.y0, self.t0, t_end, opts, self.report)]


class EnsembleRun:
    """The :data:`Runner` of an ensemble (:func:`gyrostat.solve_ensemble`): member i is a run of
    ``cores[i]`` (or ``cores[0]``) from (t0, ``y0s[i]``); its members' estimates are made in the
    engine, the companions as one ensemble (``_core.window_estimates``)."""

    __slots__ = ("cores", "y0s", "t0", "threads", "report", "batch", "count")

    def __init__(self, cores: list, y0s, t0: float, count: int, threads: int, report=None, batch: bool = True):
        self.cores, self.y0s, self.t0, self.count = cores, y0s, t0, count
        self.threads, self.report, self.batch = threads, report, batch

    def starts(self, members: list):
        """The members' initial states and models (all of them: as given)."""
        if len(members) == self.count:
            return self.cores, self.y0s
        y0s = self.y0s[members] if isinstance(self.y0s, np.ndarray) else [self.y0s[m] for m in members]
        return (self.cores if len(self.cores) == 1 else [self.cores[m] for m in members]), y0s

    def __call__(self, opts, t_end: float, members: list) -> list:
        cores, y0s = self.starts(members)
        return _core.solve_ensemble(cores, y0s, self.t0, t_end, opts, self.threads,
                                    self.report if len(members) == self.count else None, batch=self.batch)


def running_maxima(made: np.ndarray) -> tuple[list[float], list[float]]:
    """Each row's maximum over all its columns and over the first half (to the middle column
    included): the running maximum at the end and at the middle of the window (NaN stays NaN)."""
    middle = made.shape[1] // 2
    return made.max(axis=1).tolist(), made[:, :middle + 1].max(axis=1).tolist()


_RULES: dict[float, object] = {}


def _rule(gain: float):
    """The engine's WindowRule with this module's numbers and the companion's gain."""
    made = _RULES.get(gain)
    if made is None:
        made = _RULES[gain] = _core.WindowRule(fraction=WINDOW, least_times=WINDOW_TIMES, safety=WINDOW_SAFETY,
                                               floor=FLOOR, gain=gain, fit_steps=WINDOW_FIT_STEPS)
    return made


def same_times(a: np.ndarray, b: np.ndarray) -> bool:
    """Whether two runs recorded the very same output times (bit for bit: the same t_eval)."""
    return a.shape == b.shape and a.tobytes() == b.tobytes()


_UNIT_STEPS: dict[int, np.ndarray] = {}


def even_times(t0: float, t1: float, count: int) -> np.ndarray:
    """``count`` evenly spaced times from t0 to t1, both included exactly (``np.linspace`` to an
    ulp, at a fifth of its cost)."""
    unit = _UNIT_STEPS.get(count)
    if unit is None:
        unit = _UNIT_STEPS[count] = np.arange(count) / (count - 1)
    made = t0 + (t1 - t0) * unit
    made[-1] = t1
    return made


def _within(times: np.ndarray, t0: float, t1: float, fraction: float) -> int:
    """How many of a run's output times (monotone in its direction, from t0) lie in the first
    ``fraction`` of the span: they are the first ones."""
    return int(np.searchsorted((times - t0) * (1.0 if t1 >= t0 else -1.0), fraction * abs(t1 - t0), side="right"))


def window_estimates(run: Runner, cores: list, opts, t0: float, t1: float, horizons: list[float],
                     fraction: float = WINDOW, answers: list | None = None, to_horizon: bool = True) -> list[Estimate]:
    """The estimate of each member's run at ``opts`` (ending at its horizon) from runs at ``opts``
    and at :func:`tighter` ones over the first ``fraction`` of the span (module doc). With the
    members' ``answers`` (engine results sharing their output times, at least :data:`WINDOW_TIMES`
    of them in the window), the answers themselves stand for the runs at ``opts``: only the
    companion runs.
    ``to_horizon=False``: the error over the window itself, not grown to the horizon."""
    companion, gain, what = tighter(copy_options(opts), fresh=True)
    if not math.isfinite(gain):
        return [Estimate(math.nan, {}, f"no estimate: compared with {what}") for _ in cores]
    rule = _rule(gain)
    members = list(range(len(cores)))
    window = t0 + fraction * (t1 - t0)
    upper, inside = None, slice(None)
    if answers:
        times = np.asarray(answers[0].t, float)
        count = _within(times, t0, t1, fraction)
        if count >= WINDOW_TIMES and all(same_times(np.asarray(a.t, float), times) for a in answers[1:]):
            upper, inside = answers, slice(0, count)
            grid = times[:count]
            window = float(grid[-1])
    if upper is None:
        grid = even_times(t0, window, SAMPLES)
        upper = run(copy_options(opts, grid), window, members)
    companion.t_eval = grid
    lower = run(companion, window, members)
    made = []
    for i, core in enumerate(cores):
        a, b = upper[i], lower[i]
        rows = inside.stop if inside.stop is not None else len(a.t)
        if not (a.success or inside.stop is not None) or not b.success or rows != len(grid) \
                or len(b.t) != len(grid):
            failed = b if not b.success else a
            made.append(Estimate(math.nan, {}, f"no estimate: the window's run stopped ({failed.status}: "
                                                f"{failed.message})"))
            continue
        _, made_apart = apart(b, a, core, slice(None), inside)
        window_made = _core.window_from_differences(made_apart, grid, t0, horizons[i], rule, to_horizon, b.stats.steps)
        made.append(_window_estimate(window_made, quantity_names(core), t0, horizons[i], fraction, what, gain))
    return made


def _single_run_estimate(core, y0, t0: float, report, measured_on, opts, t1: float, answer, full: bool,
                         companions: dict | None) -> Estimate | None:
    """One run's estimate (the run of ``core`` from (t0, y0)) in one engine call
    (``_core.window_estimate``: the separatrix check, the companion, the comparison, the growth; with
    ``full``, over the whole span as :func:`span_estimates`), or None where :func:`estimate_runs`'
    general path takes it: a model ladder's comparison (``measured_on`` a :class:`Compared`), a
    closed form or a splitting, a failed or empty run, a run crossing a separatrix, too few output
    times in the window."""
    if t1 == t0 or isinstance(measured_on, Compared):
        return None
    companion, gain, what = companion_of(opts)
    if not math.isfinite(gain):
        return None
    # (None from the engine for a failed or empty run, and for a closed form or a splitting, which measure
    # themselves: it checks that first)
    made = _core.window_estimate(core, answer, t0, y0, t1, companion, _rule(gain), report, full)
    if made is None:
        return None
    if not full:
        return _window_estimate(made, quantity_names(core), t0, answer.t_last, WINDOW, what, gain)
    if companions is not None:  # (a whole span's companion: the contract may take it as the answer)
        companions[0] = made[6]
    return _engine_estimate(made, quantity_names(core), t0, answer, what, gain, full)


def _ensemble_estimates(run: EnsembleRun, cores: list, opts, t0: float, t1: float, answers: list, members: list[int],
                        full: bool, companions: dict | None) -> dict:
    """The members' estimates the engine makes, the companions as one ensemble
    (``_core.window_estimates``), by member; the others (a separatrix crossed, too few output
    times in the window, other output times) are left to :func:`estimate_runs`' general path."""
    companion, gain, what = companion_of(opts)
    if not math.isfinite(gain):
        return {}
    models, y0s = run.starts(members)
    found = _core.window_estimates(models, [answers[m] for m in members], t0, y0s, t1, companion, _rule(gain),
                                   run.threads, None, run.batch, full)
    made, names = {}, {}
    for m, one in zip(members, found):
        if one is not None:
            if companions is not None and full:
                companions[m] = one[6]
            core = cores[m]
            known = names.get(id(core))
            if known is None:
                known = names[id(core)] = quantity_names(core)
            made[m] = _engine_estimate(one, known, t0, answers[m], what, gain, full)
    return made


def _engine_estimate(made: tuple, names: list[str], t0: float, answer, what: str, gain: float,
                     full: bool) -> Estimate:
    """The :class:`Estimate` of the engine's measurement of one run (``_core.window_estimate``'s
    tuple): over the window, or over the whole span (``full``) as :func:`span_estimates` says it."""
    if not full:
        return _window_estimate(made, names, t0, answer.t_last, WINDOW, what, gain)
    values, _, _, _, count, failure = made[:6]
    if failure:
        return Estimate(math.nan, {}, f"no estimate: the companion run stopped ({failure})")
    per = dict(zip(names, values))
    return Estimate(max(per.values()), per, partial(_span_basis, count, what, gain, made[7]))


def _span_basis(count: int, what: str, gain: float, limit: float) -> str:
    """The words of a whole span's measurement (written when first read: :class:`Estimate`)."""
    steps = (f", its steps at most {limit:.3g} (half the run's mean step: the run's own were not its tolerance's)"
             if math.isfinite(limit) else "")
    return (f"measured at {count} output times over the whole run against a run with {what}{steps} (difference x "
            f"{gain:.3g})")


def _window_estimate(made: tuple, names: list[str], t0: float, horizon: float, fraction: float, what: str,
                     gain: float) -> Estimate:
    """The :class:`Estimate` of the engine's window estimate (``_core.window_estimate``'s tuple)."""
    values, k, grown, window, count, failure = made[:6]
    if failure:
        return Estimate(math.nan, {}, f"no estimate: the window's run stopped ({failure})")
    fitted = made[-1] if len(made) in (7, 9) else True  # (the engine's tuples end with it; a 6-tuple: fitted)
    per = dict(zip(names, values))
    return Estimate(max(per.values()), per, partial(_window_basis, t0, horizon, fraction, what, gain, k, grown, window,
                                                    count, fitted))


def _window_basis(t0: float, horizon: float, fraction: float, what: str, gain: float, k: float, grown: bool,
                  window: float, count: int, fitted: bool = True) -> str:
    """The words of a window estimate's basis (written when first read: :class:`Estimate`)."""
    exponent = f"t^{k:.2g}" if fitted else (f"t^1 (not fitted: the window's companion took fewer than "
                                            f"{WINDOW_FIT_STEPS} steps)")
    growth = (f"grown as {exponent} to t = {horizon:.6g}, times {WINDOW_SAFETY:g}" if grown
              else "over the whole run" if abs(horizon - t0) <= abs(window - t0) else "not grown")
    return (f"measured over the first {fraction:.0%} of the span ([{t0:.6g}, {window:.6g}], "
            f"{count} times) against a run with {what} (difference x {gain:.3g}), {growth}")


def span_estimates(run: Runner, cores: list, opts, t0: float, answers: list, members: list[int],
                   companions: dict | None = None) -> list[Estimate]:
    """The estimate of each member's answer (a run from ``t0``) from a companion run with
    :func:`tighter` options over the whole span (run again with its steps limited where
    ``_core.companion_step_limit`` says its tolerance did not set them), compared
    at every output time of the answer (the companions' results kept in ``companions`` by member,
    when given)."""
    if not members:
        return []
    times = np.asarray(answers[members[0]].t, float)
    shared = all(same_times(np.asarray(answers[m].t, float), times) for m in members[1:])
    grid = times if shared else np.unique(np.concatenate([np.asarray(answers[m].t, float) for m in members]))
    companion, gain, what = tighter(copy_options(opts, grid), fresh=True)
    if not math.isfinite(gain):
        return [Estimate(math.nan, {}, f"no estimate: compared with {what}") for _ in members]
    t_end = float(max(answers[m].t_last for m in members)) if len(grid) else float(opts.t_eval[-1])
    results, limits = list(run(companion, t_end, members)), {}
    for k, m in enumerate(members):  # a companion whose steps its tolerance did not set runs again, limited
        if results[k].success and type(answers[m]) is _core.Result and \
                (redo := _core.companion_step_limit(answers[m], t0, results[k].stats)) < companion.max_step:
            limited = copy.copy(companion)
            limited.max_step = limits[m] = redo
            results[k] = run(limited, t_end, [m])[0]
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
        if same_times(mine, theirs):  # the companion records the answer's own times (as a rule)
            keep_mine = keep_theirs = slice(None)
            compared = len(mine)
        else:
            keep_mine, keep_theirs = np.isin(mine, theirs), np.isin(theirs, mine)
            compared = int(keep_mine.sum())
        names, made_apart = apart(answer, other, cores[m], keep_mine, keep_theirs)
        largest = made_apart.max(axis=1).tolist() if made_apart.shape[1] else [math.nan] * len(names)
        per = {name: max(d * gain, FLOOR) if not math.isnan(d) else math.nan for name, d in zip(names, largest)}
        made.append(Estimate(max(per.values()), per, _span_basis(compared, what, gain, limits.get(m, math.inf))))
    return made


def window_error(answer, companion, core, t0: float, t1: float, gain: float) -> float | None:
    """The answer's largest error over the first :data:`WINDOW` of the span, measured against a
    companion at the same output times (the difference times ``gain``), or None where they share
    fewer than :data:`WINDOW_TIMES` output times there."""
    times = np.asarray(answer.t, float)
    if companion is None or not companion.success or not same_times(times, np.asarray(companion.t, float)):
        return None
    count = _within(times, t0, t1, WINDOW)
    if count < WINDOW_TIMES:
        return None
    _, made = apart(companion, answer, core, slice(0, count), slice(0, count))
    return float(made.max()) * gain if made.size else None


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
    if not hasattr(model, "first_crossing"):
        return None
    when = model.first_crossing(answer, after)
    return None if math.isnan(when) else float(when)


def solve_measured(core, y0, t0: float, t1: float, opts, report=None, full: bool = False,
                   companion: tuple | None = None) -> tuple:
    """The run of ``core`` from (t0, y0) to t1 and its :class:`Estimate` (None for a failed or empty
    run): in one engine call where the engine makes the estimate (``_core.solve_measured``: a
    single solve's default estimate pays one crossing of the binding), else as :func:`estimate_run`.
    ``companion``: :func:`tighter`'s (Options, gain, words) for ``opts``, made already; then a whole
    span's companion records only the measured outputs (it is not to become the answer)."""
    measured_only = companion is not None
    companion, gain, what = companion if measured_only else companion_of(opts)
    if not math.isfinite(gain):  # (nothing tighter to compare with: the general path says so)
        answer = _core.solve(core, y0, t0, t1, opts, report)
        return answer, estimate_run(core, core, y0, t0, t1, opts, answer, report, full) if answer.success else None
    answer, made = _core.solve_measured(core, y0, t0, t1, opts, companion, _rule(gain), report, full, measured_only)
    if made is not None:
        if full:
            return answer, _engine_estimate(made, quantity_names(core), t0, answer, what, gain, full)
        return answer, _window_estimate(made, quantity_names(core), t0, answer.t_last, WINDOW, what, gain)
    if t1 == t0 or not answer.success:
        return answer, None
    return answer, estimate_runs(SingleRun(core, y0, t0, report), [core], opts, t0, t1, [answer], full, engine=False)[0]


def estimate_run(measured_on, core, y0, t0: float, t1: float, opts, answer, report=None, full: bool = False):
    """The :class:`Estimate` of one run of ``core`` from (t0, y0) (:func:`estimate_runs` of a
    :class:`SingleRun`), measured on ``measured_on`` (``core``, or a :class:`Compared`)."""
    made = _single_run_estimate(core, y0, t0, report, measured_on, opts, t1, answer, full, None)
    if made is not None:
        return made
    return estimate_runs(SingleRun(core, y0, t0, report), [measured_on], opts, t0, t1, [answer], full, engine=False)[0]


def estimate_runs(run: Runner, cores: list, opts, t0: float, t1: float, answers: list, full: bool = False,
                  companions: dict | None = None, engine: bool = True) -> list:
    """Each answer's :class:`Estimate` (None for a failed or empty run, which estimates nothing):
    over a window (``full=False``) or the whole span (``full=True``); ``engine=False``: a single
    run's one engine call was tried already and left it to the general path."""
    if engine and type(run) is SingleRun and len(answers) == 1:
        made_here = _single_run_estimate(run.core, run.y0, run.t0, run.report, cores[0], opts, t1, answers[0], full,
                                         companions)
        if made_here is not None:
            return [made_here]
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
    if type(run) is EnsembleRun:  # measured in the engine where it can; the others below
        for m, e in _ensemble_estimates(run, cores, opts, t0, t1, answers, members, full, companions).items():
            made[m] = e
        members = [m for m in members if made[m] is None]
        if not members:
            return made
    crossings = {} if full else {m: t for m in members
                                 if (t := crossing(cores[m], answers[m], t0 + 0.5 * WINDOW * (t1 - t0))) is not None}
    few = [] if full else [m for m in members if m not in crossings and
                           math.isfinite(_core.companion_step_limit(answers[m], t0))]
    if full or crossings or few:  # the whole span: asked, or where a window cannot see the error's course
        spanned = members if full else list(crossings) + few
        for m, e in zip(spanned, span_estimates(run, cores, opts, t0, answers, spanned, companions)):
            if m in crossings:
                e.basis = (f"the run crosses a separatrix at t = {crossings[m]:.6g}, after the first half of the window, "
                           f"where its error grows faster than the window shows: {e.basis}")
            elif m in few:
                e.basis = (f"the run took {answers[m].stats.steps} steps, set by its first step and the span's end "
                           f"rather than its tolerance: its error lies inside them, where a window does not see it; "
                           f"{e.basis}")
            made[m] = e
        members = [m for m in members if m not in spanned]
        if not members:
            return made
    sub = run if members == list(range(len(answers))) else \
        lambda o, t, ms: run(o, t, [members[j] for j in ms])  # noqa: E731  (members renumbered)
    estimates = window_estimates(sub, [cores[m] for m in members], opts, t0, t1,
                                 [float(answers[m].t_last) for m in members],
                                 answers=[answers[m] for m in members])
    for m, e in zip(members, estimates):
        made[m] = e
    return made


