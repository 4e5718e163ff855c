"""Runs a scene of any kind: solves its runs with :func:`gyrostat.solve` (or the model ladder),
checks the assumptions, has the kind analyse the runs (the analysis a paper asks for lives in
its family module, from the recorded outputs; no physics is recomputed), writes the results
(CSV/NPZ with units), the report and the kind's plots; and runs a scene's sweep."""

from __future__ import annotations

import json
import time
import warnings
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from gyrostat import _core, output, plots, validity
from gyrostat import ladder as _ladder
from gyrostat import progress as _bars
from gyrostat.scene import Run, Scene, SceneError
from gyrostat.solution import AccuracyWarning, Solution
from gyrostat.solve import solve


def solve_scene(scene: Scene, progress: bool = True) -> tuple[dict[str, Solution], dict, dict]:
    """Solves every run of a scene; returns the solutions by run name, the report, and what the
    kind's analysis derived for its plots (references, comparisons)."""
    started = time.perf_counter()
    solutions: dict[str, Solution] = {}
    with warnings.catch_warnings():  # the runs' own doubts go to the report (below), not to stderr
        warnings.simplefilter("ignore", AccuracyWarning)
        choice = _solve_ladder(scene, solutions, progress) if scene.ladder is not None else None
        for run in scene.runs if choice is None else ():
            report = _bars.resolve(None if progress else False, description=f"{scene.name}: {run.name}")
            try:  # a bar in a terminal for a run longer than the engine's first poll (0.1 s)
                solutions[run.name] = solve(run.model, run.y0, run.t_span, **run.options, check_validity=False,
                                            progress=report if report is not None else False)
            finally:
                _bars.close(report)
    elapsed = time.perf_counter() - started
    report = {
        "scene": scene.name,
        "kind": scene.kind.name,
        "title": scene.title,
        "version": _core.__version__,
        "model": scene.model_choice,
        "model_reason": scene.model_reason,
        "seconds": elapsed,
        "runs": {name: output.run_report(s) for name, s in solutions.items()},
        "units": {},
        "inputs": scene.doc,
    }
    checks = []
    for run in scene.runs:
        solution = solutions[run.name]
        if solution.pieces:  # a run that switched models: checked where the lower rung ran
            keep = solution.rung == 0
            checks += validity.check(run.model, solution.y[keep], solution.t[keep], warn=False,
                                     outputs={k: v[keep] for k, v in solution.outputs.items()})
        elif len(solution):
            checks += scene.kind.assumptions(run, solution)
    unique = {}
    for assumption in checks:  # torques checked under several models appear once
        unique.setdefault(str(assumption), assumption)
    report["assumptions"] = [output.assumption_entry(a) for a in unique.values()]
    report["broken_assumptions"] = [str(a) for a in unique.values() if not a.holds]
    report["accuracy_warnings"] = [f"{name}: {doubt}" for name, solution in solutions.items()
                                   for doubt in solution.accuracy_warnings]
    derived: dict = {}
    if choice is not None:
        report["ladder"] = _ladder_report(choice, solutions)
        if "ladder" in scene.plots:
            derived["ladder"] = _ladder.measure(choice, scene.runs[0].t_span, scene.runs[0].options)
            report["ladder"]["measured"] = derived["ladder"]
    scene.kind.analyse(scene, solutions, report, derived)
    statuses = {s.status for s in solutions.values()}
    report["status"] = ("success" if statuses == {"success"} else
                        "interrupted" if "interrupted" in statuses else "failed")
    return solutions, report, derived


# ------------------------------------------------------------------------------------ the ladder
def _solve_ladder(scene: Scene, solutions: dict, progress: bool) -> "_ladder.Choice":
    """model = "auto": the ladder's choice (probes included), then the run on the chosen rung,
    switching up and down where its assumptions stop and start holding. The scene's runs become
    the one run solved (named as the kind's plots expect it)."""
    template = scene.runs[0]
    integration = scene.doc["integration"]
    choice = _ladder.choose(scene.ladder, template.t_span, template.options, integration["accuracy"])
    rung = choice.chosen
    name = rung.run
    events = [e for e in template.options.get("events", ()) if getattr(e, "quantity", None) in
              rung.model.state_names + rung.model.output_names]
    options = {**template.options, "events": events}
    bar = _bars.resolve(None if progress else False, description=f"{scene.name}: {rung.name}")
    try:
        solutions[name] = _ladder.run(choice, template.t_span, options, integration["phase"],
                                      progress=bar if bar is not None else False)
    finally:
        _bars.close(bar)
    scene.runs = [Run(name, rung.model, rung.y0, template.t_span, options)]
    scene.model_choice, scene.model_reason = rung.name, "the model ladder: " + choice.summary
    return choice


def _ladder_report(choice: "_ladder.Choice", solutions: dict) -> dict:
    entry = choice.report()
    solution = next(iter(solutions.values()))
    entry["switches"] = [{"t": t, "from": a, "to": b, "reason": why} for t, a, b, why in solution.switches]
    return entry


