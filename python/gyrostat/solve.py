"""One solve and one solve_ensemble for every model family, on the C++ engine.

:func:`solve` is here; the rest of a run lives beside it, and every name is importable from here as
well: the options and their checks in :mod:`gyrostat.options` (:data:`METHODS`, :class:`Options`,
:func:`make_options`, :func:`output_times`, :func:`check_run`, :data:`RUN_MEMORY_LIMIT`,
:func:`check_output_memory`), the ensembles in :mod:`gyrostat.ensemble` (:func:`solve_ensemble`,
:func:`ensemble_results`), the accuracy contract's measurement and the warnings of a returned run
in :mod:`gyrostat.answer`."""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

from gyrostat import _core
from gyrostat import accuracy as _accuracy
from gyrostat import contract as _contract
from gyrostat import progress as _bars
from gyrostat import sensitivity as _sensitivity
from gyrostat.answer import BASE_CHECK, accuracy_asked, attach, checked, estimate_mode, measured
from gyrostat.arguments import flag, floats
from gyrostat.ensemble import ensemble_results, solve_ensemble
from gyrostat.modelbase import core_of
from gyrostat.options import (METHODS, RUN_MEMORY_LIMIT, Options, check_output_memory, check_run, make_options,
                              options_of, output_times, span, warn_loose_atol, with_events)
from gyrostat.solution import Solution

__all__ = ["solve", "solve_ensemble", "ensemble_results", "METHODS", "Options", "make_options", "output_times",
           "check_run", "RUN_MEMORY_LIMIT", "check_output_memory"]

_FLOAT = np.dtype(float)


def _size(y0: np.ndarray) -> float:
    """The largest |y0| component (the accuracy contract's atol scale), 1 for an empty state (a
    model's short state read as a list: ~0.3 µs against NumPy's ~2 µs reduction)."""
    if not y0.size:
        return 1.0
    return float(max(map(abs, y0.tolist()))) if y0.size <= 64 else float(np.abs(y0).max())


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


def _with_sensitivities(model, core, y0, t0, t1, opts, names, events, asked, mode, report, check_validity) -> Solution:
    """A run with its forward sensitivities (:mod:`gyrostat.sensitivity`). Its errors measured: a run
    with events is the engine's plain run (its state measured as every plain run's, its
    sensitivities against a tighter variational run); otherwise the variational run is the answer,
    and one tighter variational run over the whole span measures its state and its sensitivities."""
    _sensitivity.check(asked, opts)
    names, columns = _sensitivity.columns(model, names, opts.atol)
    try:
        event_times = None
        if len(opts.events):  # the answer is the engine's run, its events located there; the derivatives along it
            result = _core.solve(core, y0, t0, t1, opts, report)
            state, outputs, event_times, variational = _sensitivity.along(core, columns, y0, t0, result, opts, events,
                                                                          report)
        else:
            variational, state, outputs = _core.solve_sensitivities(core, columns, y0, t0, t1, opts, report)
            result = variational
        estimate = errors = None
        if mode and t1 != t0 and result.success and event_times is not None:
            estimate = measured([result], [core], _accuracy.SingleRun(core, y0, t0, report),
                                opts, t0, t1, mode, None, True, 0.0)[1][0]
            errors = _sensitivity.measure([core], [columns], [y0], t0, t1, opts, [state], names)[0]
        elif mode and t1 != t0 and result.success:
            (estimate,), (errors,) = _sensitivity.estimates([core], [columns], [y0], t0, opts, [result], [state], names)
    finally:
        if report is not None:
            _bars.close(report)
    solution = Solution(result, model)
    remarked = solution.notes != []  # (as solve's: a run with nothing to check or remark is returned as it is)
    _sensitivity.attach(solution, names, state, outputs, event_times, variational, errors)
    if estimate is not None:
        attach(solution, estimate)
    if result.success and (not check_validity or type(model).check is BASE_CHECK) and not remarked \
            and not solution._doubts:
        return solution
    return checked(solution, model, check_validity)


