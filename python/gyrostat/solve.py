"""One solve and one solve_ensemble for every model family, on the C++ engine."""

from __future__ import annotations

import math
import warnings
from collections.abc import Callable, Sequence

import numpy as np

from gyrostat import _core
from gyrostat import accuracy as _accuracy
from gyrostat import progress as _bars
from gyrostat.modelbase import ModelBase, flag, floats, shown
from gyrostat.solution import AccuracyWarning, Solution

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
``first_step``, ``max_step``, ``step`` and ``splitting_order`` (method ``splitting``).
``repr(gyrostat.Options())`` shows the defaults."""

_DEFAULT = _core.Options()
_OPTION_NAMES = ("method", "rtol", "atol", "t_eval", "n_out", "every_step", "max_steps", "first_step", "max_step",
                 "step", "splitting_order")
_NUMBER_OPTIONS = {"rtol": float, "atol": float, "n_out": int, "max_steps": int, "first_step": float, "max_step": float,
                   "step": float, "splitting_order": int}


def make_options(options: Options | None = None, **given) -> Options:
    """An :class:`Options` from keyword arguments (None: the default), starting from ``options``
    when given. Bad values raise ValueError naming the option and the value."""
    if options is None and all(v is None for v in given.values()):
        return _DEFAULT
    if options is not None and not isinstance(options, Options):
        raise TypeError(f"options must be a gyrostat.Options, not {type(options).__name__}")
    result = Options()
    if options is not None:
        for name in _OPTION_NAMES + ("events", "dense_output"):
            setattr(result, name, getattr(options, name))
    for name, value in given.items():
        if value is None:
            continue
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
        elif name in _NUMBER_OPTIONS:
            kind = _NUMBER_OPTIONS[name]
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
        elif name == "every_step":
            value = flag(value, "every_step")
        else:
            raise TypeError(f"unknown option {name!r}; options are {', '.join(_OPTION_NAMES)}")
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


_CACHE: dict[tuple, Options] = {}


def _options(options, method, rtol, atol, t_eval, n_out, every_step, max_steps, first_step, max_step, step=None,
             splitting_order=None) -> Options:
    """make_options, with the Options of recent keyword combinations kept (they are never
    modified once made): repeated calls with the same options, ``t_eval`` given as a short list
    or tuple included, cost a dictionary look-up."""
    if options is None and (t_eval is None or (n_out is None and type(t_eval) in (list, tuple) and len(t_eval) <= 64)):
        key = (method, rtol, atol, n_out, every_step, max_steps, first_step, max_step, step, splitting_order)
        if True in key or False in key:  # True == 1 == 1.0, yet n_out=True is refused and n_out=1 is not: typed
            key += tuple(map(type, key))
        if t_eval is not None:  # a short list of output times: its values (and their types, unless all floats)
            times = tuple(t_eval)
            key += (times,) if all(type(t) is float for t in times) else (times, tuple(map(type, times)))
        try:
            return _CACHE[key]
        except KeyError:
            made = make_options(method=method, rtol=rtol, atol=atol, t_eval=t_eval, n_out=n_out, every_step=every_step,
                                max_steps=max_steps, first_step=first_step, max_step=max_step, step=step,
                                splitting_order=splitting_order)
            if len(_CACHE) >= 256:
                _CACHE.clear()
            _CACHE[key] = made
            return made
        except TypeError:  # an unhashable value: checked (and refused) by make_options
            pass
    elif n_out is not None and t_eval is not None:
        raise ValueError("give t_eval or n_out, not both")
    return make_options(options, method=method, rtol=rtol, atol=atol, t_eval=t_eval, n_out=n_out,
                        every_step=every_step, max_steps=max_steps, first_step=first_step, max_step=max_step,
                        step=step, splitting_order=splitting_order)


_BASE_CHECK = ModelBase.check
_FLOAT = np.dtype(float)


def _with_events(opts: Options, events, dense_output: bool, core) -> Options:
    """A copy of `opts` (the cached ones are never modified) with the model's events and dense output."""
    from gyrostat.events import to_core

    made = make_options(opts)
    made.events = to_core(events, list(core.state_names), list(core.output_names))
    made.dense_output = flag(dense_output, "dense_output")
    return made


