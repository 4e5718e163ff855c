"""A sweep run: :func:`sweep` checks its arguments, cuts the members into chunks and runs them
in this process (the next chunk's members made on a helper thread), on forked worker processes
or on a Dask cluster; every member is recorded, finished, failed or interrupted (Ctrl-C)."""

from __future__ import annotations

import itertools
import json
import math
import os
import signal
import sys
import time
import warnings
from collections.abc import Iterable, Sequence
from pathlib import Path

import numpy as np

from gyrostat import _core
from gyrostat import progress as _bars
from gyrostat.arguments import flag
from gyrostat.sweeps.chunks import _WORKER, _blank, _members, _put_values, _said, _solve_members, solve_chunk
from gyrostat.sweeps.plan import Plan
from gyrostat.sweeps.storage import _finish, _Memory, _NetCDF

WORKERS_FROM = 10_000
"""Members from which a sweep on this machine runs on worker processes by default (``workers=None``,
where the platform forks): below it, forking the workers and their first chunk cost more than
making members on one helper thread beside the engine's."""


# ------------------------------------------------------------------------------------ the sweep
def _chunk_size(plan: Plan, trajectories: bool, extrema: tuple[str, ...], workers: int) -> int:
    per_member = sum(a.nbytes if a.dtype != object else 64 for a in _blank(plan, 1, trajectories, extrema).values())
    by_memory = max(1, (64 * 2**20) // (2 * per_member))  # the chunk's arrays and the engine's results
    by_balance = max(1, math.ceil(plan.size / (4 * workers)))  # a few chunks per worker at least
    return int(min(by_memory, by_balance, 8192))


def sweep(scene, vary, *, samples: int | None = None, seed: int | None = None, run: str | None = None,
          trajectories: bool = True, extrema: Sequence[str] | None = None, chunk_size: int | None = None,
          threads: int = 0, workers: int | None = None, client=None, path: str | Path | None = None,
          check_validity: bool = True, progress=None, allow_import: Iterable[str] | str | None = None,
          error_estimate: bool = True):
    """Solves a scene for every member of a grid or a dispersion of its numeric entries.

    Parameters
    ----------
    scene:
        A scene file, a scene document (dict) or a :class:`gyrostat.scene.Scene`; or a
        :class:`Plan` made already (``vary``, ``samples``, ``seed`` and ``run`` are then its own).
    vary:
        ``{path: values}`` (a grid: the product of the value lists), ``{path: distribution}``
        (a dispersion: :class:`Uniform`, :class:`Normal`, :class:`LogUniform`), or a list of
        :class:`Parameter` (a name, several paths, a scale).
    samples, seed:
        The number of members of a dispersion and its seed (None: a fresh seed, recorded in
        ``attrs["seed"]``); member i draws from ``SeedSequence(seed, spawn_key=(i,))``.
    run:
        The scene's run to sweep (default: its only run, or ``"full"``).
    trajectories:
        Keep every member's trajectory (dimension ``time``); False keeps only the summaries.
    extrema:
        Quantities whose minimum and maximum over the output times are kept (default: every
        named output of the run's model).
    chunk_size, threads:
        Members per ensemble call (default: about 64 MB of results, at least 4 chunks per
        worker) and C++ threads per chunk (≤ 0: every core here; 1 per task on Dask).
    workers:
        Processes on this machine, each making its chunks' members and solving them on one C++
        thread (SciPy's convention: ``-1`` one per core). ``1``: this process alone, the next
        chunk's members made on a helper thread while the engine's threads solve the current one;
        Python's lock keeps that helper to one core, so that making members bounds the throughput
        (~30 us a member) whatever the cores. None (default): one per core when the sweep has
        at least :data:`WORKERS_FROM` members, ``threads ≤ 0`` and the platform forks (Linux),
        else 1. Workers are forks of this process (elsewhere spawned: the calling script then
        needs the ``if __name__ == "__main__":`` guard, as with Dask). Ignored with ``client``.
    client:
        A ``dask.distributed.Client``: chunks become tasks on its cluster; the results are
        identical to the local ones.
    path:
        Stream each chunk to this NetCDF file as it finishes (memory bounded by a chunk) and
        return the file opened lazily (along ``member``; :func:`open_sweep` reshapes a grid).
    check_validity:
        Check an averaged model's assumptions along every member (``broken_assumptions``,
        ``first_broken_assumption``): how far to trust each member's answer.
    error_estimate:
        Measure every member's global error (the variable ``error_estimate``, relative;
        :mod:`gyrostat.accuracy`; with the scene's ``integration.accuracy`` each member meets it).
        Default True; False saves its cost (~0.3–0.5 of each run).
    progress:
        None: a bar over the members in a terminal; True, False, or a callable of the fraction.
    allow_import:
        Modules whose code a scene file or document may name besides the scene file's folder
        (:mod:`gyrostat.scene_code`); the same rule holds on every worker.

    Returns
    -------
    xarray.Dataset
        See the module's documentation. Ctrl-C stops the sweep: the members finished are kept,
        the others have status ``"interrupted"`` (``attrs["interrupted"] = 1``) and a warning
        says how many. Results equal the members solved one by one with :func:`gyrostat.solve`
        bit for bit, except members that :func:`gyrostat.solve_ensemble` integrates in SIMD
        batches (``taylor`` or ``dop853`` on the gyrostat with constant and linear torques,
        ``dop853`` with vectorised compiled user torques besides, the averaged model under
        ``dop853``), which equal them to the tolerance.

    Examples
    --------
    The spin-down of a symmetric body under linear damping over a grid of two damping rates:
    the axial rate r decays as exp(-D t / C), to exp(-1) at t = 10 s for D = 0.1 N m s.

    >>> import gyrostat
    >>> scene = {"body": {"moments": [2.0, 2.0, 1.0]},
    ...          "torques": [{"type": "linear_damping", "diagonal": [0.1, 0.1, 0.1]}],
    ...          "initial": {"omega": [0.1, 0.0, 1.0]},
    ...          "integration": {"model": "full", "t_span": [0.0, 10.0], "n_out": 11}}
    >>> ds = gyrostat.sweep(scene, {"torques[0].diagonal[2]": [0.1, 0.2]}, trajectories=False, progress=False)
    >>> [round(float(r), 4) for r in ds["final_r"].values]
    [0.3679, 0.1353]
    """
    plan = scene if isinstance(scene, Plan) else Plan(scene, vary, samples=samples, seed=seed, run=run,
                                                                allow_import=allow_import)
    if trajectories and getattr(plan, "varies_n_out", False):
        raise ValueError("integration.n_out varies across members: their trajectories differ in length; keep "
                         "summaries only (trajectories=False)")
    if extrema is None:
        extrema = plan.output_names
    extrema = tuple(extrema)
    unknown = [name for name in extrema if name not in plan.names]
    if unknown:
        raise ValueError(f"extrema: {unknown} are not quantities of the run ({', '.join(plan.names)})")
    processes = _processes(workers, threads, plan.size) if client is None else 1
    workers = len(client.scheduler_info()["workers"]) if client is not None else processes
    if chunk_size is None:
        chunk_size = _chunk_size(plan, trajectories, extrema, workers)
    if isinstance(chunk_size, bool) or not isinstance(chunk_size, (int, np.integer)) or chunk_size < 1:
        raise ValueError(f"chunk_size = {chunk_size!r} must be a positive integer")
    if isinstance(threads, bool) or not isinstance(threads, (int, np.integer)) or abs(threads) > 4096:
        raise ValueError(f"threads = {threads!r} must be a whole number of at most 4096 (<= 0: one per core)")
    sink = _NetCDF(plan, path, trajectories, extrema) if path is not None else _Memory(plan, trajectories, extrema)
    ranges = [(s, min(s + chunk_size, plan.size)) for s in range(0, plan.size, chunk_size)]
    bar = _bars.resolve(progress, total=plan.size, unit="member", description=f"sweep {plan.scene_name}")
    started = time.perf_counter()
    options = {"trajectories": trajectories, "extrema": extrema, "check_validity": flag(check_validity, "check_validity"),
               "error_estimate": flag(error_estimate, "error_estimate")}
    try:
        if client is None and processes > 1:
            finished = _run_processes(plan, ranges, sink, bar, processes, threads, options)
        elif client is None:
            finished = _run_local(plan, ranges, sink, bar, threads, options)
        else:
            finished = _run_dask(plan, ranges, sink, bar, client, threads, options)
    finally:
        _bars.close(bar)
    missing = [r for r in ranges if r not in finished]
    for start, stop in missing:  # never run: written as such, so that no member is lost
        blank = _blank(plan, stop - start, trajectories, extrema)
        _put_values(blank, plan, plan.values_range(start, stop))
        sink.put(start, blank)
    attrs = {"gyrostat_version": _core.__version__, "scene": plan.scene_name, "kind": plan.kind_name,
             "run": plan.run, "model": plan.model_choice, "model_reason": plan.model_reason, "mode": plan.mode,
             "members": plan.size, "seconds": time.perf_counter() - started,
             "interrupted": int(bool(missing) or finished.get("interrupted", False)),
             "plan": json.dumps(plan.describe()), "extrema": json.dumps(list(extrema))}
    if plan.seed is not None:
        attrs["seed"] = plan.seed
    ds = sink.close(plan, attrs)
    if attrs["interrupted"]:
        unfinished = int((ds["status"] == "interrupted").sum())
        warnings.warn(f"sweep interrupted: {plan.size - unfinished} of {plan.size} members finished; the others have "
                      "status 'interrupted'", RuntimeWarning, stacklevel=2)
    return ds if path is not None else _finish(ds, plan.describe())


def _run_local(plan, ranges, sink, bar, threads, options) -> dict:
    """The chunks in turn on this machine. The next chunk's members are made (Python) on a helper
    thread while this thread solves the current one (C++, the GIL released) and records it: the
    same members, values and results as :func:`solve_chunk`, with the Python work beside the
    engine's instead of between its runs. Ctrl-C reaches the engine as in one solve_ensemble call
    (this thread runs it)."""
    from concurrent.futures import ThreadPoolExecutor

    finished: dict = {}
    done = 0
    making = (options["trajectories"], tuple(options["extrema"]))
    solving = {k: v for k, v in options.items() if k not in ("trajectories", "extrema")}
    helper = ThreadPoolExecutor(max_workers=1, thread_name_prefix="gyrostat-sweep-members")
    upcoming = helper.submit(_members, plan, *ranges[0], *making) if ranges else None
    try:
        for index, (start, stop) in enumerate(ranges):
            members = upcoming.result()
            if index + 1 < len(ranges):
                upcoming = helper.submit(_members, plan, *ranges[index + 1], *making)
            report = None if bar is None else (lambda f, d=done, n=stop - start: bar((d + f * n) / plan.size))
            chunk = _solve_members(plan, members, threads=threads, trajectories=making[0], extrema=making[1],
                                   progress=report, **solving)
            sink.put(start, chunk)
            finished[(start, stop)] = True
            done += stop - start
            if bar is not None:
                bar(done / plan.size)
            if chunk["interrupted"][0]:
                finished["interrupted"] = True
                break
    except KeyboardInterrupt:
        finished["interrupted"] = True
    finally:
        helper.shutdown(wait=True, cancel_futures=True)
    return finished


def _cores() -> int:
    try:
        return len(os.sched_getaffinity(0))  # the cores this process may run on (a container's share)
    except AttributeError:
        return os.cpu_count() or 1


def _forks() -> bool:
    import multiprocessing

    return sys.platform.startswith("linux") and "fork" in multiprocessing.get_all_start_methods()


def _daemon() -> bool:
    """Whether this process is a daemon (a Dask worker's, a multiprocessing pool's): it may not
    start processes of its own."""
    import multiprocessing

    return multiprocessing.current_process().daemon


def _processes(workers, threads, members: int) -> int:
    """The worker processes of a sweep run here (:func:`sweep`'s ``workers``); 1: this process."""
    if workers is None:
        return _cores() if members >= WORKERS_FROM and threads <= 0 and _forks() and not _daemon() else 1
    if isinstance(workers, bool) or not isinstance(workers, (int, np.integer)) or workers == 0 or workers < -1 \
            or workers > 4096:
        raise ValueError(f"workers = {workers!r} must be a positive whole number of at most 4096, -1 (one per core) "
                         "or None (chosen from the sweep's size)")
    processes = _cores() if workers == -1 else int(workers)
    if processes > 1 and _daemon():
        raise ValueError(f"workers = {workers!r}: this process is a daemon (a Dask worker's or a process pool's) and "
                         "cannot start processes; use workers=1 (or client= to run the chunks on Dask)")
    return processes


def _worker_start(plan, options: dict, stopping) -> None:
    """A worker process's start: Ctrl-C is the parent's to handle (it sets ``stopping`` and
    forwards the signal; a worker takes it only while the engine runs: :func:`_interruptible`);
    the sweep kept."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    _WORKER.update(plan=plan, options=options, stopping=stopping)


def _worker_chunk(start: int, stop: int) -> dict:
    if _WORKER["stopping"].is_set():  # queued before the sweep was stopped: not run
        raise KeyboardInterrupt
    return solve_chunk(_WORKER["plan"], start, stop, **_WORKER["options"])


def _run_processes(plan, ranges, sink, bar, processes, threads, options) -> dict:
    """The chunks on ``processes`` forked worker processes (one C++ thread each, or ``threads``):
    each makes its chunks' members and solves them, :func:`solve_chunk` as on Dask, so that making
    members runs on every core instead of one helper thread. Ctrl-C: the chunks finished are kept,
    the running ones stop and return what they computed (the parent forwards the signal to its
    workers), the others are not run."""
    import multiprocessing
    from concurrent.futures import FIRST_COMPLETED, ProcessPoolExecutor, wait
    from concurrent.futures.process import BrokenProcessPool

    context = multiprocessing.get_context("fork" if _forks() else "spawn")
    per_chunk = threads if threads > 0 else 1
    stopping = context.Event()
    pool = ProcessPoolExecutor(processes, mp_context=context, initializer=_worker_start,
                               initargs=(plan, {**options, "threads": per_chunk}, stopping))
    finished: dict = {}
    queue = iter(ranges)
    running: dict = {}
    done = 0

    def unsolved(start: int, stop: int, error: BaseException) -> dict:
        """A chunk no worker returned: its members' values, and why (Ctrl-C: interrupted)."""
        chunk = _blank(plan, stop - start, options["trajectories"], options["extrema"])
        if isinstance(error, KeyboardInterrupt):
            chunk["interrupted"] = np.ones(1, dtype=bool)
        else:
            chunk["status"][:] = "failed"
            chunk["message"][:] = f"the worker process failed: {_said(error)}"
        _put_values(chunk, plan, plan.values_range(start, stop))
        return chunk

    def submit(count: int) -> None:
        for start, stop in itertools.islice(queue, count):
            try:
                running[pool.submit(_worker_chunk, start, stop)] = (start, stop)
            except BrokenProcessPool as error:  # a worker died (killed, out of memory): no chunk runs any more
                for first, last in [(start, stop), *queue]:
                    put(first, last, unsolved(first, last, error))
                return

    def put(start: int, stop: int, chunk: dict) -> None:
        nonlocal done
        sink.put(start, chunk)
        finished[(start, stop)] = True
        if chunk.get("interrupted", np.zeros(1, bool))[0]:
            finished["interrupted"] = True
        done += stop - start
        if bar is not None:
            bar(done / plan.size)

    def take(future) -> None:
        start, stop = running.pop(future)
        try:
            chunk = future.result()
        except BaseException as error:  # noqa: B036 - a worker lost, or stopped by Ctrl-C before its engine ran
            chunk = unsolved(start, stop, error)
        put(start, stop, chunk)

    try:
        try:
            submit(2 * processes)
            while running and not finished.get("interrupted"):
                completed, _ = wait(list(running), return_when=FIRST_COMPLETED)
                for future in completed:
                    take(future)
                submit(len(completed))
        except KeyboardInterrupt:
            finished["interrupted"] = True
        if finished.get("interrupted"):
            stopping.set()
            for future in list(running):
                if future.cancel():
                    running.pop(future)
            for process in list(getattr(pool, "_processes", {}).values()):  # the workers' engines stop
                try:
                    os.kill(process.pid, signal.SIGINT)
                except OSError:
                    pass
            for future in list(running):  # what the running chunks computed
                take(future)
    finally:
        pool.shutdown(wait=True, cancel_futures=True)
    return finished


def _run_dask(plan, ranges, sink, bar, client, threads, options) -> dict:
    from distributed import as_completed

    finished: dict = {}
    window = 2 * max(1, len(client.scheduler_info()["workers"]))
    per_task = threads if threads > 0 else 1
    queue = iter(ranges)
    futures = {}

    def submit():
        for start, stop in itertools.islice(queue, 1):
            future = client.submit(solve_chunk, plan, start, stop, threads=per_task, pure=False, **options)
            futures[future] = (start, stop)
            return future
        return None

    running = as_completed([f for f in (submit() for _ in range(window)) if f is not None])
    done = 0
    try:
        for future in running:
            start, stop = futures.pop(future)
            try:
                chunk = future.result()
            except Exception as error:  # a worker lost or a task failing: its members say why
                chunk = _blank(plan, stop - start, options["trajectories"], options["extrema"])
                chunk["status"][:] = "failed"
                chunk["message"][:] = f"the Dask task failed: {_said(error)}"
                _put_values(chunk, plan, plan.values_range(start, stop))
            sink.put(start, chunk)
            finished[(start, stop)] = True
            done += stop - start
            if bar is not None:
                bar(done / plan.size)
            following = submit()
            if following is not None:
                running.add(following)
    except KeyboardInterrupt:
        finished["interrupted"] = True
        for future in list(futures):
            future.cancel()
    return finished
