"""The chosen rung's run: terminal events on its assumptions, a switch up to the top where one
stops holding and back down when it holds again, the pieces joined into one
:class:`gyrostat.Solution` (:func:`run`); and every rung run over the span for the ladder chart
(:func:`measure`)."""

from __future__ import annotations

import math
import time
from collections.abc import Callable

import numpy as np

from gyrostat import _core
from gyrostat.accuracy import Estimate as RunEstimate
from gyrostat.events import Event, labels, terminal_count, to_core
from gyrostat.ladder.choosing import CACHE_SIZE
from gyrostat.ladder.probe import _DEFAULT, _segment
from gyrostat.ladder.rungs import MAX_SWITCHES, Choice, Rung, Watch
from gyrostat.solution import Solution

INTEGRATION_SHARE = 0.1
"""A lower rung's integration is asked for this share of the accuracy; the model's error takes the rest."""
from gyrostat.solve import make_options, solve


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
    if rung is not top and kept.get("accuracy") is not None:
        kept["accuracy"] = INTEGRATION_SHARE * kept["accuracy"]  # the rest is the model's own error
    n_out = int(options.get("n_out", _DEFAULT.n_out))
    extra_events = list(options.get("events", []))
    if rung is top or not rung.watches:  # one run, asked for as the scene asks for it (n_out: the same times)
        timing = {"t_eval": options["t_eval"]} if options.get("t_eval") is not None else {"n_out": n_out}
        names = set(rung.model.state_names) | set(rung.model.output_names)
        missing = [e for e in extra_events if isinstance(e, Event) and e.quantity not in names]
        solution = solve(rung.model, rung.y0, span, **kept, **timing, compare=rung.compare,
                         events=[e for e in extra_events if not any(e is m for m in missing)] or None,
                         check_validity=False, progress=progress if progress is not None else False)
        solution.notes += [f"event {e.label!r}: {e.quantity!r} is not a quantity of the {rung.name} model (the "
                           f"ladder's choice): not located" for e in missing]
        return solution
    kept.pop("accuracy", None)  # a switching run keeps the rungs' tolerances; its estimate is the model's
    dropped = kept.pop("sensitivities", None)  # (not carried across a switch: said in the run's notes below)
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
    made = segments[0][1] if not switches and not wanted else _join(rung, segments, switches, wanted)
    if dropped:
        made.notes.append(f"sensitivities {list(dropped)} not computed: a run that may switch between models (the "
                          f"{rung.name} rung watches its assumptions) carries none; give model = 'full' for them")
    return made


def run_estimate(choice: Choice, solution: Solution) -> Solution:
    """The chosen rung's run given its whole error: a lower rung's model error (the probe's measured
    estimate, extrapolated to the horizon) plus its integration's own estimate; the top's is its
    integration's. (A watch fitted to the accuracy bounds the error where the run switches up,
    SAFETY·3c·x at the limit: the basis states that bound, which is not a measurement; measured
    against the full model, the error at the switches was far below it.)"""
    rung, top, estimate = choice.chosen, choice.rungs[-1], choice.estimate
    if rung is top or estimate is None:
        return solution
    model = estimate.value
    words = f"the model's error {estimate.value:.3g} (the ladder's probe: {estimate.basis})"
    own = solution.estimate
    integration = own.value if own is not None and math.isfinite(own.value) else 0.0
    if own is not None:
        words += f"; plus the integration's {integration:.3g} ({own.basis})"
    per = {name: model + value for name, value in (own.per_quantity if own is not None else {}).items()}
    combined = RunEstimate(model + integration, per or {"compared": model}, words, choice.accuracy)
    if combined.value > choice.accuracy:
        combined.warning = (f"the measured error {combined.value:.3g} of the {rung.name} model exceeds the accuracy "
                            f"{choice.accuracy:g}: set the scene's model to the top rung ({top.name}) to meet it")
        solution.doubt(combined.warning)
    solution.estimate = combined
    solution.notes.append(f"error estimate {combined.value:.3g}: {words}")
    return solution


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
    own = reference.error_estimate  # the top's own error, measured by its companion run
    expected = top.compare(reference)
    scale = float(np.max(np.linalg.norm(expected, axis=1))) or 1.0
    rows = []
    for rung in choice.rungs:
        if rung.name not in runs:
            continue
        seconds, solution = runs[rung.name]
        n = min(len(solution), len(reference))
        compare = rung.compare if rung.compare is not None else top.compare
        if rung is top:
            error = float(own) if math.isfinite(own) else 0.0
            estimate = {"value": error} if math.isfinite(own) else None
        else:
            error = float(np.max(np.linalg.norm(compare(solution)[:n] - expected[:n], axis=1))) / scale
            estimate = next((e.get("estimate") for e in choice.entries if e["rung"] == rung.name), None)
        rows.append({"rung": rung.name, "seconds": seconds, "error": error, "chosen": rung is choice.chosen,
                     "estimate": estimate["value"] if estimate else None, "steps": int(solution.stats["steps"]),
                     "switches": len(solution.switches), "reference": rung is top and not math.isfinite(own)})
    return rows + skipped