def _continuation(previous: Solution, t0, opts: Options, first_step) -> tuple[np.ndarray, Options]:
    """The state to continue a run from, and its options (the step it would have tried next)."""
    if not np.isfinite(previous.t_last) or len(previous.y_last) == 0:
        raise ValueError("this solution does not say where its run stopped: it cannot be continued")
    if t0 != previous.t_last:
        raise ValueError(f"to continue a run, start at its t_last = {previous.t_last!r}, not at t0 = {t0!r}")
    if first_step is None and previous.h_next > 0:
        opts = make_options(opts)
        opts.first_step = float(previous.h_next)
    return previous.y_last, opts


def _warn_loose_atol(atol: float, y0: np.ndarray) -> None:
    """An absolute tolerance above every component of the state accepts any step: say so."""
    largest = float(np.max(np.abs(y0))) if y0.size else 0.0
    if atol > largest:
        warnings.warn(f"atol = {atol:g} exceeds every component of the initial state (the largest is {largest:g}): "
                      "the error control then accepts any step and the result has no correct digits; give atol "
                      "well below the size of the state", UserWarning, stacklevel=3)


def _core_model(model):
    try:
        return model._core
    except AttributeError:
        raise TypeError(f"model must be a gyrostat model (Model, AveragedModel, MovingMassModel, TorqueFreeModel, "
                        f"lagrange.LagrangeTop, lagrange.LagrangeAveraged, orthogonal.OrthogonalModel), not "
                        f"{type(model).__name__}") from None


def _span(t_span) -> tuple[float, float]:
    """(t0, t1) as floats, or a ValueError naming t_span and its value."""
    try:
        t0, t1 = t_span
    except (TypeError, ValueError):
        raise ValueError(f"t_span must be (t0, t1), got {shown(t_span)}") from None
    if type(t0) in (float, int) and type(t1) in (float, int):  # the common case, without NumPy
        return float(t0), float(t1)
    t0, t1 = floats((t0, t1), "t_span", "two numbers (t0, t1)")
    return float(t0), float(t1)


def _checked(solution: Solution, model, check_validity: bool) -> Solution:
    if solution.status == "interrupted":
        warnings.warn(f"interrupted: {solution.message}", RuntimeWarning, stacklevel=3)
    for doubt in solution.accuracy_warnings:
        warnings.warn(doubt, AccuracyWarning, stacklevel=3)
    if check_validity and type(model).check is not _BASE_CHECK and len(solution):
        from gyrostat.assumptions import ValidityWarning

        for assumption in model.check(solution):
            if not assumption.holds:
                solution.notes.append(f"assumption broken: {assumption}")
                warnings.warn(str(assumption), ValidityWarning, stacklevel=3)
    return solution


def _estimate_mode(error_estimate) -> str:
    """``error_estimate`` as "window", "full" or "" (off); ValueError naming another value."""
    if error_estimate is True or error_estimate == "window":
        return "window"
    if error_estimate is False:
        return ""
    if error_estimate == "full":
        return "full"
    raise ValueError(f"error_estimate = {error_estimate!r} must be True, False or 'full'")


def _accuracy_asked(accuracy) -> float | None:
    """The accuracy asked as a float, or a ValueError naming a value that is not in (0, 1)."""
    if accuracy is None:
        return None
    if isinstance(accuracy, bool) or not isinstance(accuracy, (int, float, np.integer, np.floating)) \
            or not 0 < accuracy < 1:
        raise ValueError(f"accuracy = {accuracy!r} must be a number in (0, 1): the largest relative error accepted")
    return float(accuracy)


