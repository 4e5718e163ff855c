"""The options of a run, written once: :data:`OPTIONS` names the integration options and their
types, and everything else reads it — :func:`make_options` (an :class:`Options` from keywords,
each value checked), the options of recent keyword combinations kept (:func:`options_of`),
:func:`check_run` (a run's options checked without running), and the limit on what one run may
record (:data:`RUN_MEMORY_LIMIT`, :func:`check_output_memory`). :func:`gyrostat.solve`,
:func:`gyrostat.solve_ensemble` and :mod:`gyrostat.accuracy` take their option names from here;
``gyrostat.solve`` re-exports the public names."""

from __future__ import annotations

import math
import operator
import warnings
from collections.abc import Callable

import numpy as np

from gyrostat import _core
from gyrostat.arguments import flag, floats, shown

__all__ = ["METHODS", "Options", "OPTIONS", "OPTION_NAMES", "RUN_MEMORY_LIMIT", "make_options", "output_times",
           "check_run", "check_output_memory"]

METHODS: tuple[str, ...] = tuple(_core.methods())
"""Integrators: ``dop853`` (fixed-size, allocation-free; the default for non-stiff problems),
``taylor`` (adaptive-order Taylor series for the polynomial right-hand sides of the gyrostat
with constant and linear torques: the fastest at tight tolerances), ``cvode_bdf`` (stiff),
``cvode_adams``, ``arkode_fehlberg8``, ``arkode_verner6``, ``splitting`` (the exact free-body
flow composed with the torques' flow at a fixed ``step``, order ``splitting_order`` = 2, 4 or 6:
for long horizons of weakly perturbed bodies; the gyrostat ``Model``, the Lagrange top and the
orthogonal-torque model, when their free part has a closed form; see docs/integrators.md). A model
that needs no integration (:class:`gyrostat.TorqueFreeModel`) is evaluated in closed form
whatever the method."""

Options = _core.Options
"""Every integrator option with its default, in one place (the C++ engine's ``Options``):
``method``, ``rtol``, ``atol``, ``t_eval``, ``n_out``, ``every_step``, ``max_steps``,
``first_step``, ``max_step``, ``step`` and ``splitting_order`` (method ``splitting``), and
``sensitivity_error_control`` (a run with sensitivities). ``repr(gyrostat.Options())`` shows the
defaults."""

OPTIONS: dict[str, type] = {"method": str, "rtol": float, "atol": float, "t_eval": np.ndarray, "n_out": int,
                            "every_step": bool, "max_steps": int, "first_step": float, "max_step": float,
                            "step": float, "splitting_order": int, "sensitivity_error_control": bool}
"""The integration options, each with the type of its value: the one list that :func:`make_options`,
:func:`options_of`, :func:`check_run` and the accuracy contract's companions read (the keywords of
:func:`gyrostat.solve`, :func:`gyrostat.solve_ensemble` and ``ensemble_results`` are checked
against it by the tests; the defaults live in :class:`Options`)."""
OPTION_NAMES: tuple[str, ...] = tuple(OPTIONS)
"""The names of :data:`OPTIONS`, in its order."""

RUN_MEMORY_LIMIT = _core.max_output_bytes
"""The bytes of output one run may record: the engine refuses a run above it (``Recorder`` in
cpp/include/gyrostat/integrate/recorder.hpp); :func:`gyrostat.solve_ensemble` applies it to all members together."""

_DEFAULT = _core.Options()


