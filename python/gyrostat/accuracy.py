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
  invariants, quadratic growth of a phase error whose frequency error itself drifts), is the
  estimate. Cost: ~0.3× the run (dop853), ``error_estimate=False`` turns it off. A run that
  crosses a separatrix of its model after the first half of the window (the sign of the model's
  ``separatrix``, declared in C++, changes: the body's rotation moves to another axis) is measured
  over the whole span instead, as with ``"full"``: the error jumps at the crossing, which the
  window's growth cannot foresee (it read 0.007–0.024× the true error on a viscous cavity that
  crosses at 57 % of its span).
* ``error_estimate="full"``: the companion run at the tighter tolerances covers the whole span,
  compared at every output time (cost: one more run, a little dearer than the run itself).
* **accuracy given**: :mod:`gyrostat.contract` chooses the tolerances and measures the answer with
  the functions here.
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
SAMPLES = 201
"""Window and probe compare their runs at this many evenly spaced times."""
WINDOW_TIMES = 16
"""The window compares the run's own output times when it holds at least this many of them."""
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


def grow(last: float, half: float, end: float, middle: float, far: float, least: float = 1.0) -> tuple[float, float]:
    """A difference's running maximum over a window (``last`` at its end, ``half`` at its middle
    output time), grown to the horizon as t^k, k fitted over the window's second half and kept
    within [least, 2]; (value, k). ``end``, ``middle``, ``far``: the distances from t0 of the window's
    end, its middle output time and the horizon (a backward run grows the same way)."""
    if far <= end or last == 0.0:
        return last, 1.0
    k = 1.0 if half <= 0 else min(2.0, max(least, math.log(last / half) / math.log(end / middle)))
    return last * (far / end) ** k, k


def running_maxima(made: np.ndarray) -> tuple[list[float], list[float]]:
    """Each row's maximum over all its columns and over the first half (to the middle column
    included): the running maximum at the end and at the middle of the window (NaN stays NaN)."""
    middle = made.shape[1] // 2
    return made.max(axis=1).tolist(), made[:, :middle + 1].max(axis=1).tolist()


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
    companion runs. ``to_horizon=False``: the error over the window itself, not grown to the horizon."""
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
    companion, gain, what = tighter(copy_options(opts, grid), fresh=True)
    if not math.isfinite(gain):
        return [Estimate(math.nan, {}, f"no estimate: compared with {what}") for _ in cores]
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
        per, ks = {}, []
        grows = to_horizon and abs(horizons[i] - t0) > abs(window - t0)
        names, made_apart = apart(b, a, core, slice(None), inside)
        lasts, halves = running_maxima(made_apart)
        end, middle, far = abs(grid[-1] - t0), abs(grid[len(grid) // 2] - t0), abs(horizons[i] - t0)
        for name, last, half in zip(names, lasts, halves):
            value, k = grow(last * gain, half * gain, end, middle, far) if grows else (last * gain, 1.0)
            per[name] = max(value * (WINDOW_SAFETY if grows else 1.0), FLOOR)
            ks.append(k)
        growth = (f"grown as t^{max(ks):.2g} to t = {horizons[i]:.6g}, times {WINDOW_SAFETY:g}" if grows
                  else "over the whole run" if abs(horizons[i] - t0) <= abs(window - t0) else "not grown")
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
    shared = all(same_times(np.asarray(answers[m].t, float), times) for m in members[1:])
    grid = times if shared else np.unique(np.concatenate([np.asarray(answers[m].t, float) for m in members]))
    companion, gain, what = tighter(copy_options(opts, grid), fresh=True)
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
        if same_times(mine, theirs):  # the companion records the answer's own times (as a rule)
            keep_mine = keep_theirs = slice(None)
            compared = len(mine)
        else:
            keep_mine, keep_theirs = np.isin(mine, theirs), np.isin(theirs, mine)
            compared = int(keep_mine.sum())
        names, made_apart = apart(answer, other, cores[m], keep_mine, keep_theirs)
        largest = made_apart.max(axis=1).tolist() if made_apart.shape[1] else [math.nan] * len(names)
        per = {name: max(d * gain, FLOOR) if not math.isnan(d) else math.nan for name, d in zip(names, largest)}
        made.append(Estimate(max(per.values()), per,
                             f"measured at {compared} output times over the whole run against a run "
                             f"with {what} (difference x {gain:.3g})"))
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