def _measured(results: list, cores: list, run, opts, t0: float, t1: float, mode: str, accuracy: float | None,
              explicit: bool, size: float) -> tuple[list, list]:
    """The answers and their estimates: tolerances chosen for ``accuracy`` (:func:`gyrostat.accuracy.meet`)
    unless they were given (``explicit``), or the given run measured (``mode``)."""
    if accuracy is not None and not explicit:
        return _accuracy.meet(run, cores, opts, t0, t1, accuracy, size)
    if results is None:
        results = run(opts, t1, list(range(len(cores))))
    if not mode and accuracy is None:
        return results, [None] * len(results)
    estimates = _accuracy.estimate_runs(run, cores, opts, t0, t1, results, full=mode == "full" or not mode)
    for estimate in estimates:
        if estimate is not None and accuracy is not None:
            estimate.accuracy = accuracy
            if estimate.value > accuracy:
                estimate.warning = (f"the measured error {estimate.value:.3g} exceeds the accuracy {accuracy:g} at the "
                                    f"tolerances given (rtol {opts.rtol:g}, atol {opts.atol:g}): leave rtol and atol "
                                    f"out to have them chosen, or tighten rtol about "
                                    f"{opts.rtol * _accuracy.MARGIN * accuracy / estimate.value:.2g}")
    return results, estimates


def _attach(solution: Solution, estimate) -> Solution:
    """The estimate on the solution: its value, its basis among the notes, its warning among the doubts."""
    if estimate is None:
        return solution
    solution.estimate = estimate
    solution.notes.append(f"error estimate {estimate.value:.3g}: {estimate.basis}")
    if estimate.warning:
        solution.doubt(estimate.warning)
    return solution


