"""Events: where a quantity crosses a value, located by the engine on each step's continuous
extension (DOP853's 7th-order dense output, the Taylor polynomial, CVODE's and ARKODE's
interpolants, the closed form itself), to a few ulps of t, not interpolated between outputs.

An event is

* :class:`Event` on a state component or a named output of the model (``Event("r")``,
  ``Event("g")``, ``Event("m", value=0.999, direction=1)``): evaluated in C++, the fast path;
* or a Python callable ``f(t, y)``, as in SciPy's ``solve_ivp``, with optional attributes
  ``terminal`` (bool or a count) and ``direction``: one call into Python per evaluation, the
  slow path (fine for a few thousand steps, not for ensembles of millions).

``direction``: +1 only upward crossings (g from negative to non-negative), −1 only downward,
0 both (SciPy's convention). ``terminal``: False, True (stop at the first crossing) or n (stop
at the n-th). A solution gives ``t_events`` and ``y_events`` (SciPy's names: one array per
event) and ``terminal_event`` (the index of the event that stopped the run, or None).

Events the papers need ship with their families: :func:`gyrostat.orthogonal.g_zero`,
:func:`gyrostat.averaged.r_zero`, :func:`gyrostat.lagrange.turning_points`,
:func:`gyrostat.lagrange.near_separatrix`, and the validity of the averaging failing
(:func:`gyrostat.averaged.averaging_fails`, :func:`gyrostat.lagrange.averaging_fails`).
"""

from __future__ import annotations

import math
import re
from collections.abc import Callable
from dataclasses import dataclass
from inspect import CO_VARARGS
from types import FunctionType

from gyrostat import _core


@dataclass(frozen=True)
class Event:
    """``quantity`` (a state component or a named output of the model) crossing ``value``."""

    quantity: str
    value: float = 0.0
    direction: int = 0
    terminal: bool | int = False
    name: str | None = None

    def __post_init__(self):
        _direction(self.direction, f"event {self.quantity!r}")
        if isinstance(self.value, bool) or not isinstance(self.value, (int, float)) or not math.isfinite(self.value):
            raise ValueError(f"event value = {self.value!r} must be a finite number")
        terminal_count(self.terminal, self.quantity)

    @property
    def label(self) -> str:
        """The name given, else one from the quantity, the value and the direction: ``r = 0``,
        ``r rises through 0``, ``r falls through 0`` (two events that differ only in direction
        get distinct names; :func:`labels` numbers the ones still alike)."""
        if self.name:
            return self.name
        crossing = {0: "=", 1: "rises through", -1: "falls through"}[self.direction]
        return f"{self.quantity} {crossing} {self.value:g}"


def _direction(direction, what: str) -> int:
    """-1, 0 or 1 (a bool or a string is not a direction), or a ValueError naming the event."""
    if isinstance(direction, (bool, str)) or direction not in (-1, 0, 1):
        raise ValueError(f"{what}: direction = {direction!r}: choose -1, 0 or 1")
    return int(direction)


def terminal_count(terminal, what) -> int:
    """The count of crossings after which the event stops the run (0: never), or a ValueError naming it."""
    if terminal is True:
        return 1
    if terminal is False or terminal is None:
        return 0
    if isinstance(terminal, int) and terminal >= 0:
        return terminal
    raise ValueError(f"event {what!r}: terminal = {terminal!r} must be a bool or a count >= 0")


def _check_signature(function: Callable, i: int, name: str) -> None:
    """A callable event is called as f(t, y): one that cannot be is a TypeError naming it now,
    before the run (a callable without a signature to read is called as it is)."""
    if type(function) is FunctionType:  # a plain function: its code says it, without inspect (~100 us)
        code = function.__code__
        required = code.co_argcount - len(function.__defaults__ or ())
        keywords = code.co_varnames[code.co_argcount:code.co_argcount + code.co_kwonlyargcount]
        if ((code.co_argcount >= 2 or code.co_flags & CO_VARARGS) and required <= 2
                and all(k in (function.__kwdefaults__ or {}) for k in keywords)):
            return
    import inspect

    try:
        signature = inspect.signature(function)
    except (TypeError, ValueError):
        return
    try:
        signature.bind(0.0, None)
    except TypeError as error:
        raise TypeError(f"event {i} ({name}) must take (t, y): {error}") from None


def _listed(events) -> list:
    if events is None:
        return []
    return [events] if callable(events) or isinstance(events, (Event, _core.Event)) else list(events)


def labels(events) -> list[str]:
    """The names the events are reported under, one per event, all distinct: an Event's
    :attr:`Event.label`, a callable's ``__name__``; a name that repeats an earlier one gets
    " (2)", " (3)", ... (so that ``t_events`` by name and the report keep every event)."""
    names: list[str] = []
    for i, event in enumerate(_listed(events)):
        base = (event.label if isinstance(event, Event) else event.name if isinstance(event, _core.Event)
                else getattr(event, "__name__", f"event {i}"))
        name, count = base, 1
        while name in names:
            count += 1
            name = f"{base} ({count})"
        names.append(name)
    return names


def to_core(events, state_names, output_names) -> list:
    """The engine's events for a model with these state and output names (an engine event made
    already, ``_core.Event``, such as a model's ``watch_event``, is passed as it is)."""
    events = _listed(events)
    names = labels(events)
    core = []
    for i, event in enumerate(events):
        if isinstance(event, Event):
            if event.quantity in state_names:
                kind, index = "state", state_names.index(event.quantity)
            elif event.quantity in output_names:
                kind, index = "output", output_names.index(event.quantity)
            else:
                raise ValueError(f"event {i}: {event.quantity!r} is neither a state component "
                                 f"({', '.join(state_names)}) nor an output ({', '.join(output_names)}) of this model")
            core.append(_core.Event(kind, index, float(event.value), event.direction,
                                    terminal_count(event.terminal, event.quantity), names[i]))
        elif isinstance(event, _core.Event):  # an engine event made already (the ladder's watch_event)
            core.append(event)
        elif callable(event):
            name = names[i]
            direction = _direction(getattr(event, "direction", 0), f"event {i} ({name})")
            _check_signature(event, i, name)
            function: Callable = event
            core.append(_core.Event("function", i, 0.0, direction,
                                    terminal_count(getattr(event, "terminal", False), name), name, function))
        else:
            raise TypeError(f"event {i} must be a gyrostat.events.Event or a callable f(t, y), "
                            f"not {type(event).__name__}")
    return core


def variable_name(label: str) -> str:
    """A variable name for an event's label (``"g = 0"`` → ``g_0``): in NetCDF files and Datasets."""
    return re.sub(r"[^0-9A-Za-z_.]+", "_", label).strip("_") or "event"