def make_options(options: Options | None = None, **given) -> Options:
    """An :class:`Options` from keyword arguments (None: the default), starting from ``options``
    when given. Bad values raise ValueError naming the option and the value."""
    if options is None and all(v is None for v in given.values()):
        return _DEFAULT
    if options is not None and not isinstance(options, Options):
        raise TypeError(f"options must be a gyrostat.Options, not {type(options).__name__}")
    result = Options()
    if options is not None:
        for name in OPTION_NAMES + ("events", "dense_output"):
            setattr(result, name, getattr(options, name))
    for name, value in given.items():
        if value is None:
            continue
        kind = OPTIONS.get(name)
        if name == "method":
            if value not in METHODS:
                raise ValueError(f"unknown method {value!r}; choose one of {', '.join(METHODS)}")
            if value == "arkode_verner6":
                warnings.warn(
                    "arkode_verner6: the ARKODE_VERNER_8_5_6 table of SUNDIALS 6.4 converges at order 3, not 6 "
                    "(measured; see docs/integrators.md): expect global errors far above rtol; prefer dop853",
                    UserWarning, stacklevel=3)
        elif name == "t_eval":
            value = output_times(value)
        elif kind in (int, float):
            if isinstance(value, bool) or not isinstance(value, (int, float, np.integer, np.floating)):
                raise ValueError(f"{name} = {value!r} must be a number")
            if kind is int:
                if not math.isfinite(value) or value != int(value):
                    raise ValueError(f"{name} = {value!r} must be a whole number")
                if abs(value) > 2**62:
                    raise ValueError(f"{name} = {value!r} is too large")
            if name == "step" and not (value > 0):  # NaN fails too
                raise ValueError(f"step = {value!r} must be a positive number (the fixed step of method 'splitting')")
            if name == "splitting_order" and value not in (2, 4, 6):
                raise ValueError(f"splitting_order = {value!r} must be 2, 4 or 6")
            value = kind(value)
        elif kind is bool:
            value = flag(value, name)
        else:
            raise TypeError(f"unknown option {name!r}; options are {', '.join(OPTION_NAMES)}")
        setattr(result, name, value)
    return result


def output_times(t_eval) -> np.ndarray:
    """The output times as a 1-D array of floats, at least one; ValueError naming t_eval otherwise."""
    t = floats(t_eval, "t_eval", "output times (numbers)")
    if t.ndim != 1:
        raise ValueError(f"t_eval must be one-dimensional, got shape {t.shape}")
    if t.size == 0:
        raise ValueError("t_eval = [] holds no output time: give at least one (or n_out, or neither)")
    return t


option_values = operator.itemgetter(*OPTION_NAMES)
"""``option_values(locals())``: the values of the integration options among a function's arguments
(a function whose keywords include every name of :data:`OPTIONS`), as a tuple in the order of
:data:`OPTIONS` (one call in C: :func:`gyrostat.solve` reads its options so on every call)."""
_T_EVAL, _N_OUT = OPTION_NAMES.index("t_eval"), OPTION_NAMES.index("n_out")

_CACHE: dict[tuple, Options] = {}
_SHARED: set[int] = set()
"""The ids of the Options in :data:`_CACHE` (alive, and never modified, while they are there)."""
_DERIVED: dict[tuple[int, object], object] = {}
_BOOLS = frozenset((True, False))


def derived(opts: Options, purpose, make: Callable[[Options], object]):
    """``make(opts)``, made once for an Options of the cache (:func:`options_of`: never modified, so
    the same value every time) and afresh for any other (a caller's own may change between calls).
    What it returns is shared: not to be modified."""
    if id(opts) not in _SHARED:
        return make(opts)
    key = (id(opts), purpose)
    made = _DERIVED.get(key)
    if made is None:
        if len(_DERIVED) >= 4096:  # (purposes keyed by a run's span and accuracy: bounded)
            _DERIVED.clear()
        made = _DERIVED[key] = make(opts)
    return made


def options_of(options, values: tuple, listed=None) -> Options:
    """make_options, with the Options of recent keyword combinations kept (they are never
    modified once made): repeated calls with the same options, ``t_eval`` given as a short list
    or tuple included, cost a dictionary look-up. ``values``: the value of every option of
    :data:`OPTIONS`, in its order (None: not given; :data:`option_values`). ``listed``: the list of
    output times given, where ``values`` holds it as a tuple (:func:`gyrostat.solve` passes it so:
    a tuple keys the cache as it is, with no key rebuilt; a refusal names the list given)."""
    t_eval, n_out = values[_T_EVAL], values[_N_OUT]
    if options is None and (t_eval is None or (n_out is None and type(t_eval) in (list, tuple) and len(t_eval) <= 64)):
        if type(t_eval) is list:
            listed, t_eval = t_eval, tuple(t_eval)
            values = values[:_T_EVAL] + (t_eval,) + values[_T_EVAL + 1:]
        key = values
        try:
            if not _BOOLS.isdisjoint(key):  # True == 1 == 1.0, yet n_out=True is refused and n_out=1 is not: typed
                key += tuple(map(type, key))
            if t_eval is not None and not (len(t_eval) == 2 and type(t_eval[0]) is float and type(t_eval[1]) is float) \
                    and bool in map(type, t_eval):  # the output times' types too, where one is a bool
                key += (tuple(map(type, t_eval)),)
            return _CACHE[key]
        except KeyError:
            made = make_options(**_named(values, listed))
            if len(_CACHE) >= 256:
                _CACHE.clear()
                _SHARED.clear()
                _DERIVED.clear()
            _CACHE[key] = made
            _SHARED.add(id(made))
            return made
        except TypeError:  # an unhashable value: checked (and refused) by make_options
            pass
    elif n_out is not None and t_eval is not None:
        raise ValueError("give t_eval or n_out, not both")
    return make_options(options, **_named(values, listed))