def solve(model, y0, t_span, *, method: str | None = None, rtol: float | None = None, atol: float | None = None,
          t_eval=None, n_out: int | None = None, every_step: bool | None = None, max_steps: int | None = None,
          first_step: float | None = None, max_step: float | None = None, step: float | None = None,
          splitting_order: int | None = None, options: Options | None = None,
          events=None, dense_output: bool = False, progress: bool | Callable[[float], object] | None = None,
          check_validity: bool = True, accuracy: float | None = None,
          error_estimate: bool | str = True, compare: Callable | None = None) -> Solution:
    """Solves any model from the initial state ``y0`` over ``t_span = (t0, t1)``.

    Parameters
    ----------
    model : gyrostat.ModelBase
        :class:`gyrostat.Model`, :class:`gyrostat.AveragedModel`, :class:`gyrostat.MovingMassModel`,
        :class:`gyrostat.TorqueFreeModel`, :class:`gyrostat.lagrange.LagrangeTop`,
        :class:`gyrostat.lagrange.LagrangeAveraged` or :class:`gyrostat.orthogonal.OrthogonalModel`.
    y0 : array_like or Solution
        The initial state (``model.state_names``, units in ``model.units``), or a shorter one where the model completes it
        (ω alone for a model with attitude: identity quaternion; τ(0) = 0 for the orthogonal
        torque; a full top state for the averaged top: its (G_z, H, r)). Or a :class:`Solution`
        to continue its run: ``solve(model, sol, (sol.t_last, t1))`` starts from its last
        accepted state with the step it would have tried next (a run stopped by ``max_steps``
        or Ctrl-C, continued, follows the uninterrupted one: DOP853 and Taylor step for step,
        CVODE/ARKODE to the tolerance, since their multistep history restarts).
    t_span : (float, float)
        (t0, t1), in s; t1 < t0 integrates backwards.
    method : str, optional
        The integrator, one of :data:`gyrostat.METHODS` or ``"auto"`` (DOP853, switching to
        CVODE BDF where the problem turns stiff). Default ``"dop853"``.
    rtol : float, optional
        Relative tolerance (dimensionless). Default 1e-8.
    atol : float, optional
        Absolute tolerance, in the units of each state component (rad/s for ω). Default 1e-10.
    t_eval : array_like, optional
        Output times in the span, in s. Outputs come from each method's dense output between
        steps, so memory grows with the outputs asked for, not with the steps.
    n_out : int, optional
        Number of evenly spaced output times when ``t_eval`` is not given. Default 1001.
    every_step : bool, optional
        Record every accepted step as well as the output times. Default False.
    max_steps : int, optional
        Most steps before the run stops with status ``max_steps_reached``. Default 10^6.
    first_step : float, optional
        The first step size, in s (default: the method picks it).
    max_step : float, optional
        The largest step size, in s (default: unbounded).
    step : float, optional
        ``method="splitting"``: the fixed step h, in s (a ValueError names a value ≤ 0 or
        NaN). Left out, it is chosen from ``rtol`` by the splitting's own error estimate. The
        free flow is exact (elliptic functions); constant and linear torques have an exact
        flow too, the others are integrated over each sub-step by one 8th-order step. The run
        estimates its own global error (steps of h against h/2 at up to 32 steps, at most one
        in three: ``solution.error_estimate``, ``solution.notes``) and warns
        (:class:`gyrostat.AccuracyWarning`) when it exceeds ``rtol``, or when a step above
        the span was clamped to it.
    splitting_order : {2, 4, 6}, optional
        ``method="splitting"``: the order of the composition (2: Strang, 4 (default), 6:
        Yoshida's triple jumps).
    options : gyrostat.Options, optional
        All the options above at once (None keeps the defaults of :class:`gyrostat.Options`,
        the one place where defaults live); keywords given as well override it.
    events : Event, callable or list of them, optional
        :class:`gyrostat.events.Event` (a state component or named output crossing a value,
        evaluated in C++) or callables ``f(t, y)`` as in SciPy (the slow path), or a list of
        them; located on each step's continuous extension. Results: ``t_events``, ``y_events``,
        ``terminal_event``. Terminal events end the run (status success). A callable returns a
        number (anything else is a ValueError naming the event); an exception it raises, like
        one of a ``progress`` callable, propagates as it was raised.
    dense_output : bool, optional
        Keep every step's continuous extension so that the solution can be called anywhere in
        the span, ``solution(t)`` and ``solution(t, name)`` (memory then grows with the steps taken, not with the outputs).
    progress : bool or callable, optional
        None (default): a progress bar on stderr when it is a terminal; ``True``: a bar;
        ``False``: none; or a callable of the fraction done, called from the run at most every
        0.1 s (so a short run never shows a bar). Progress never changes the trajectory.
    accuracy : float, optional
        The largest relative error accepted on the quantities the run reports
        (:func:`gyrostat.accuracy.quantities`: ω, the quaternion, the slow variables, |G|, T, ...)
        over the whole span. rtol and atol (or the splitting's step) are then chosen to meet it
        (a probe, then the run and a companion at 4× tighter tolerances over the whole span,
        repeated tighter when the measured error exceeds it: ~2.5× the cost of the cheapest run
        that meets it); given with rtol or atol, those win and the run is only measured against
        it. A run that cannot meet it warns (:class:`gyrostat.AccuracyWarning`) with the
        measured error and what would meet it.
    error_estimate : bool or "full", optional
        Measure the answer's global error (default True): ``solution.error_estimate``,
        ``error_estimates`` (per quantity) and ``error_basis``. True: from a companion run at 4×
        tighter tolerances over the first 20 % of the span, grown to its end (~0.45× the run's
        cost); ``"full"``: the companion covers the whole span; False: not measured.
    compare : callable, optional
        ``compare(solution) -> (n, m) array``: the quantities ``accuracy`` and the estimate apply
        to, instead of :func:`gyrostat.accuracy.quantities` (one quantity, ``"compared"``, relative
        to its largest row norm): e.g. |G| and T alone when ω's phase does not matter.
    check_validity : bool, optional
        For an averaged model, check its assumptions along the solution; broken ones are warned
        about (:class:`gyrostat.ValidityWarning`) and listed in ``solution.notes``.

    Returns
    -------
    Solution
        Times, states and the model's named outputs recorded during the run. A failing run
        (too many steps, step-size underflow, a non-finite state) returns its partial trajectory
        with ``status`` and ``message``; Ctrl-C stops the run within a fraction of a second and
        returns what was computed with status ``"interrupted"``. Bad input (negative rtol, NaN
        state, t_eval outside the span, a state of the wrong size) raises ValueError naming the value.

    Examples
    --------
    A prolate body spinning about its minor axis (A3 = 4 < A1 = A2) with a viscous-fluid cavity
    (the tutorial's satellite), one event where the spin rate r falls through 1.9 rad/s:

    >>> import gyrostat
    >>> from gyrostat.events import Event
    >>> body = gyrostat.Body([12.0, 12.0, 4.0])
    >>> cavity = gyrostat.ViscousCavity(density=970.0, viscosity=2.0, radius=0.25)
    >>> model = gyrostat.Model(body, [cavity])
    >>> sol = gyrostat.solve(model, [0.05, 0.0, 2.0], (0.0, 36000.0), rtol=1e-10, n_out=201,
    ...                      events=[Event("r", 1.9, direction=-1)])
    >>> sol.status, sol.y.shape, round(float(sol.t_events[0][0]))
    ('success', (201, 3), 14263)
    >>> bool(abs(sol["angular_momentum_norm"][-1] / sol["angular_momentum_norm"][0] - 1) < 1e-7)
    True
    """
    try:
        core = model._core
    except AttributeError:
        core = _core_model(model)
    opts = _options(options, method, rtol, atol, t_eval, n_out, every_step, max_steps, first_step, max_step, step,
                    splitting_order)
    if events is not None or dense_output is not False:
        opts = _with_events(opts, events, dense_output, core)
    t0, t1 = _span(t_span)
    if type(y0) is not np.ndarray or y0.dtype is not _FLOAT:  # an array of floats needs no conversion
        if isinstance(y0, Solution):
            y0, opts = _continuation(y0, t0, opts, first_step)
        y0 = floats(y0, "y0")
    if y0.ndim != 1:
        raise ValueError(f"y0 must be one state (a 1-D array), got shape {y0.shape}")
    if atol is not None and atol > 1e-3:
        _warn_loose_atol(atol, y0)
    check_validity = check_validity if check_validity is True else flag(check_validity, "check_validity")
    report = _bars.default() if progress is None else _bars.resolve(progress)
    mode = _estimate_mode(error_estimate) if error_estimate is not True else "window"
    asked = _accuracy_asked(accuracy) if accuracy is not None else None
    try:
        if asked is None:
            result = _core.solve(core, y0, t0, t1, opts, report)  # an exception of the user's callbacks propagates
            estimate = None
            if mode and t1 != t0 and result.success:
                estimate = _measured([result], [_accuracy.Compared(core, compare, model) if compare else core], lambda o, t, ms: [_core.solve(core, y0, t0, t, o, report)],
                                     opts, t0, t1, mode, None, True, 0.0)[1][0]
        else:
            explicit = rtol is not None or atol is not None or step is not None or options is not None
            size = float(np.max(np.abs(y0))) if y0.size else 1.0
            measured = [_accuracy.Compared(core, compare, model) if compare else core]
            results, estimates = _measured(None, measured, lambda o, t, ms: [_core.solve(core, y0, t0, t, o, report)],
                                           opts, t0, t1, mode, asked, explicit, size)
            result, estimate = results[0], estimates[0]
    finally:
        if report is not None:
            _bars.close(report)
    solution = Solution(result, model)
    if estimate is not None:
        _attach(solution, estimate)
    if result.success and (not check_validity or type(model).check is _BASE_CHECK) and not result.warnings \
            and not solution._doubts:
        return solution
    return _checked(solution, model, check_validity)


