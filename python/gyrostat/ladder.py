"""The model ladder: a scene gets no more model than it needs.

Each family has rungs, cheapest first (its scene kind's ``ladder``, listed in its family module
under ``gyrostat/families/``); the last is the scene's most complete model (the *top*).

``model = "auto"`` with a requested accuracy (``integration.accuracy``: the largest relative error
accepted on the quantities the scene's outputs need) takes the cheapest rung that

1. can give those quantities at all (an averaged model gives no ω(t), only its slow variables);
2. has its assumptions holding at the start (:mod:`gyrostat.validity`);
3. has a *measured* error estimate below the accuracy (:func:`probe`): the rung and the top are both run
   over a probe window at the start (20 periods of the fast motion the rung averages or reduces, at most
   a twentieth of the span), their difference in the compared quantities gives the O(ε) constant (the
   largest difference over the window, relative to the quantities' size) and its growth (the largest
   difference over the window's second half minus the first's, per unit time), extrapolated to the
   horizon linearly (the growth law of first-order averaging over times ~1/ε) for slow variables, and
   quadratically where ω(t) itself is compared (its phase error integrates the slow error), times 2.

The chosen lower rung then runs with terminal events on its assumptions (:class:`Watch`): where one
stops holding (r near zero, the nutation period long against the slow time, k² near 1), the run
continues on the top from the state lifted back (C++ ``full_state``: the slow variables at the fast
phase ``integration.phase``, default 0) and comes back down when the assumption holds again with a
margin (hysteresis). The run is one :class:`gyrostat.Solution` joined from its pieces in the lower
rung's variables (:meth:`gyrostat.Solution.join`); the report lists every switch with its time
and reason. The closed form needs no estimate (it is exact to
rounding). The integrator is part of the choice too: ``method = "auto"`` (the scenes' default) picks
DOP853 or CVODE BDF by the stiffness measured along the run.
"""

from __future__ import annotations

import copy
import dataclasses
import io
import math
import pickle
import time
import warnings
from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np

from gyrostat import _core
from gyrostat.events import Event, labels, terminal_count, to_core
from gyrostat.solution import AccuracyWarning, Solution
from gyrostat.solve import make_options, solve
from gyrostat.assumptions import Assumption

ACCURACY = 1e-3
"""Default of ``integration.accuracy``: the relative error accepted on the compared quantities."""
PROBE_PERIODS = 20
"""The probe covers this many periods of the fast motion."""
PROBE_FRACTION = 0.05
"""... and at most this fraction of the span (so that it costs at most that much of a full run)."""
SAFETY = 2.0
"""The measured estimate is multiplied by this before it is compared with the accuracy."""
MAX_SWITCHES = 100
"""A run that switches more often than this stays on the top rung (the assumption flickers)."""


# ------------------------------------------------------------------------------------ pieces
@dataclass(frozen=True)
class Watch:
    """An assumption of a lower rung watched along its run: the model output ``output`` must stay
    below ``limit``; after a switch up, the run comes back down when it falls below ``back``."""

    output: str
    limit: float
    back: float
    statement: str
    scales_error: bool = False
    """The output is the small parameter of the rung's error (slow rate / fast frequency, the
    adiabaticity N): its limit is lowered so that the error c·value stays within the accuracy."""

    def ratio(self, value: float) -> float:
        """0 at ``back``, 1 at ``limit``."""
        return (value - self.back) / (self.limit - self.back)