# ------------------------------------------------------------------------------------ a scene on disk
def run_scene(path: str | Path | Scene, out_dir: str | Path, progress: bool = True) -> dict:
    """Loads (unless given a loaded :class:`Scene`), solves, saves and plots one scene of any
    kind; returns its report (also written as report.json; ``plots_skipped`` names the plots
    asked for that could not be drawn, with the reason). Scene errors raise
    :class:`gyrostat.schema.SceneError` (one line)."""
    scene = path if isinstance(path, Scene) else Scene.from_toml(path)
    solutions, report, derived = solve_scene(scene, progress=progress)
    for broken in report["broken_assumptions"]:
        warnings.warn(f"{scene.name}: {broken}", validity.ValidityWarning, stacklevel=2)
    folder = Path(out_dir) / scene.name
    folder.mkdir(parents=True, exist_ok=True)
    files: list[Path] = []
    runs = [run.name for run in scene.runs]
    for name in runs:
        solution = solutions[name]
        stem = "result" if len(runs) == 1 or name == "full" else f"result_{name}"
        files += output.write_solution(solution, folder, stem, scene.kind.extra_columns(scene, solution))
        report["units"].update(solution.units)
    drawn = plots.draw_scene(scene, solutions, derived, folder)
    report["plots_skipped"] = plots.skipped(scene, drawn)
    files += drawn
    report["files"] = [str(f) for f in files] + [str(folder / "report.json")]
    output.write_report(report, folder)
    return report


# ------------------------------------------------------------------------------------ a sweep on disk
@dataclass
class SweepJob:
    """A sweep checked against its scene before any member runs (:func:`prepare_sweep`)."""

    scene: Scene
    plan: object  # gyrostat.sweeps.Plan
    trajectories: bool
    summary: str
    contour: float | None
    lines: list


def prepare_sweep(path: str | Path | Scene, vary=None, *, samples: int | None = None, seed: int | None = None,
                  run: str | None = None, trajectories: bool | None = None,
                  summary: str | None = None) -> SweepJob:
    """A scene's sweep (its ``[sweep]`` table, or ``vary``: a list of
    :class:`gyrostat.sweeps.Parameter` that replaces the table's parameters) with everything it
    can get wrong checked now: the paths, the grid or dispersion, the run, the summary and the
    plot's reference lines. Errors of the table are SceneErrors naming ``[sweep]``."""
    from gyrostat import sweeps

    scene = path if isinstance(path, Scene) else Scene.from_toml(path)
    spec = scene.doc.get("sweep", {})
    from_table = vary is None
    try:
        if from_table:
            if not spec:
                raise SceneError(f"{scene.name} has no [sweep] table: give the parameters to vary (--vary)")
            vary = [sweeps.parameter_from_table(p, f"[sweep.vary[{i}]]") for i, p in enumerate(spec["vary"])]
        plan = sweeps.Plan(scene, vary, samples=samples if samples is not None else spec.get("samples"),
                           seed=seed if seed is not None else spec.get("seed"), run=run or spec.get("run"))
        trajectories = trajectories if trajectories is not None else spec.get("trajectories", False)
        expression = sweeps.check_plot(plan, summary or spec.get("summary") or None, trajectories=trajectories,
                                       contour=spec.get("contour"), lines=spec.get("lines"))
    except ValueError as error:  # SceneError included
        if not from_table or str(error).startswith("["):
            raise
        raise SceneError(f"[sweep] {error}") from None
    return SweepJob(scene, plan, trajectories, expression, spec.get("contour"), spec.get("lines") or [])


def run_sweep(path: str | Path | SweepJob, out_dir: str | Path, vary=None, *, samples: int | None = None,
              seed: int | None = None, run: str | None = None, trajectories: bool | None = None,
              summary: str | None = None, client=None, threads: int = 0, chunk_size: int | None = None,
              progress: bool | None = None) -> dict:
    """Runs a scene's sweep (:func:`prepare_sweep`, or a job it made): every member's results
    streamed to ``OUT/SCENE/sweep.nc``, the summary plotted against the parameters in
    ``sweep.png``, a report in ``sweep.json``; returns the report."""
    from gyrostat import sweeps

    job = path if isinstance(path, SweepJob) else prepare_sweep(path, vary, samples=samples, seed=seed, run=run,
                                                                 trajectories=trajectories, summary=summary)
    scene = job.scene
    folder = Path(out_dir) / scene.name
    folder.mkdir(parents=True, exist_ok=True)
    target = folder / "sweep.nc"
    ds = sweeps.sweep(job.plan, None, trajectories=job.trajectories, client=client, threads=threads,
                      chunk_size=chunk_size, path=target, progress=progress)
    ds.close()
    ds = sweeps.open_sweep(target)
    expression = job.summary
    values = sweeps.summary(ds, expression)
    statuses = {str(k): int(v) for k, v in zip(*np.unique(ds["status"].values.astype(str), return_counts=True))}
    report = {"scene": scene.name, "title": scene.title, "members": int(ds.attrs["members"]),
              "mode": ds.attrs["mode"], "seed": ds.attrs.get("seed"), "run": ds.attrs["run"],
              "model": ds.attrs["model"], "seconds": float(ds.attrs["seconds"]),
              "members_per_second": float(ds.attrs["members"]) / max(float(ds.attrs["seconds"]), 1e-12),
              "statuses": statuses, "interrupted": bool(ds.attrs["interrupted"]), "summary": expression,
              "summary_range": [float(np.nanmin(values.values)), float(np.nanmax(values.values))]
              if np.isfinite(values.values).any() else None,
              "parameters": json.loads(ds.attrs["plan"])["parameters"],
              "members_with_broken_assumptions": int((ds["broken_assumptions"] > 0).sum()),
              "broken_assumptions": sorted({str(a) for a in np.unique(ds["first_broken_assumption"].values) if a}),
              "members_with_accuracy_warnings": int((ds["accuracy_warning"] != "").sum()),
              "accuracy_warnings": sorted({str(a) for a in np.unique(ds["accuracy_warning"].values) if a})[:5]}
    files = [target, plots.sweep(ds, expression, f"{scene.title}: sweep", folder / "sweep.png",
                                 contour=job.contour, lines=job.lines)]
    report["files"] = [str(f) for f in files] + [str(folder / "sweep.json")]
    (folder / "sweep.json").write_text(json.dumps(output.clean(report), indent=2) + "\n")
    return report