def solve_ensemble(models: ModelBase | Sequence[ModelBase], y0s, t_span, *, threads: int = 0,
                   method: str | None = None, rtol: float | None = None, atol: float | None = None, t_eval=None,
                   n_out: int | None = None, every_step: bool | None = None, max_steps: int | None = None,
                   first_step: float | None = None, max_step: float | None = None, step: float | None = None,
                   splitting_order: int | None = None, options: Options | None = None,
                   events=None, dense_output: bool = False, progress: bool | Callable[[float], object] | None = None,
                   check_validity: bool = True, batch: bool = True, accuracy: float | None = None,
                   error_estimate: bool | str = True) -> list[Solution]:
    """Solves N trajectories in one call on a pool of C++ threads (GIL released).

    ``models`` is one model for every member or a sequence of N (different parameters, or
    different families, per member); ``y0s`` is (N, dim), or any iterable of N states (of each
    member's own size, short states completed as in :func:`solve`; a generator is read once).
    Results come in index order. All members' outputs together are held to the limit of one
    run's (2 GiB: ``RUN_MEMORY_LIMIT``), checked before any member starts.

    With ``batch=True`` (the default), members that a SIMD batch covers run
    :data:`gyrostat.simd_lanes` at a time, one per lane, each lane with its own parameters,
    time, step size and status: the gyrostat :class:`Model` with constant and linear torques
    (with or without attitude) under ``taylor`` or ``dop853``, the same with user torques
    compiled with the vectorised signature (:class:`gyrostat.CustomTorque`, called once per stage
    for the batch's lanes) under ``dop853``, and the averaged symmetric model
    under ``dop853``, without events, dense output or ``every_step`` (and not ``taylor`` for ω
    alone with the SSE2 batches on a CPU with AVX2, where one body at a time is faster:
    :data:`gyrostat.taylor_kernel`). They equal single
    :func:`solve` runs to the tolerance, not bit for bit (vectorised rounding; a Taylor batch
    uses the highest order any lane needs). Every other member, and every member with
    ``batch=False``, equals its single run bit for bit. A member with bad input gets
    ``status == "invalid_input"`` and its message; the others are unaffected. ``threads`` ≤ 0
    uses every hardware thread. ``progress`` is called with the fraction of members finished;
    Ctrl-C stops the members running (status ``"interrupted"``, partial trajectories kept) and
    those not started (empty, ``"interrupted"``). Options, ``events`` and ``dense_output`` as in
    :func:`solve`: every member watches the same events and stops on its own terminal event (the
    events are resolved against the first model's names: give members of one family); the first
    exception an event callable raises is raised again once the members have finished.

    Parameters
    ----------
    models : gyrostat.ModelBase or sequence of them
        One model for every member, or one per member.
    y0s : array_like, shape (N, dim), or iterable of N states
        The initial states (units in ``model.units``).
    t_span : (float, float)
        (t0, t1), in s, the same for every member.
    threads : int, optional
        C++ threads; ≤ 0 (default): every hardware thread.
    method : str, optional
        The integrator for every member (see :func:`solve`).
    rtol : float, optional
        Relative tolerance, dimensionless.
    atol : float, optional
        Absolute tolerance, in the state's units.
    t_eval : array_like, optional
        Output times of every member, in s.
    n_out : int, optional
        Evenly spaced output times when ``t_eval`` is not given.
    every_step : bool, optional
        Record every accepted step too (not in SIMD batches).
    max_steps : int, optional
        Most steps per member.
    first_step : float, optional
        First step size, in s.
    max_step : float, optional
        Largest step size, in s.
    step : float, optional
        Fixed step of ``method="splitting"``, in s.
    splitting_order : {2, 4, 6}, optional
        Order of ``method="splitting"``.
    options : gyrostat.Options, optional
        All of these at once; keywords override it.
    events : Event, callable or list of them, optional
        Watched by every member; each stops on its own terminal event.
    dense_output : bool, optional
        Keep each member's continuous extension (``sol(t)``).
    progress : bool or callable, optional
        A bar, or a callable of the fraction of members finished.
    check_validity : bool, optional
        Check an averaged model's assumptions along each member.
    batch : bool, optional
        Run the members a SIMD batch covers :data:`gyrostat.simd_lanes` at a time (default True).
    accuracy : float, optional
        As in :func:`solve`: one rtol for every member, the tightest any member needs (members
        whose measured error still exceeds it run again, tighter); each member's own estimate.
    error_estimate : bool or "full", optional
        As in :func:`solve`: each member's measured error (``error_estimate``), default True.

    Returns
    -------
    list of Solution
        One per member, in index order.

    Examples
    --------
    Three spin rates of one symmetric body with linear damping, integrated at once (r decays
    as exp(-D t / C), to exp(-1) at t = 10 s):

    >>> import numpy as np
    >>> import gyrostat
    >>> model = gyrostat.Model(gyrostat.Body([2.0, 2.0, 1.0]), [gyrostat.LinearDamping(diagonal=[0.1, 0.1, 0.1])])
    >>> y0s = np.array([[0.1, 0.0, 1.0], [0.1, 0.0, 2.0], [0.1, 0.0, 3.0]])
    >>> sols = gyrostat.solve_ensemble(model, y0s, (0.0, 10.0), n_out=11)
    >>> [round(float(sol["r"][-1] / sol["r"][0]), 4) for sol in sols]
    [0.3679, 0.3679, 0.3679]
    """
    check_validity = flag(check_validity, "check_validity")
    models, results, estimates = ensemble_results(
        models, y0s, t_span, threads=threads, method=method, rtol=rtol, atol=atol, t_eval=t_eval, n_out=n_out,
        every_step=every_step, max_steps=max_steps, first_step=first_step, max_step=max_step, step=step,
        splitting_order=splitting_order, options=options, events=events, dense_output=dense_output,
        progress=progress, batch=batch, accuracy=accuracy, error_estimate=error_estimate)
    solutions = [_attach(Solution(r, models[0] if len(models) == 1 else models[i]), e)
                 for i, (r, e) in enumerate(zip(results, estimates))]
    return [_checked(s, s.model, check_validity) if s.success or s.accuracy_warnings else s for s in solutions]