@dataclass
class Rung:
    """One model of a family's ladder: the model, its initial state, and how it is compared."""

    name: str
    model: object
    y0: np.ndarray
    description: str
    compare: Callable[[Solution], np.ndarray] | None = None
    """The quantities compared with the top, (n, m), from a solution of this rung."""
    blocked: str = ""
    """Why this rung cannot answer the scene ("" when it can)."""
    fast_period: float = math.inf
    """The period of the motion the rung averages or reduces (sets the probe's length)."""
    watches: tuple[Watch, ...] = ()
    """Assumptions watched along the run (empty: nothing to switch on)."""
    start_checks: Callable[[], list[Assumption]] = lambda: []
    """The rung's assumptions at the initial state."""
    basis: str = ""
    """What the error estimate rests on, besides the probe."""
    small: float | None = None
    """The small parameter of a reduction: the probe reports its constant, measured / small."""
    exact: bool = False
    """The reduction is exact (no model error): the probe's difference is the integrators' own."""
    phase_compared: bool = False
    """The compared quantities include the fast motion itself (ω(t), not only slow variables):
    its phase error is the integral of a frequency error that grows like the slow one, so the
    error grows quadratically, not linearly."""
    run: str = "full"
    """The name of the scene run this rung's solution stands for (the name its kind's analysis
    and plots look for)."""
    complete: Callable[[np.ndarray], np.ndarray] | None = None
    """(The top rung) its full state from the ω a lower rung lifts to where the run switches up,
    when the top carries more (a moving mass's displacement and velocity). None: the model's
    ``initial_state`` (the identity attitude, say)."""
    fast_compare: Callable[[Solution], np.ndarray] | None = None
    """ω(t) as this rung gives it (an averaged rung carrying the fast phase: the free motion at
    that phase), (n, 3): the probe compares it with the top's ω (:func:`rates`) and extrapolates
    its error quadratically (the phase's error integrates the frequency's); reported beside the
    estimate (``fast_motion``), not used for the choice, which rests on ``compare``."""


@dataclass
class Estimate:
    """A measured error estimate of a rung against the top, extrapolated to the horizon."""

    value: float
    measured: float
    growth: float
    probe: tuple[float, float]
    seconds: dict[str, float]
    basis: str
    fast: Estimate | None = None
    """The error of ω(t) at the phase the rung carries (:attr:`Rung.fast_compare`), when it carries one."""

    def as_dict(self) -> dict:
        entry = {"value": self.value, "measured_in_probe": self.measured, "growth_per_unit_time": self.growth,
                 "probe": list(self.probe), "probe_seconds": self.seconds, "basis": self.basis}
        if self.fast is not None:
            entry["fast_motion"] = self.fast.as_dict()
        return entry


@dataclass
class Choice:
    """The ladder's decision for a scene: each rung considered, why it was taken or not."""

    rungs: list[Rung]
    chosen: Rung
    accuracy: float
    entries: list[dict] = field(default_factory=list)
    estimate: Estimate | None = None
    reused: bool = False
    """The choice was made for an identical scene solved before (no probe ran this time)."""

    @property
    def summary(self) -> str:
        if self.estimate is None:
            error = "exact to rounding" if self.chosen.name == "closed_form" else "reference model"
        else:
            error = f"estimated error {self.estimate.value:.2g} <= {self.accuracy:g}"
        return f"model {self.chosen.name} ({error})"

    def report(self) -> dict:
        return {"accuracy": self.accuracy, "chosen": self.chosen.name, "summary": self.summary,
                "estimate": self.estimate.as_dict() if self.estimate else None, "rungs": self.entries,
                "reused": self.reused}


# ------------------------------------------------------------------------------------ compared quantities
def rates(solution) -> np.ndarray:
    """ω = (p, q, r): (n, 3)."""
    return np.column_stack([solution["p"], solution["q"], solution["r"]])


# ------------------------------------------------------------------------------------ the probe
PROBE_SAMPLES = 201
"""The probe compares the rungs at this many evenly spaced times of its window."""
_PROBED = ("method", "rtol", "atol", "max_steps")
_DEFAULT = _core.Options()


def _solve(rung: Rung, y0, span, options: dict, t_eval=None, events=None) -> Solution:
    kept = {k: v for k, v in options.items() if k in _PROBED}
    return solve(rung.model, y0, span, **kept, t_eval=t_eval, events=events, check_validity=False, progress=False)


def _run_on_engine(rung: Rung, y0, span, opts) -> Solution:
    """A probe's run: the engine called once with Options made beforehand (the checks of
    :func:`gyrostat.solve` were made on the scene's own runs)."""
    return Solution(_core.solve(rung.model._core, np.asarray(y0, float), float(span[0]), float(span[1]), opts, None),
                    rung.model)


def _segment(rung: Rung, y0, span, opts) -> Solution:
    """A piece of a switching run: the engine called with the rung's Options made once; the run's
    doubts warned about as :func:`gyrostat.solve` warns them."""
    solution = _run_on_engine(rung, y0, span, opts)
    for doubt in solution.accuracy_warnings:
        warnings.warn(doubt, AccuracyWarning, stacklevel=3)
    return solution


