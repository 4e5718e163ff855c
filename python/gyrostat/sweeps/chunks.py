"""A chunk of a sweep's members, solved and recorded: the members' runs made (a member the
physics refuses: ``invalid_input``), grouped and solved one ensemble call per group (a member
whose run raises: ``failed``, alone), and what a sweep keeps of each written into the chunk's
arrays. The same in this process, in a worker process (Ctrl-C handled around the engine's run)
or on a Dask worker."""

from __future__ import annotations

import gc
import signal
from collections.abc import Sequence

import numpy as np

from gyrostat import _core
from gyrostat.events import variable_name
from gyrostat.kind import reusing
from gyrostat.schema import SceneError
from gyrostat.solution import Solution
from gyrostat.solution_views import sensitivity_column
from gyrostat.sweeps.plan import Plan

STATS = ("steps", "rhs_evals", "rejected_steps", "jacobian_evals", "nonlinear_conv_failures")


def _blank(plan: Plan, count: int, trajectories: bool, extrema: tuple[str, ...]) -> dict[str, np.ndarray]:
    """A chunk's arrays before any member is solved: NaN, zero counts, status ``interrupted``."""
    arrays: dict[str, np.ndarray] = {
        "status": np.full(count, "interrupted", dtype=object),
        "message": np.full(count, "not run: the sweep was stopped first", dtype=object),
        "terminal_event": np.full(count, "", dtype=object),
        "broken_assumptions": np.zeros(count, dtype=np.int64),
        "first_broken_assumption": np.full(count, "", dtype=object),
        "accuracy_warning": np.full(count, "", dtype=object),
        "error_estimate": np.full(count, np.nan),
    }
    for name in STATS:
        arrays[name] = np.zeros(count, dtype=np.int64)
    arrays["last_step"] = np.full(count, np.nan)
    arrays["t_final"] = np.full(count, np.nan)
    for name in plan.names:
        arrays[f"final_{name}"] = np.full(count, np.nan)
    for name in extrema:
        arrays[f"min_{name}"] = np.full(count, np.nan)
        arrays[f"max_{name}"] = np.full(count, np.nan)
    for name in plan.sensitivities:
        for quantity in plan.names:
            arrays[f"final_{sensitivity_column(quantity, name)}"] = np.full(count, np.nan)
    for label in plan.event_labels:
        arrays[f"first_{variable_name(label)}"] = np.full(count, np.nan)
        arrays[f"count_{variable_name(label)}"] = np.zeros(count, dtype=np.int64)
    if trajectories:
        arrays["t"] = np.full((count, plan.n_out), np.nan)
        for name in plan.names:
            arrays[name] = np.full((count, plan.n_out), np.nan)
    for parameter in plan.parameters:
        arrays[parameter.name] = np.full(count, np.nan)
    return arrays


def _record(arrays: dict, j: int, solution, plan: Plan, trajectories: bool, extrema: tuple[str, ...]) -> None:
    arrays["status"][j], arrays["message"][j] = solution.status, solution.message
    stats = solution.stats
    for name in STATS:
        arrays[name][j] = stats[name]
    arrays["last_step"][j] = stats["last_step"]
    n = len(solution)
    if n:
        arrays["t_final"][j] = solution.t[-1]
        if solution.state_names + solution.output_names == plan.names:  # one matrix: no per-name look-ups
            table = np.hstack([solution.y, solution._result.outputs]) if plan.output_names else solution.y
            present = plan.names
        else:  # a member whose model names differ: by name, NaN where it has no such quantity
            present = tuple(name for name in plan.names if name in solution)
            table = np.column_stack([solution[name] for name in present]) if present else np.empty((n, 0))
        for k, name in enumerate(present):
            arrays[f"final_{name}"][j] = table[-1, k]
        if extrema:
            low, high = table.min(axis=0), table.max(axis=0)
            for k, name in enumerate(present):
                if name in extrema:
                    arrays[f"min_{name}"][j], arrays[f"max_{name}"][j] = low[k], high[k]
        if trajectories:
            m = min(n, plan.n_out)
            arrays["t"][j, :m] = solution.t[:m]
            for k, name in enumerate(present):
                arrays[name][j, :m] = table[:m, k]
    for label, times in zip(solution.event_names, solution.t_events):
        if label in plan.event_labels:
            key = variable_name(label)
            arrays[f"count_{key}"][j] = len(times)
            if len(times):
                arrays[f"first_{key}"][j] = times[0]
    if solution.terminal_event is not None:
        arrays["terminal_event"][j] = solution.event_names[solution.terminal_event]