def solve(model, y0, t_span, *, method: str | None = None, rtol: float | None = None, atol: float | None = None,
          t_eval=None, n_out: int | None = None, every_step: bool | None = None, max_steps: int | None = None,
          first_step: float | None = None, max_step: float | None = None, step: float | None = None,
          splitting_order: int | None = None, sensitivity_error_control: bool | None = None,
          options: Options | None = None, events=None, dense_output: bool = False, progress: bool | Callable[[float], object] | None = None,
          check_validity: bool = True, accuracy: float | None = None,
          error_estimate: bool | str = True, compare: Callable | None = None,
          sensitivities: str | list[str] | None = None) -> Solution:
    """Solves any model from the initial state ``y0`` over ``t_span = (t0, t1)``.

    Parameters
    ----------
    model : gyrostat.ModelBase
        :class:`gyrostat.Model`, :class:`gyrostat.AveragedModel`, :class:`gyrostat.TriaxialAveragedModel`,
        :class:`gyrostat.MovingMassModel`, :class:`gyrostat.TorqueFreeModel`, :class:`gyrostat.lagrange.LagrangeTop`,
        :class:`gyrostat.lagrange.LagrangeAveraged` or :class:`gyrostat.orthogonal.OrthogonalModel`.
    y0 : array_like or Solution
        The initial state (``model.state_names``, units in ``model.units``), or a shorter one where the model completes it
        (ω alone for a model with attitude: identity quaternion; τ(0) = 0 for the orthogonal
        torque; a full top state for the averaged top: its (G_z, H, r)). Or a :class:`Solution`
        to continue its run: ``solve(model, sol, (sol.t_last, t1))`` starts from its last
        accepted state with the step it would have tried next (a run stopped by ``max_steps``
        or Ctrl-C, continued, follows the uninterrupted one: DOP853 step for step, Taylor and
        CVODE/ARKODE to the tolerance, since Taylor's step prediction and their multistep
        history restart).
    t_span : (float, float)
        (t0, t1), in s; t1 < t0 integrates backwards.
    method : str, optional
        The integrator, one of :data:`gyrostat.METHODS` or ``"auto"`` (DOP853, switching to
        CVODE BDF where the problem turns stiff). Default ``"dop853"``; with ``accuracy`` and no
        method, DOP853 or Taylor, whichever its probe predicts cheaper (Taylor where it covers the
        model, for accuracies ≤ 1e-5).
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
    sensitivity_error_control : bool, optional
        With ``sensitivities``: whether their errors join the state's in the step-size control
        (CVODES's ``errconS``). False (default, CVODES's too): the steps are the plain run's, so the
        derivatives leave the answer as it was; each one's error is measured and reported
        (``solution.sensitivity_errors``), not held to rtol. True: held to rtol and atol too, at the
        cost of the steps they take (1-1.6x the plain run's on ``bench/sensitivity_cost.py``'s
        cases). dop853 and taylor; cvode_bdf holds them always.
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
    sensitivities : str or list of str, optional
        Forward sensitivities to integrate with the run: the derivatives of the solution with
        respect to initial state components (by their names) and parameters (``"moments[0]"``,
        ``"LinearDamping.matrix[0,0]"``, ``"ViscousCavity.viscosity"``, …:
        :func:`gyrostat.sensitivity.parameter_names`), read with ``solution.sensitivity(name)``.
        Integrated by dop853 (or ``method="cvode_bdf"`` for a stiff model, ``method="taylor"``
        for a gyrostat under constant and linear torques) on the variational equations, with the
        plain run's steps (``sensitivity_error_control``: or held to rtol and atol too); with
        ``events``, ``solution.sensitivity(name, event=k)`` gives the event times' derivatives.
        Not with ``accuracy`` or another method (a ValueError says so).
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
    # the options in the order of OPTIONS, named here rather than read by option_values(locals()): that
    # costs ~1 us of the ~2 us a call adds to the engine (bench/python_overhead.py); the order is tested
    # (a list of output times as a tuple: it keys options_of's cache as it is)
    listed = type(t_eval) is list
    values = (method, rtol, atol, tuple(t_eval) if listed else t_eval, n_out, every_step, max_steps, first_step, max_step,
              step, splitting_order, sensitivity_error_control)
    try:
        core = model._core
    except AttributeError:
        core = core_of(model)
    opts = options_of(options, values, t_eval if listed else None)
    if events is not None or dense_output is not False:
        opts = with_events(opts, events, dense_output, core)
    t0, t1 = span(t_span)
    if type(y0) is not np.ndarray or y0.dtype is not _FLOAT:  # an array of floats needs no conversion
        if isinstance(y0, Solution):
            y0, opts = _continuation(y0, t0, opts, first_step)
        y0 = floats(y0, "y0")
    if y0.ndim != 1:
        raise ValueError(f"y0 must be one state (a 1-D array), got shape {y0.shape}")
    if atol is not None and atol > 1e-3:
        warn_loose_atol(atol, y0)
    check_validity = check_validity if check_validity is True else flag(check_validity, "check_validity")
    report = _bars.default() if progress is None else _bars.resolve(progress)
    mode = estimate_mode(error_estimate) if error_estimate is not True else "window"
    if compare is not None and not callable(compare):
        raise TypeError(f"compare must be a callable solution -> (n, m) array, not {type(compare).__name__}")
    asked = accuracy_asked(accuracy) if accuracy is not None else None
    if sensitivities is not None:
        return _with_sensitivities(model, core, y0, t0, t1, opts, sensitivities, events, asked, mode, report,
                                   check_validity)
    try:
        if asked is None and mode and compare is None and t1 != t0:  # the run and its estimate in one engine call
            result, estimate = _accuracy.solve_measured(core, y0, t0, t1, opts, report, mode == "full")
        elif asked is None:
            result = _core.solve(core, y0, t0, t1, opts, report)  # an exception of the user's callbacks propagates
            estimate = None
            if mode and t1 != t0 and result.success:
                estimate = _accuracy.estimate_run(_accuracy.Compared(core, compare, model), core, y0, t0, t1, opts,
                                                  result, report, mode == "full")
        elif not (explicit := rtol is not None or atol is not None or step is not None or options is not None) \
                and compare is None and t1 != t0:  # accuracy asked: the contract's single run
            result, estimate = _contract.meet_single(core, y0, t0, t1, opts, asked, _size(y0), report,
                                                     choose=method is None)
        else:
            size = _size(y0)
            measured_on = [_accuracy.Compared(core, compare, model) if compare else core]
            results, estimates = measured(None, measured_on, _accuracy.SingleRun(core, y0, t0, report),
                                          opts, t0, t1, mode, asked, explicit, size,
                                          choose_method=method is None and options is None)
            result, estimate = results[0], estimates[0]
    finally:
        if report is not None:
            _bars.close(report)
    solution = Solution(result, model)
    remarked = solution.notes != []  # the engine's notes and warnings (read once by Solution)
    if estimate is not None:
        attach(solution, estimate)
    if result.success and (not check_validity or type(model).check is BASE_CHECK) and not remarked \
            and not solution._doubts:
        return solution
    return checked(solution, model, check_validity)