def probe(rung: Rung, top: Rung, span: tuple[float, float], options: dict) -> Estimate:
    """The rung's error against the top, measured at the start and extrapolated to the horizon.

    Both run over [t0, t0 + T], T = min(20 fast periods, span/20), compared at 201 times:
    d(t) = |Δ(compared quantities)| / max |compared quantities of the top|. The estimate at the
    horizon t1 is SAFETY · (max(max d, floor) + g (t1 − t0 − T)), g = max(0, max d(second half) −
    max d(first half)) / (T/2): the oscillating O(ε) part, plus the drift measured over the window,
    grown linearly (quadratically, g (t² / 1.5T), where ω(t) itself is compared). The floor
    rtol·√(fast periods in the span) is the integrators' own error (per-period local errors adding
    up like a random walk), which the comparison with the top cannot resolve below."""
    t0, t1 = span
    window = min(PROBE_PERIODS * rung.fast_period, PROBE_FRACTION * (t1 - t0))
    times = np.linspace(t0, t0 + window, PROBE_SAMPLES)
    opts = make_options(**{k: v for k, v in options.items() if k in _PROBED}, t_eval=times)
    started = time.perf_counter()
    upper = _run_on_engine(top, top.y0, (t0, t0 + window), opts)
    middle = time.perf_counter()
    lower = _run_on_engine(rung, rung.y0, (t0, t0 + window), opts)
    ended = time.perf_counter()
    return _estimate(rung, top, span, options, window, upper, lower, {top.name: middle - started,
                                                                       rung.name: ended - middle})


def _estimate(rung: Rung, top: Rung, span, options: dict, window: float, upper: Solution, lower: Solution,
              seconds: dict) -> Estimate:
    """The estimate from the two runs of a probe over [t0, t0 + window] at PROBE_SAMPLES times."""
    t0, t1 = span
    samples = PROBE_SAMPLES
    if not (upper.success and lower.success) or len(upper) != samples or len(lower) != samples:
        failed = upper if not upper.success else lower
        return Estimate(math.inf, math.inf, math.inf, (t0, t0 + window), seconds,
                        f"the probe failed ({failed.status}: {failed.message})")

    def extrapolated(reference, values, quadratic: bool, law: str, basis: str, small: float | None = None) -> Estimate:
        reference = np.asarray(reference, float)
        apart = reference - values
        scale = float(np.sqrt((reference * reference).sum(axis=1)).max()) or 1.0  # the rows' norms, as np.linalg.norm
        difference = np.sqrt((apart * apart).sum(axis=1)) / scale
        measured = float(difference.max())
        half = samples // 2
        growth = max(0.0, float(difference[half:].max() - difference[:half].max())) / (0.5 * window)
        rest = max(0.0, t1 - t0 - window)
        # d = c t²: the halves' maxima differ by (3/4) c T², so growth = 1.5 c T and c = growth / (1.5 T)
        # the integrators' own error as a floor: per-period local errors ~ rtol adding up like a random walk
        periods = (t1 - t0) / rung.fast_period
        floor = float(options.get("rtol", _DEFAULT.rtol)) * math.sqrt(max(periods, 1.0))
        value = SAFETY * (max(measured, floor) + (growth * (rest + rest**2 / (1.5 * window)) if quadratic
                                                 else growth * rest))
        text = (f"probe over [{t0:g}, {t0 + window:g}] ({window / rung.fast_period:.3g} fast periods): largest relative "
                f"difference {measured:.3g} (at least rtol x sqrt(fast periods) = {floor:.3g}, the integrators' own), "
                f"growth {growth:.3g} per unit time, extrapolated {law} to t = {t1:g}, times {SAFETY:g}" + basis
                + (f"; constant of the O(small) error: {measured / small:.3g}" if small else ""))
        return Estimate(value, measured, growth, (t0, t0 + window), seconds, text)

    law = ("quadratically (the fast phase is compared)" if rung.phase_compared else
           "linearly (an exact reduction: the difference is the integrators' own, and grows as theirs)" if rung.exact
           else "linearly")
    estimate = extrapolated(top.compare(upper), rung.compare(lower), rung.phase_compared, law,
                            f"; {rung.basis}" if rung.basis else "", rung.small)
    if rung.fast_compare is not None:
        estimate.fast = extrapolated(rates(upper), rung.fast_compare(lower), True,
                                     "quadratically (the phase's error integrates the frequency's)",
                                     "; omega at the carried phase against the top's: reported, not used for the choice")
    return estimate