def _record_results(arrays: dict, rows: list[int], results: list, models: list, plan: Plan, trajectories: bool,
                    extrema: tuple[str, ...]) -> list[str]:
    """:func:`_record` for the members of one ensemble call (chunk rows ``rows``, the engine's
    ``Result`` of each and its model, one or one per member), in bulk: for a summaries-only sweep
    without events, status, message, statistics, final values and extrema as columns over the
    members (``_core.summaries``, one pass in C++); a member with a terminal event or other names
    than the plan's, and every member of a sweep that keeps trajectories or events, by
    :func:`_record`. Returns each member's first accuracy warning ("" for none)."""
    model_of = (lambda k: models[0]) if len(models) == 1 else models.__getitem__
    for j, found in zip(rows, getattr(results, "sensitivities", ())):
        _record_sensitivities(arrays, j, found, plan)
    if trajectories or plan.event_labels:
        for k, (j, r) in enumerate(zip(rows, results)):
            _record(arrays, j, Solution(r, model_of(k)), plan, trajectories, extrema)
        return [r.warnings[0] if len(r.warnings) else "" for r in results]
    columns = _core.summaries(results, plan.state_names, plan.output_names, bool(extrema))
    rows = np.asarray(rows, dtype=np.intp)
    arrays["status"][rows] = columns["status"]
    arrays["message"][rows] = columns["message"]
    for name in STATS + ("last_step",):
        arrays[name][rows] = columns[name]
    ran = columns["rows"] > 0
    bulk = ran & columns["named"] & (columns["terminal_event"] < 0)
    for k in np.flatnonzero(ran & ~bulk):  # a terminal event, or a model with other names: by name
        _record(arrays, rows[k], Solution(results[k], model_of(k)), plan, trajectories, extrema)
    chosen = rows[bulk]
    arrays["t_final"][chosen] = columns["t_final"][bulk]
    finals = columns["final"][bulk]
    for c, name in enumerate(plan.names):
        arrays[f"final_{name}"][chosen] = finals[:, c]
        if name in extrema:
            arrays[f"min_{name}"][chosen] = columns["min"][bulk, c]
            arrays[f"max_{name}"][chosen] = columns["max"][bulk, c]
    return columns["warning"]


def _record_sensitivities(arrays: dict, j: int, found: tuple, plan: Plan) -> None:
    """A member's derivatives of its final state and outputs (``found``: names, ∂y/∂p, ∂outputs/∂p
    at its output times, as :class:`gyrostat.sensitivity.MemberResults` holds them)."""
    names, state, outputs = found[:3]
    if not len(state):
        return
    final = np.vstack([state[-1], outputs[-1]])  # (state + outputs, columns), in the plan's order
    for c, name in enumerate(names):
        for k, quantity in enumerate(plan.names[:len(final)]):
            key = f"final_{sensitivity_column(quantity, name)}"
            if key in arrays:
                arrays[key][j] = final[k, c]


def _put_values(arrays: dict, plan: Plan, drawn: list[tuple[float, ...]]) -> None:
    """The members' parameter values (one tuple per member) into their columns of a chunk."""
    for k, parameter in enumerate(plan.parameters):
        arrays[parameter.name][:] = [values[k] for values in drawn]