def _named(values: tuple, listed) -> dict:
    """The options by name, ``t_eval`` as the user gave it (``listed``: a list passed as a tuple)."""
    named = dict(zip(OPTION_NAMES, values))
    if listed is not None:
        named["t_eval"] = listed
    return named


def with_events(opts: Options, events, dense_output: bool, core) -> Options:
    """A copy of `opts` (the cached ones are never modified) with the model's events and dense output."""
    from gyrostat.events import to_core

    made = make_options(opts)
    made.events = to_core(events, list(core.state_names), list(core.output_names))
    made.dense_output = flag(dense_output, "dense_output")
    return made


def span(t_span) -> tuple[float, float]:
    """(t0, t1) as floats, or a ValueError naming t_span and its value."""
    if type(t_span) is tuple and len(t_span) == 2 and type(t_span[0]) is float and type(t_span[1]) is float:
        return t_span  # the commonest case, in the fewest steps (bench/python_overhead.py)
    try:
        t0, t1 = t_span
    except (TypeError, ValueError):
        raise ValueError(f"t_span must be (t0, t1), got {shown(t_span)}") from None
    if type(t0) in (float, int) and type(t1) in (float, int):  # the common case, without NumPy
        return float(t0), float(t1)
    t0, t1 = floats((t0, t1), "t_span", "two numbers (t0, t1)")
    return float(t0), float(t1)


def warn_loose_atol(atol: float, y0: np.ndarray) -> None:
    """An absolute tolerance above every component of the state accepts any step: say so."""
    largest = float(np.max(np.abs(y0))) if y0.size else 0.0
    if atol > largest:
        warnings.warn(f"atol = {atol:g} exceeds every component of the initial state (the largest is {largest:g}): "
                      "the error control then accepts any step and the result has no correct digits; give atol "
                      "well below the size of the state", UserWarning, stacklevel=3)


def check_output_memory(models, members: int, outputs: int, what: str) -> None:
    """A ValueError starting with ``what`` when ``members`` runs of these models (one for all, or
    one per member) would record more than RUN_MEMORY_LIMIT bytes at ``outputs`` output times
    (t, the state and the named outputs at each, as the engine counts them; ``every_step`` is
    not counted: unknown before the run)."""
    widths, known = [], {}
    for m in models:
        key = (m.family, m.dim)  # the model the engine runs, and so its outputs
        if key not in known:
            known[key] = 1 + m.dim + len(m.output_names)
        widths.append(known[key])
    need = float(members) * max(outputs, 2) * sum(widths) / len(widths) * 8.0
    if need > RUN_MEMORY_LIMIT:
        raise ValueError(f"{what} would take {need / 2**30:.3g} GiB (limit {RUN_MEMORY_LIMIT / 2**30:g} GiB for "
                         "one run's outputs): ask for fewer outputs" + (" or fewer members" if members > 1 else ""))


def check_run(model, t_span, options: dict) -> None:
    """The options of a run of ``model`` over ``t_span`` checked as :func:`gyrostat.solve` checks them
    (tolerances, steps, output times and their memory), without running: a ValueError naming
    the value. ``method`` is taken as valid (a scene's schema has checked it); events are not
    options here."""
    opts = make_options(**{name: options[name] for name in OPTION_NAMES if name in options and name != "method"})
    outputs = len(opts.t_eval) or opts.n_out
    check_output_memory([model], 1, outputs, f"n_out = {outputs} output times")
    opts.validate(*span(t_span))