CACHE_SIZE = 64
"""The choices of this many scenes are kept (:func:`scene_key`): solving a scene again skips its probes."""
_CHOICES: dict[bytes, Choice] = {}


class _PlainPickler(pickle.Pickler):
    """Pickles numbers, strings, booleans, lists, tuples, tables and NumPy arrays and scalars (their
    bytes: every digit), and refuses anything else (a Python callable, say) with TypeError."""

    def reducer_override(self, value):
        if isinstance(value, (np.ndarray, np.generic)) and value.dtype != object:
            return _plain_array, (value.dtype.str, np.shape(value), value.tobytes())
        if value is _plain_array:
            return NotImplemented  # (by its name)
        raise TypeError(type(value).__name__)


def _plain_array(dtype: str, shape: tuple, data: bytes) -> np.ndarray:
    """The array a scene key holds (_PlainPickler)."""
    return np.frombuffer(data, dtype=dtype).reshape(shape)


def scene_key(doc: dict) -> bytes | None:
    """The scene document (defaults filled in) as bytes: equal documents give equal rungs, models
    and probes, hence the same choice (a table written in another key order is another key: it is
    probed once more). None for a document holding anything but numbers, strings, booleans, lists,
    tables and NumPy arrays (a Python callable, say): such a scene is probed every time. (A
    pickle: ~4 µs for a paper's scene, where sorted JSON took ~30.)"""
    buffer = io.BytesIO()
    try:
        _PlainPickler(buffer, protocol=pickle.HIGHEST_PROTOCOL).dump(doc)
    except (TypeError, pickle.PicklingError):
        return None
    return buffer.getvalue()


def choose(rungs: list[Rung], span: tuple[float, float], options: dict, accuracy: float = ACCURACY,
           key: bytes | None = None) -> Choice:
    """The cheapest rung that can answer, whose assumptions hold at the start and whose measured
    estimate is at most ``accuracy``; the top when none is.

    With ``key`` (:func:`scene_key` of the scene that made the rungs) the choice of the last
    :data:`CACHE_SIZE` scenes is kept: the same scene solved again reuses it, probes and all
    (``Choice.reused``; its report says so), instead of probing again. The choice is a function
    of the scene alone (its rungs, span, options and accuracy all come from it), so it is the
    same choice."""
    if key is not None:
        cached = _CHOICES.get(key)
        if cached is not None:
            return dataclasses.replace(cached, entries=_copied(cached.entries), reused=True)
        made = choose(rungs, span, options, accuracy)
        if len(_CHOICES) >= CACHE_SIZE:
            _CHOICES.pop(next(iter(_CHOICES)))
        _CHOICES[key] = made
        return made
    rungs = list(rungs)
    top = rungs[-1]
    entries: list[dict] = []
    for index, rung in enumerate(rungs[:-1]):
        entry = {"rung": rung.name, "model": rung.description}
        entries.append(entry)
        if rung.blocked:
            entry.update(taken=False, reason=rung.blocked)
            continue
        broken = [a for a in rung.start_checks() if not a.holds]
        if broken:
            entry.update(taken=False, reason="assumption broken at the start: " + "; ".join(map(str, broken)))
            continue
        if rung.name == "closed_form":
            entry.update(taken=True, reason="nothing perturbs the body: the exact flow needs no integration",
                         estimate=None)
            return Choice(rungs, rung, accuracy, entries + _rest(rungs, rung))
        t0, t1 = span
        if not math.isfinite(rung.fast_period) or PROBE_PERIODS * rung.fast_period > PROBE_FRACTION * (t1 - t0):
            entry.update(taken=False, reason=(
                f"the span holds {(t1 - t0) / rung.fast_period:.3g} fast periods: too few for the averaging to pay "
                f"(a probe of {PROBE_PERIODS} periods would cost more than {PROBE_FRACTION:.0%} of the full run)"))
            continue
        estimate = probe(rung, top, span, options)
        refusal = "" if estimate.value <= accuracy else f"estimated error {estimate.value:.3g} > accuracy {accuracy:g}"
        if not refusal:
            rung, refusal = _fit_watches(rung, estimate, accuracy)
            rungs[index] = rung
        entry["estimate"] = estimate.as_dict()
        if refusal:
            entry.update(taken=False, reason=refusal)
            continue
        if estimate.value <= accuracy:
            entry.update(taken=True, reason=f"estimated error {estimate.value:.3g} <= accuracy {accuracy:g}")
            return Choice(rungs, rung, accuracy, entries + _rest(rungs, rung), estimate)
        entry.update(taken=False, reason=f"estimated error {estimate.value:.3g} > accuracy {accuracy:g}")
    entries.append({"rung": top.name, "model": top.description, "taken": True,
                    "reason": "the scene's most complete model (the reference of the rungs below)"})
    return Choice(rungs, top, accuracy, entries)


