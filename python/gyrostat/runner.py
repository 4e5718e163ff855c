"""Runs a scene of any kind: solves its runs with :func:`gyrostat.solve` (or the model ladder),
checks the assumptions, has the kind analyse the runs (the analysis a paper asks for lives in
its family module, from the recorded outputs; no physics is recomputed), writes the results
(CSV/NPZ with units), the report and the kind's plots; and runs a scene's sweep."""

from __future__ import annotations

import json
import math
import time
import warnings
from collections.abc import Iterable, Mapping
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
                                     outputs=_Rows(solution.outputs, keep))
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
            derived["ladder_accuracy"] = choice.accuracy
            report["ladder"]["measured"] = derived["ladder"]
    scene.kind.analyse(scene, solutions, report, derived)
    # the kind's analysis may add broken assumptions of its own: sorted after it
    expected = scene.doc.get("expected_broken", [])
    markers = {text: _marker(text, expected) for text in report["broken_assumptions"]}
    report["expected_broken"] = [{"assumption": text, "why": m["why"]} for text, m in markers.items() if m]
    report["unexpected_broken"] = [text for text, m in markers.items() if not m]
    report["expected_but_held"] = [m["assumption"] for m in expected
                                   if not any(text.startswith(m["assumption"]) for text in report["broken_assumptions"])]
    statuses = {s.status for s in solutions.values()}
    report["status"] = ("success" if statuses == {"success"} else
                        "interrupted" if "interrupted" in statuses else "failed")
    report["error_estimates"] = {name: s.error_estimate for name, s in solutions.items()}
    report["agreement"] = agreement(report)
    report["verdict"] = verdict(report)
    return solutions, report, derived


class _Rows(Mapping):
    """The outputs at the rows ``keep``, each selected when it is read (a check reads one or two
    of them)."""

    def __init__(self, outputs: dict, keep: np.ndarray):
        self._outputs, self._keep = outputs, keep

    def __getitem__(self, name: str) -> np.ndarray:
        return self._outputs[name][self._keep]

    def __iter__(self):
        return iter(self._outputs)

    def __len__(self) -> int:
        return len(self._outputs)


def _marker(text: str, expected: list[dict]) -> dict | None:
    """The scene's [[expected_broken]] entry that names this broken assumption, if any."""
    return next((m for m in expected if text.startswith(m["assumption"])), None)


def agreement(report: dict) -> str:
    """What the scene measured against a reference, in one line: the kind's analysis' maximum
    differences (``averaged_vs_full*``, ``max_error_vs_closed_form``) as the report holds them, and
    beside them each run's own estimate (``error_estimates``)."""
    parts = []
    for key, value in report.items():
        if key.startswith("averaged_vs_full") and isinstance(value, dict):
            numbers = ", ".join(f"{name} {v:.2g}" for name, v in value.items() if isinstance(v, float))
            if numbers:
                parts.append(f"{key.replace('_', ' ')}: {numbers}")
        elif key == "max_error_vs_closed_form":
            parts.append(f"max |omega - closed form| {value:.2g}")
    if parts and report.get("error_estimates"):  # the runs' own estimates beside what was measured
        parts.append("estimated: " + ", ".join(f"{name} {value:.2g}" for name, value in report["error_estimates"].items()
                                             if value == value))
    return "; ".join(parts)


def verdict(report: dict) -> str:
    """One word or phrase for the summary: the status, then whether every assumption held, held
    but for the ones the scene expects to break (its [[expected_broken]]), or broke unexpectedly,
    and whether a run doubts its own accuracy."""
    if report["status"] != "success":
        return report["status"]
    unmet = [name for name, run in report.get("runs", {}).items()
             if (run.get("error_estimate") or {}).get("met") is False]
    if unmet:
        return f"accuracy not met ({', '.join(unmet)}: see accuracy_warnings)"
    notes = []
    if report["unexpected_broken"]:
        notes.append(f"WARNING {len(report['unexpected_broken'])} assumption(s) broken")
    if report["expected_but_held"]:
        notes.append(f"{len(report['expected_but_held'])} expected break(s) not seen")
    if report["accuracy_warnings"]:
        notes.append(f"WARNING accuracy ({len(report['accuracy_warnings'])})")
    if report["expected_broken"]:
        notes.append(f"{len(report['expected_broken'])} broken as expected")
    return "ok" + (", " + ", ".join(notes) if notes else "")