def ensemble_results(models, y0s, t_span, *, threads: int = 0, method=None, rtol=None, atol=None, t_eval=None,
                      n_out=None, every_step=None, max_steps=None, first_step=None, max_step=None, step=None,
                      splitting_order=None, options=None, events=None, dense_output=False, progress=None,
                      batch=True, accuracy=None, error_estimate=False) -> tuple[list, list, list]:
    """:func:`solve_ensemble` up to the engine's results, without a :class:`Solution` per member:
    for callers that summarise many members at once (:func:`gyrostat.sweeps.solve_chunk`).

    Parameters
    ----------
    models, y0s, t_span, threads, method, rtol, atol, t_eval, n_out, every_step, max_steps, first_step, max_step, \
step, splitting_order, options, events, dense_output, progress, batch, accuracy, error_estimate
        As in :func:`solve_ensemble` (which checks them the same way); ``error_estimate`` defaults
        to False here.

    Returns
    -------
    (list, list, list)
        The models (one for every member, or one per member), the engine's ``Result`` of
        every member, in index order (``Solution(result, model)`` makes a member's Solution),
        and each member's :class:`gyrostat.accuracy.Estimate` (None: not measured).

    Examples
    --------
    >>> import numpy as np
    >>> import gyrostat
    >>> from gyrostat.solve import ensemble_results
    >>> model = gyrostat.Model(gyrostat.Body([2.0, 2.0, 1.0]), [gyrostat.LinearDamping(diagonal=[0.1, 0.1, 0.1])])
    >>> _, results, _ = ensemble_results(model, np.array([[0.1, 0.0, 1.0], [0.1, 0.0, 2.0]]), (0.0, 10.0), n_out=11)
    >>> [r.status for r in results], [round(float(r.y[-1, 2] / r.y[0, 2]), 4) for r in results]
    (['success', 'success'], [0.3679, 0.3679])
    """
    if isinstance(models, ModelBase):
        models = [models]
    models = list(models)
    if not models:
        raise ValueError("solve_ensemble needs at least one model")
    cores = [_core_model(m) for m in models]
    if not isinstance(y0s, (np.ndarray, Sequence)):  # a generator or any other iterable of states
        try:
            y0s = list(y0s)
        except TypeError:
            raise ValueError(f"y0s must be (N, dim) numbers or a sequence of N states, got {shown(y0s)}") from None
    if isinstance(y0s, np.ndarray) or (len(y0s) and not isinstance(y0s[0], (list, tuple, np.ndarray))):
        y0s = floats(y0s, "y0s")
        if y0s.ndim != 2:
            raise ValueError(f"y0s must be (N, dim), got shape {y0s.shape}")
        count = y0s.shape[0]
    else:
        y0s = [floats(y, f"y0s[{i}]").ravel() for i, y in enumerate(y0s)]
        count = len(y0s)
    if len(models) not in (1, count):
        raise ValueError(f"{len(models)} models for {count} initial states: give 1 or {count}")
    opts = _options(options, method, rtol, atol, t_eval, n_out, every_step, max_steps, first_step, max_step, step,
                    splitting_order)
    if events is not None or dense_output is not False:
        if len({tuple(c.state_names) + tuple(c.output_names) for c in cores}) > 1:
            raise ValueError("events in an ensemble need members of one family (the same state and output names)")
        opts = _with_events(opts, events, dense_output, cores[0])
    t0, t1 = _span(t_span)
    if atol is not None and atol > 1e-3:
        _warn_loose_atol(atol, np.abs(np.asarray(y0s[0] if isinstance(y0s, list) else y0s, float)).max(axis=0))
    if isinstance(threads, bool) or not isinstance(threads, (int, np.integer)) or abs(threads) > 4096:
        raise ValueError(f"threads = {threads!r} must be a whole number of at most 4096 (<= 0: one per core)")
    batch = flag(batch, "batch")
    outputs = len(opts.t_eval) or opts.n_out
    check_output_memory(cores, count, outputs, f"{count} members x {outputs} output times")
    mode = _estimate_mode(error_estimate)
    asked = _accuracy_asked(accuracy)
    report = _bars.resolve(progress, total=count, unit="member")

    def run(o, t_end, members):  # the members' runs (all of them: the answer's, with the progress)
        if len(members) == count:
            return _core.solve_ensemble(cores, y0s, t0, t_end, o, int(threads), report, batch=batch)
        starts = y0s[members] if isinstance(y0s, np.ndarray) else [y0s[m] for m in members]
        chosen = cores if len(cores) == 1 else [cores[m] for m in members]
        return _core.solve_ensemble(chosen, starts, t0, t_end, o, int(threads), None, batch=batch)

    try:
        if not mode and asked is None:
            return models, run(opts, t1, list(range(count))), [None] * count
        explicit = rtol is not None or atol is not None or step is not None or options is not None
        size = max((float(np.max(np.abs(y))) for y in y0s if len(y)), default=1.0)
        results, estimates = _measured(None, cores * count if len(cores) == 1 else cores, run, opts, t0, t1, mode,
                                       asked, explicit, size)
    finally:
        _bars.close(report)
    return models, results, estimates


RUN_MEMORY_LIMIT = _core.max_output_bytes
"""The bytes of output one run may record: the engine refuses a run above it (``Recorder`` in
cpp/include/gyrostat/integrate/recorder.hpp); :func:`solve_ensemble` applies it to all members together."""


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
    """The options of a run of ``model`` over ``t_span`` checked as :func:`solve` checks them
    (tolerances, steps, output times and their memory), without running: a ValueError naming
    the value. ``method`` is taken as valid (a scene's schema has checked it); events are not
    options here."""
    opts = make_options(**{name: options[name] for name in _OPTION_NAMES if name in options and name != "method"})
    outputs = len(opts.t_eval) or opts.n_out
    check_output_memory([model], 1, outputs, f"n_out = {outputs} output times")
    opts.validate(*_span(t_span))