def _copied(value):
    """A deep copy of a choice's entries (dicts, lists and numbers, as :func:`choose` makes them),
    without copy.deepcopy's bookkeeping."""
    if isinstance(value, dict):
        return {k: _copied(v) for k, v in value.items()}
    if isinstance(value, list):
        return [_copied(v) for v in value]
    return copy.deepcopy(value) if not isinstance(value, (str, int, float, bool, type(None), tuple)) else value


def _fit_watches(rung: Rung, estimate: Estimate, accuracy: float) -> tuple[Rung, str]:
    """The rung with its error-scaling watch fitted to the accuracy. Its error is c·x, x the
    watched small parameter (slow/fast, N) and c measured by the probe (its largest difference
    over x at the start). At a switch up the error is at most 3c·x: c·x carried by the lower
    rung, and up to 2c·x from lifting at a fixed phase instead of the true one (the slow
    variables' oscillation c·x·f(φ) differs by at most twice its amplitude). The run therefore
    leaves the rung where SAFETY·3c·x reaches the accuracy: limit = min(the assumption's own
    limit, accuracy / (3 SAFETY c)), and comes back below limit/2; the estimate covers it,
    SAFETY·3c·limit. ("" or why the rung cannot hold the accuracy even at the start.)"""
    watches = list(rung.watches)
    scaling = [i for i, w in enumerate(watches) if w.scales_error]
    if not scaling or not math.isfinite(estimate.measured):
        return rung, ""
    i = scaling[0]
    watch = watches[i]
    names = list(rung.model.output_names)
    start = float(rung.model._core.outputs_at(estimate.probe[0], np.asarray(rung.y0, float))[names.index(watch.output)])
    if not start > 0:
        return rung, ""
    c = estimate.measured / start
    limit = min(watch.limit, accuracy / (3.0 * SAFETY * c)) if c > 0 else watch.limit
    if start >= limit:
        return rung, (f"the measured error constant c = {c:.3g} of the O({watch.output}) error needs {watch.output} <= "
                      f"{limit:.3g} for the accuracy {accuracy:g}; it is {start:.3g} at the start")
    watches[i] = dataclasses.replace(watch, limit=limit, back=0.5 * limit)
    estimate.value = max(estimate.value, 3.0 * SAFETY * c * limit)
    estimate.basis += (f"; error = c {watch.output} with c = {c:.3g} (measured): the run switches up where "
                       f"{watch.output} reaches {limit:.3g} and back below {0.5 * limit:.3g}, an error of at most "
                       f"{SAFETY:g} x 3c x {limit:.3g} = {3.0 * SAFETY * c * limit:.3g} there")
    return dataclasses.replace(rung, watches=tuple(watches)), ""


def _rest(rungs: list[Rung], chosen: Rung) -> list[dict]:
    above = rungs[rungs.index(chosen) + 1:]
    return [{"rung": r.name, "model": r.description, "taken": False, "reason": "not needed"} for r in above]