# ------------------------------------------------------------------------------------ the ladder
def _solve_ladder(scene: Scene, solutions: dict, progress: bool) -> "_ladder.Choice":
    """model = "auto": the ladder's choice (probes included), then the run on the chosen rung,
    switching up and down where its assumptions stop and start holding. The scene's runs become
    the one run solved (named as the kind's plots expect it)."""
    template = scene.runs[0]
    integration = scene.doc["integration"]
    choice = _ladder.choose(scene.ladder, template.t_span, template.options, integration.get("accuracy") or _ladder.ACCURACY,
                            key=_ladder.scene_key(scene.doc))
    rung = choice.chosen
    name = rung.run
    # the scene's events, located wherever the run's model has their quantity (the run's notes name
    # the others: ladder.run)
    options = {**template.options, "events": list(template.options.get("events", ()))}
    bar = _bars.resolve(None if progress else False, description=f"{scene.name}: {rung.name}")
    try:
        solutions[name] = _ladder.run_estimate(choice, _ladder.run(choice, template.t_span, options,
                                                                    integration["phase"],
                                                                    progress=bar if bar is not None else False))
    finally:
        _bars.close(bar)
    scene.runs = [Run(name, rung.model, rung.y0, template.t_span, options)]
    scene.model_choice, scene.model_reason = rung.name, "the model ladder: " + choice.summary
    measured = solutions[name].error_estimate
    if math.isfinite(measured):
        scene.model_reason += f"; the run's measured error {measured:.3g}"
    return choice


def _ladder_report(choice: "_ladder.Choice", solutions: dict) -> dict:
    entry = choice.report()
    solution = next(iter(solutions.values()))
    entry["switches"] = [{"t": t, "from": a, "to": b, "reason": why} for t, a, b, why in solution.switches]
    return entry


# ------------------------------------------------------------------------------------ a scene on disk
def run_scene(path: str | Path | Scene, out_dir: str | Path, progress: bool = True, *,
              allow_import: Iterable[str] | str | None = None) -> dict:
    """Loads (unless given a loaded :class:`Scene`; ``allow_import`` as in
    :meth:`Scene.from_file`), solves, saves and plots one scene of any kind; returns its report
    (also written as report.json; ``plots_skipped`` names the plots asked for that could not be
    drawn, with the reason). Scene errors raise :class:`gyrostat.schema.SceneError` (one line)."""
    started = time.perf_counter()
    scene = path if isinstance(path, Scene) else Scene.from_file(path, allow_import=allow_import)
    solutions, report, derived = solve_scene(scene, progress=progress)
    for broken in report["broken_assumptions"]:
        marker = _marker(broken, scene.doc.get("expected_broken", []))
        warnings.warn(f"{scene.name}: {broken}" + (f" (expected: {marker['why']})" if marker else ""),
                      validity.ValidityWarning, stacklevel=2)
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
    report["folder"] = str(folder)
    report["seconds_total"] = time.perf_counter() - started  # solving, checks, files and plots
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
                  summary: str | None = None, allow_import: Iterable[str] | str | None = None) -> SweepJob:
    """A scene's sweep (its ``[sweep]`` table, or ``vary``: a list of
    :class:`gyrostat.sweeps.Parameter` that replaces the table's parameters) with everything it
    can get wrong checked now: the paths, the grid or dispersion, the run, the summary and the
    plot's reference lines. Errors of the table are SceneErrors naming ``[sweep]``. ``allow_import``
    as in :meth:`Scene.from_file`."""
    from gyrostat import sweeps

    scene = path if isinstance(path, Scene) else Scene.from_file(path, allow_import=allow_import)
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
              summary: str | None = None, client=None, threads: int = 0, workers: int | None = None,
              chunk_size: int | None = None, progress: bool | None = None,
              allow_import: Iterable[str] | str | None = None) -> dict:
    """Runs a scene's sweep (:func:`prepare_sweep`, or a job it made): every member's results
    streamed to ``OUT/SCENE/sweep.nc``, the summary plotted against the parameters in
    ``sweep.png``, a report in ``sweep.json``; returns the report."""
    from gyrostat import sweeps

    job = path if isinstance(path, SweepJob) else prepare_sweep(path, vary, samples=samples, seed=seed, run=run,
                                                                 trajectories=trajectories, summary=summary,
                                                                 allow_import=allow_import)
    scene = job.scene
    folder = Path(out_dir) / scene.name
    folder.mkdir(parents=True, exist_ok=True)
    target = folder / "sweep.nc"
    ds = sweeps.sweep(job.plan, None, trajectories=job.trajectories, client=client, threads=threads,
                      workers=workers, chunk_size=chunk_size, path=target, progress=progress)
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
    expected = scene.doc.get("expected_broken", [])  # the scene's own markers, as for its run
    report["unexpected_broken"] = [text for text in report["broken_assumptions"] if not _marker(text, expected)]
    report["expected_parts"] = sorted({m["assumption"] for text in report["broken_assumptions"]
                                       if (m := _marker(text, expected))})
    files = [target, plots.sweep(ds, values, f"{scene.title}: sweep", folder / "sweep.png",
                                 contour=job.contour, lines=job.lines)]
    report["files"] = [str(f) for f in files] + [str(folder / "sweep.json")]
    (folder / "sweep.json").write_text(json.dumps(output.clean(report), indent=2) + "\n")
    return report