def solve_chunk(plan: Plan, start: int, stop: int, *, threads: int = 0, trajectories: bool = True,
                extrema: Sequence[str] = (), check_validity: bool = True, error_estimate: bool = True,
                progress=None) -> dict[str, np.ndarray]:
    """Solves members ``start`` to ``stop - 1`` of a plan and returns their arrays (what a sweep
    keeps of each). Members that share options are one :func:`gyrostat.solve_ensemble` call on
    ``threads`` C++ threads; a member the physics refuses gets status ``invalid_input``, a member
    whose run raises (a user's torque) status ``failed`` and its exception as message; with
    ``check_validity``, the assumptions of an averaged model are checked along each member (the
    count of broken ones and the first, per member). The same on every machine: a Dask task
    runs exactly this.

    Parameters
    ----------
    plan : Plan
        The sweep.
    start, stop : int
        The members, ``range(start, stop)``.
    threads : int, optional
        C++ threads (≤ 0: every core).
    trajectories : bool, optional
        Keep each member's trajectory.
    extrema : sequence of str, optional
        Quantities whose minimum and maximum are kept.
    check_validity : bool, optional
        Check an averaged model's assumptions along each member.
    error_estimate : bool, optional
        Measure each member's global error (``error_estimate``; :mod:`gyrostat.accuracy`), default True.
    progress : callable, optional
        Called with the number of members finished.

    Examples
    --------
    >>> from gyrostat import sweeps
    >>> from gyrostat.scene import SCENES
    >>> plan = sweeps.Plan(SCENES / "forced_damped.toml", {"torques[0].moment[2]": [0.05, 0.1]})
    >>> chunk = sweeps.solve_chunk(plan, 0, 2, trajectories=False)
    >>> list(chunk["status"]), chunk["final_r"].round(4)  # r in rad/s at t1
    (['success', 'success'], array([1.4521, 2.9912]))
    """
    return _solve_members(plan, _members(plan, start, stop, trajectories, tuple(extrema)), threads=threads,
                          trajectories=trajectories, extrema=tuple(extrema), check_validity=check_validity,
                          error_estimate=error_estimate, progress=progress)


def _members(plan: Plan, start: int, stop: int, trajectories: bool, extrema: tuple[str, ...]) -> tuple[dict, dict]:
    """The first half of :func:`solve_chunk`, pure Python: the chunk's arrays with every member's
    values (and the refused members' status), and the runs grouped by span, options and events."""
    count = stop - start
    arrays = _blank(plan, count, trajectories, extrema)
    arrays["interrupted"] = np.zeros(1, dtype=bool)
    groups: dict[tuple, list] = {}
    drawn = plan.values_range(start, stop)
    _put_values(arrays, plan, drawn)
    # the members' documents, models and runs are many small containers kept to the chunk's end: the cyclic
    # collector, paused while they are made, would otherwise pass over them again and again (~15% of the time)
    collecting = gc.isenabled()
    gc.disable()
    try:
        with reusing(plan.base):  # the body and torques no parameter changes: built once for the chunk
            for j, values in enumerate(drawn):
                try:
                    run = plan.member(values)
                except (SceneError, ValueError) as error:
                    arrays["status"][j], arrays["message"][j] = "invalid_input", " ".join(str(error).split())
                    continue
                options = tuple(sorted((k, tuple(v) if isinstance(v, list) else v)  # (lists, e.g. sensitivities: as keys)
                                       for k, v in run.options.items() if k != "events"))
                key = (run.t_span, options, tuple(run.options.get("events", ())))
                groups.setdefault(key, []).append((j, run))
    finally:
        if collecting:
            gc.enable()
    return arrays, groups