# ------------------------------------------------------------------------------------ switching
class _PieceEvents:
    """The caller's events (the scene's [[events]]) over a run that switches models: each one given
    by quantity (gyrostat.events.Event) is located on every piece whose model has that quantity
    (the lower rung's and the top's name theirs alike: r, a, ...); the crossings are kept in the
    lower rung's variables (a top's state mapped down), a terminal one's count runs across the
    pieces and ends the whole run. A piece whose model lacks the quantity is named in the run's
    notes. An event that reads one model's state (a callable, an engine event) cannot be carried
    across models: refused by name."""

    def __init__(self, events: list, lower: Rung):
        for k, event in enumerate(events):
            if not isinstance(event, Event):
                raise ValueError(f"event {k} ({type(event).__name__}): a run that may switch models locates events "
                                 "given by quantity (gyrostat.events.Event) on each model's pieces; this one reads one "
                                 "model's state: give it as an Event, or set the scene's model to one rung")
        self.events, self.lower = list(events), lower
        self.names = labels(self.events)
        self.counts = [terminal_count(e.terminal, e.quantity) for e in self.events]
        self.seen = [0] * len(self.events)
        self.times: list[list] = [[] for _ in self.events]
        self.states: list[list] = [[] for _ in self.events]
        self.notes: list[str] = []
        self.terminal: int | None = None
        self._which: list[int] = []

    def __bool__(self) -> bool:
        return bool(self.events)

    def on(self, rung: Rung) -> list:
        """The engine events of this piece (on ``rung``'s model), terminal counts net of the
        crossings seen on the pieces before."""
        if not self.events:
            return []
        core = rung.model._core
        states, outputs = list(core.state_names), list(core.output_names)
        made, self._which = [], []
        for k, event in enumerate(self.events):
            if event.quantity in states:
                kind, index = "state", states.index(event.quantity)
            elif event.quantity in outputs:
                kind, index = "output", outputs.index(event.quantity)
            else:
                continue
            left = self.counts[k] - self.seen[k] if self.counts[k] else 0
            made.append(_core.Event(kind, index, float(event.value), event.direction, left, self.names[k]))
            self._which.append(k)
        return made

    def record(self, rung: Rung, solution: Solution, first: int) -> bool:
        """The crossings of the piece just run (its events from index ``first`` on are the
        caller's, in the order :meth:`on` made them); True when a terminal one ended the run."""
        if not self.events:
            return False
        for k, event in enumerate(self.events):
            if k not in self._which and len(solution):
                self.notes.append(f"event {self.names[k]!r}: {event.quantity!r} is not a quantity of the {rung.name} "
                                  f"model: not located over t in [{solution.t[0]:.6g}, {solution.t_last:.6g}]")
        for j, k in enumerate(self._which):
            times = np.asarray(solution.t_events[first + j], float)
            if not len(times):
                continue
            states = np.asarray(solution.y_events[first + j], float).reshape(len(times), -1)
            if rung is not self.lower:
                states = np.asarray(self.lower.model._core.initial_states(states))
            self.times[k].append(times)
            self.states[k].append(states)
            self.seen[k] += len(times)
        ended = solution.terminal_event
        if ended is not None and ended >= first:
            self.terminal = self._which[ended - first]
            return True
        return False

    def joined(self, dim: int) -> dict:
        """What :meth:`gyrostat.Solution.join` takes of them."""
        return {"event_names": tuple(self.names),
                "t_events": [np.concatenate(t) if t else np.zeros(0) for t in self.times],
                "y_events": [np.vstack(y) if y else np.zeros((0, dim)) for y in self.states],
                "terminal_event": -1 if self.terminal is None else self.terminal, "notes": tuple(self.notes)}


def _join(lower: Rung, segments: list[tuple[str, Solution]], switches: list[tuple],
          wanted: _PieceEvents | None = None) -> Solution:
    """A run that went up and down the ladder as one Solution in the lower rung's variables: the
    pieces run on the top are mapped down by the lower model's own projection (C++
    ``initial_state``) and its outputs evaluated there (C++ ``outputs_at``); ``rung`` is 0 where
    the lower rung ran, 1 on the top."""
    core = lower.model._core
    parts = []
    for name, sol in segments:
        if not len(sol):
            continue
        if name == lower.name:  # the lower model's own run: its outputs' matrix, in output_names' order
            parts.append((sol.t, sol.y, sol._result.outputs, 0))
        else:
            projected = core.initial_states(sol.y)
            parts.append((sol.t, projected, core.outputs_along(sol.t, projected), 1))
    name, last = segments[-1]
    y_last = last.y_last if name == lower.name else np.asarray(core.initial_state(last.y_last))
    events = wanted.joined(len(core.state_names)) if wanted else {}
    return Solution.join(lower.model, segments, parts, switches, y_last, **events)


_SWITCH_EVENTS: dict[int, tuple] = {}


