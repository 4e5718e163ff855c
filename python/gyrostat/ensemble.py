"""Many runs at once: :func:`solve_ensemble` solves N trajectories in one call on a pool of C++
threads (SIMD batches where they apply), :func:`ensemble_results` the same up to the engine's
results, for callers that summarise many members at once (the sweeps). ``gyrostat.solve``
re-exports both."""

from __future__ import annotations

from collections.abc import Callable, Sequence

import numpy as np

from gyrostat import _core
from gyrostat import accuracy as _accuracy
from gyrostat import progress as _bars
from gyrostat import sensitivity as _sensitivity
from gyrostat.answer import accuracy_asked, attach, checked, estimate_mode, measured
from gyrostat.arguments import flag, floats, shown
from gyrostat.modelbase import ModelBase, core_of
from gyrostat.options import (OPTION_NAMES, Options, check_output_memory, option_values, options_of, span,
                              warn_loose_atol, with_events)
from gyrostat.solution import Solution


def solve_ensemble(models: ModelBase | Sequence[ModelBase], y0s, t_span, *, threads: int = 0,
                   method: str | None = None, rtol: float | None = None, atol: float | None = None, t_eval=None,
                   n_out: int | None = None, every_step: bool | None = None, max_steps: int | None = None,
                   first_step: float | None = None, max_step: float | None = None, step: float | None = None,
                   splitting_order: int | None = None, sensitivity_error_control: bool | None = None,
                   options: Options | None = None, events=None, dense_output: bool = False, progress: bool | Callable[[float], object] | None = None,
                   check_validity: bool = True, batch: bool = True, accuracy: float | None = None,
                   error_estimate: bool | str = True, sensitivities: str | list[str] | None = None) -> list[Solution]:
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
    sensitivity_error_control : bool, optional
        As in :func:`solve`: whether the sensitivities' errors join the state's in the step-size
        control (default False: the plain runs' steps).
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
    sensitivities : str or list of str, optional
        As in :func:`solve`: each member's derivatives with respect to these names (its own
        parameters moved on its own model), ``solutions[i].sensitivity(name)``.

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
    given = dict(zip(OPTION_NAMES, option_values(locals())))
    check_validity = flag(check_validity, "check_validity")
    models, results, estimates = ensemble_results(
        models, y0s, t_span, threads=threads, **given, options=options, events=events, dense_output=dense_output,
        progress=progress, batch=batch, accuracy=accuracy, error_estimate=error_estimate, sensitivities=sensitivities)
    solutions = [attach(Solution(r, models[0] if len(models) == 1 else models[i]), e)
                 for i, (r, e) in enumerate(zip(results, estimates))]
    for solution, found in zip(solutions, getattr(results, "sensitivities", ())):
        _sensitivity.attach(solution, *found)
    return [checked(s, s.model, check_validity) if s.success or s.accuracy_warnings else s for s in solutions]


def _largest(y0s) -> float:
    """The largest |component| of the initial states (the accuracy contract's atol scale; 1 for none)."""
    if isinstance(y0s, np.ndarray) and y0s.ndim == 2 and y0s.size:
        return float(np.abs(y0s).max())
    return max((float(np.max(np.abs(y))) for y in y0s if len(y)), default=1.0)


def ensemble_results(models, y0s, t_span, *, threads: int = 0, method=None, rtol=None, atol=None, t_eval=None,
                      n_out=None, every_step=None, max_steps=None, first_step=None, max_step=None, step=None,
                      splitting_order=None, sensitivity_error_control=None, options=None, events=None,
                      dense_output=False, progress=None,
                      batch=True, accuracy=None, error_estimate=False, sensitivities=None) -> tuple[list, list, list]:
    """:func:`solve_ensemble` up to the engine's results, without a :class:`Solution` per member:
    for callers that summarise many members at once (:func:`gyrostat.sweeps.solve_chunk`).

    Parameters
    ----------
    models, y0s, t_span, threads, method, rtol, atol, t_eval, n_out, every_step, max_steps, first_step, max_step, \
step, splitting_order, sensitivity_error_control, options, events, dense_output, progress, batch, accuracy, \
error_estimate, sensitivities
        As in :func:`solve_ensemble` (which checks them the same way); ``error_estimate`` defaults
        to False here. With ``sensitivities``, the results are a
        :class:`gyrostat.sensitivity.MemberResults` (each member's derivatives beside its Result).

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
    values = option_values(locals())
    if isinstance(models, ModelBase):
        models = [models]
    models = list(models)
    if not models:
        raise ValueError("solve_ensemble needs at least one model")
    cores = [core_of(m) for m in models]
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
    opts = options_of(options, values)
    if events is not None or dense_output is not False:
        if len({tuple(c.state_names) + tuple(c.output_names) for c in cores}) > 1:
            raise ValueError("events in an ensemble need members of one family (the same state and output names)")
        opts = with_events(opts, events, dense_output, cores[0])
    t0, t1 = span(t_span)
    if atol is not None and atol > 1e-3:
        warn_loose_atol(atol, np.abs(np.asarray(y0s[0] if isinstance(y0s, list) else y0s, float)).max(axis=0))
    if isinstance(threads, bool) or not isinstance(threads, (int, np.integer)) or abs(threads) > 4096:
        raise ValueError(f"threads = {threads!r} must be a whole number of at most 4096 (<= 0: one per core)")
    batch = flag(batch, "batch")
    outputs = len(opts.t_eval) or opts.n_out
    check_output_memory(cores, count, outputs, f"{count} members x {outputs} output times")
    mode = estimate_mode(error_estimate)
    asked = accuracy_asked(accuracy)
    report = _bars.resolve(progress, total=count, unit="member")

    run = _accuracy.EnsembleRun(cores, y0s, t0, count, int(threads), report, batch)  # (all members: with the progress)

    try:
        if sensitivities is not None:
            _sensitivity.check(asked, opts)
            if len(opts.events):  # the engine's runs, their events located there; the derivatives along them
                results = _sensitivity.ensemble_along(models, cores, y0s, t0, opts, sensitivities,
                                                      run(opts, t1, list(range(count))), events)
            else:
                results = _sensitivity.ensemble(models, cores, y0s, t0, t1, opts, sensitivities, int(threads), report)
            estimates = [None] * count
            if mode:  # each member measured as solve measures one run with sensitivities
                column_sets = [_sensitivity.columns(m, sensitivities, opts.atol)[1] for m in models]
                found = results.sensitivities
                names, states = (found[0][0] if found else ()), [f[1] for f in found]
                if len(opts.events):  # plain answers: their states as every plain run's
                    errors = _sensitivity.measure(cores, column_sets, y0s, t0, t1, opts, states, names, int(threads))
                    size = _largest(y0s)
                    estimates = measured(list(results), cores * count if len(cores) == 1 else cores, run, opts, t0, t1,
                                         mode, None, True, size)[1]
                else:  # the variational runs are the answers: one tighter variational run measures both
                    estimates, errors = _sensitivity.estimates(cores, column_sets, y0s, t0, opts, list(results), states,
                                                               names, int(threads))
                results.sensitivities = [f + (e,) for f, e in zip(found, errors)]
            return models, results, estimates
        if not mode and asked is None:
            return models, run(opts, t1, list(range(count))), [None] * count
        explicit = rtol is not None or atol is not None or step is not None or options is not None
        size = _largest(y0s)
        results, estimates = measured(None, cores * count if len(cores) == 1 else cores, run, opts, t0, t1, mode,
                                       asked, explicit, size, choose_method=method is None and options is None)
    finally:
        _bars.close(report)
    return models, results, estimates