def _solve_members(plan: Plan, members_of_chunk: tuple[dict, dict], *, threads: int, trajectories: bool,
                   extrema: tuple[str, ...], check_validity: bool, progress,
                   error_estimate: bool = True) -> dict[str, np.ndarray]:
    """The second half of :func:`solve_chunk`: the groups solved (one solve_ensemble each, the
    engine's pool with the GIL released) and each member's summary recorded."""
    from gyrostat.modelbase import ModelBase
    from gyrostat.solve import ensemble_results

    arrays, groups = members_of_chunk
    count = len(arrays["status"])
    done = count - sum(len(members) for members in groups.values())
    for (span, options, events), members in groups.items():
        size, share = len(members), len(members) / count

        def report(fraction, before=done / count, share=share):
            progress(before + share * fraction)

        # the engine's results, not a Solution per member: the summaries are made in bulk (_record_results);
        # each member's doubts are recorded (accuracy_warning), not warned about
        models = [run.model for _, run in members]
        starts = [run.y0 for _, run in members]
        if len({len(y0) for y0 in starts}) == 1:
            starts = np.stack(starts)  # one (members, dim) array: converted once, not member by member
        with _interruptible():
            try:
                _, results, estimates = ensemble_results(models, starts, span, threads=threads,
                                                          events=list(events) or None,
                                                          error_estimate=error_estimate,
                                                          progress=report if progress is not None else False,
                                                          **dict(options))
            except Exception:  # a member's run raised (a user's torque): each member solved alone
                members, results = _one_by_one(arrays, members, span, events, options, threads,
                                               report if progress is not None else None)
                estimates = [None] * len(results)
                models = [run.model for _, run in members]
        rows = [j for j, _ in members]
        if rows:
            arrays["accuracy_warning"][rows] = _record_results(arrays, rows, results, models, plan, trajectories,
                                                               extrema)
            for j, estimate in zip(rows, estimates):
                if estimate is not None:
                    arrays["error_estimate"][j] = estimate.value
                    if estimate.warning and not arrays["accuracy_warning"][j]:
                        arrays["accuracy_warning"][j] = estimate.warning
        checked = {kind: check_validity and kind.check is not ModelBase.check for kind in {type(m) for m in models}}
        for (j, run), result in zip(members, results):
            if checked[type(run.model)] and len(result.t):
                broken = [str(a) for a in run.model.check(Solution(result, run.model)) if not a.holds]  # the averaging's
                arrays["broken_assumptions"][j] = len(broken)
                arrays["first_broken_assumption"][j] = broken[0] if broken else ""
        done += size
        if any(r.status == "interrupted" for r in results):
            arrays["interrupted"][0] = True
            break
    return arrays


def _said(error: BaseException) -> str:
    """An exception as one line of a member's ``message``: its type and its words."""
    return f"{type(error).__name__}: {' '.join(str(error).split())}"


def _one_by_one(arrays: dict, members: list, span, events, options, threads: int, report) -> tuple[list, list]:
    """The members of an ensemble call that raised (the engine raises the first exception a
    member's run raised, a user's torque's, once the members have finished), solved again one
    at a time, so that an exception is its own member's alone: that member gets status
    ``failed`` and the exception as its message, every other member the result of its own run
    (an ensemble of one: the numbers of its lane in the call, bit for bit). Returns the members
    that returned a result and their results; stops at a member Ctrl-C interrupted (the later
    ones stay ``interrupted``)."""
    from gyrostat.solve import ensemble_results

    solved, results = [], []
    for k, (j, run) in enumerate(members):
        try:
            _, (result,), _ = ensemble_results([run.model], [run.y0], span, threads=threads,
                                            events=list(events) or None, progress=False, **dict(options))
        except Exception as error:  # this member's own: recorded, the others go on
            arrays["status"][j], arrays["message"][j] = "failed", _said(error)
        else:
            solved.append((j, run))
            results.append(result)
            if result.status == "interrupted":
                break
        if report is not None:
            report((k + 1) / len(members))
    return solved, results


# A worker process's sweep: the plan and the options, set once when the worker starts (a fork
# inherits them; they are not sent with every chunk).
_WORKER: dict = {}


def _stop_once(signum, frame):
    """A worker's Ctrl-C: the first stops the engine (KeyboardInterrupt, which the engine takes as
    Ctrl-C: it returns what it computed); a second (the terminal's and the parent's) is ignored,
    so that it cannot strike the results on their way back."""
    if not _WORKER.get("stopped"):
        _WORKER["stopped"] = True
        raise KeyboardInterrupt


class _interruptible:
    """In a worker process, around the engine's run: Ctrl-C (forwarded by the parent) stops the
    engine, which returns what it computed, as in the parent; outside it a worker ignores Ctrl-C, so
    that an idle worker never dies of it. Elsewhere: nothing."""

    def __enter__(self):
        if _WORKER:
            signal.signal(signal.SIGINT, _stop_once)
            if _WORKER["stopping"].is_set() or _WORKER.get("stopped"):  # the sweep was stopped while this chunk's members were made
                raise KeyboardInterrupt

    def __exit__(self, *exc):
        if _WORKER:
            signal.signal(signal.SIGINT, signal.SIG_IGN)
        return False