def _switch_events(lower: Rung, top: Rung) -> tuple[list, list]:
    """The engine events of a switching run, as made for the rungs of a choice (kept with it: a
    choice reused solves its scene again with the same events; they are read-only): on the lower
    rung, a watch reaching its limit; on the top, :func:`_back_down`."""
    kept = _SWITCH_EVENTS.get(id(lower))
    if kept is not None and kept[0] is lower and kept[1] is top:
        return kept[2], kept[3]
    fails = [Event(w.output, w.limit, 1, True, w.statement) for w in lower.watches]
    made = []
    for rung, events in ((lower, fails), (top, [_back_down(lower)])):
        core = rung.model._core
        made.append(to_core(events, list(core.state_names), list(core.output_names)))
    if len(_SWITCH_EVENTS) >= 2 * CACHE_SIZE:
        _SWITCH_EVENTS.pop(next(iter(_SWITCH_EVENTS)))
    _SWITCH_EVENTS[id(lower)] = (lower, top, made[0], made[1])  # (the rungs held: their ids stay theirs)
    return made[0], made[1]


def _back_down(lower: Rung):
    """The terminal event of a run on the top rung: every watched assumption of ``lower`` holds
    again with margin. An engine event evaluated in C++ (the lower model's ``watch_event``: the
    largest :meth:`Watch.ratio` of its outputs at the state mapped down, no call into Python) once
    per fast period of the lower rung: the watched ratios change on the slow time scale, and each
    evaluation maps the state down and evaluates the averaged rates (for the triaxial rung with a
    torque averaged by quadrature, ~10 µs: at every step it made the top's run ~15× slower). Or
    :func:`_trouble`, the same g in Python at every step, for watches whose ``ratio`` is their own."""
    core = lower.model._core
    if all(type(w).ratio is Watch.ratio for w in lower.watches) and hasattr(core, "watch_event"):
        names = list(core.output_names)
        interval = lower.fast_period if math.isfinite(lower.fast_period) else 0.0
        return core.watch_event([names.index(w.output) for w in lower.watches], [w.back for w in lower.watches],
                                [w.limit for w in lower.watches], "assumptions hold again", -1, 1, interval)
    return _trouble(lower)


def _trouble(lower: Rung) -> Callable[[float, np.ndarray], float]:
    """g(t, y) on the top rung: the largest Watch.ratio of the lower model's outputs at the
    projected state, minus 0 (so g falls through 0 where every assumption holds with margin)."""
    core = lower.model._core
    names = list(core.output_names)
    watched = [(names.index(w.output), w.ratio) for w in lower.watches]
    outputs_at = core.outputs_at

    def back_down(t, y):  # called at every step of the top's run (y: the engine's float array)
        values = outputs_at(t, y)
        ratios = [ratio(float(values[i])) for i, ratio in watched]
        return max(ratios) if all(map(math.isfinite, ratios)) else 1.0  # as watch_event: no margin on a NaN

    back_down.direction = -1
    back_down.terminal = True
    back_down.__name__ = "assumptions hold again"
    return back_down


def _lifted(rung: Rung, top: Rung, y, phase: float) -> np.ndarray:
    """The top's state from the lower rung's state y: its lift at the fast phase (C++
    ``full_state``), completed where the top carries more (:attr:`Rung.complete`)."""
    state = np.asarray(rung.model._core.full_state(np.asarray(y, float), float(phase)))
    if len(state) < top.model.dim:
        state = np.asarray(top.complete(state) if top.complete else top.model.initial_state(state))
    return state


def run(choice: Choice, span: tuple[float, float], options: dict, phase: float = 0.0, progress=None):
    """Solves the chosen rung over the span; a lower rung with watched assumptions switches up to
    the top where one stops holding and back down where all hold again. Returns a Solution (one
    joined from its pieces when the run switched: :meth:`gyrostat.Solution.join`)."""
    rung, top = choice.chosen, choice.rungs[-1]
    t0, t1 = span
    kept = {k: v for k, v in options.items() if k not in ("n_out", "t_eval", "events")}
    n_out = int(options.get("n_out", _DEFAULT.n_out))
    extra_events = list(options.get("events", []))
    if rung is top or not rung.watches:  # one run, asked for as the scene asks for it (n_out: the same times)
        timing = {"t_eval": options["t_eval"]} if options.get("t_eval") is not None else {"n_out": n_out}
        names = set(rung.model.state_names) | set(rung.model.output_names)
        missing = [e for e in extra_events if isinstance(e, Event) and e.quantity not in names]
        solution = solve(rung.model, rung.y0, span, **kept, **timing,
                         events=[e for e in extra_events if not any(e is m for m in missing)] or None,
                         check_validity=False, progress=progress if progress is not None else False)
        solution.notes += [f"event {e.label!r}: {e.quantity!r} is not a quantity of the {rung.name} model (the "
                           f"ladder's choice): not located" for e in missing]
        return solution
    grid = np.asarray(options["t_eval"], float) if options.get("t_eval") is not None else np.linspace(t0, t1, n_out)
    # each rung's options made once per run, its events included (each segment sets its output times)
    opts = {False: make_options(**kept), True: make_options(**kept)}
    switch_events = _switch_events(rung, top)
    opts[False].events, opts[True].events = switch_events
    wanted = _PieceEvents(extra_events, rung)  # the caller's events, located on every piece
    segments: list[tuple[str, Solution]] = []
    switches: list[tuple] = []
    t, state, on_top = t0, rung.y0, False
    while True:
        times = grid[(grid > t) | ((grid == t) & (not segments))]
        opts[on_top].t_eval = times if len(times) else np.array([t1])
        current = top if on_top else rung
        own = wanted.on(current)
        if wanted:
            opts[on_top].events = switch_events[on_top] + own
        sol = _segment(current, state, (t, t1), opts[on_top])
        segments.append((current.name, sol))
        ended_by_caller = wanted.record(current, sol, len(switch_events[on_top]))
        if not sol.success or sol.terminal_event is None or sol.t_last >= t1 or ended_by_caller:
            break
        t = float(sol.t_last)
        if on_top:
            state = np.asarray(rung.model._core.initial_state(np.asarray(sol.y_last)))
            switches.append((t, top.name, rung.name, "every watched assumption holds again with margin"))
        else:
            watch = rung.watches[sol.terminal_event]
            state = _lifted(rung, top, sol.y_last, phase)
            switches.append((t, rung.name, top.name, f"{watch.statement}: {watch.output} reached {watch.limit:g}"))
        on_top = not on_top
        if len(switches) > MAX_SWITCHES:
            opts[True].t_eval = grid[grid > t] if np.any(grid > t) else np.array([t1])
            opts[True].events = wanted.on(top)
            rest = _segment(top, state if on_top else _lifted(rung, top, state, phase), (t, t1), opts[True])
            segments.append((top.name, rest))
            wanted.record(top, rest, 0)
            switches.append((t, rung.name, top.name, f"more than {MAX_SWITCHES} switches: stays on the top"))
            break
    if not switches and not wanted:
        return segments[0][1]
    return _join(rung, segments, switches, wanted)


# ------------------------------------------------------------------------------------ the chart
def measure(choice: Choice, span: tuple[float, float], options: dict) -> list[dict]:
    """Every rung that can answer, run over the whole span (switching where it would), timed, and
    its largest relative error in the compared quantities against the top at the output times:
    what the ladder chart draws, and for every rung that cannot answer a row with ``skipped``, the
    reason (the chart lists them). (The chart's cost: one run of every rung, the top included.)"""
    top = choice.rungs[-1]
    runs = {}
    skipped = []
    for rung in choice.rungs:
        if rung.blocked or rung.model is None:
            skipped.append({"rung": rung.name, "skipped": rung.blocked or "no model for this scene", "chosen": False})
            continue
        started = time.perf_counter()
        solution = run(Choice(choice.rungs, rung, choice.accuracy), span, options)
        runs[rung.name] = (time.perf_counter() - started, solution)
    seconds_top, reference = runs[top.name]
    expected = top.compare(reference)
    scale = float(np.max(np.linalg.norm(expected, axis=1))) or 1.0
    rows = []
    for rung in choice.rungs:
        if rung.name not in runs:
            continue
        seconds, solution = runs[rung.name]
        n = min(len(solution), len(reference))
        compare = rung.compare if rung.compare is not None else top.compare
        error = 0.0 if rung is top else float(np.max(np.linalg.norm(compare(solution)[:n] - expected[:n], axis=1))) / scale
        estimate = next((e.get("estimate") for e in choice.entries if e["rung"] == rung.name), None)
        rows.append({"rung": rung.name, "seconds": seconds, "error": error, "chosen": rung is choice.chosen,
                     "estimate": estimate["value"] if estimate else None, "steps": int(solution.stats["steps"]),
                     "switches": len(solution.switches), "reference": rung is top})
    return rows + skipped
