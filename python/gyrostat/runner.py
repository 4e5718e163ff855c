"""Runs a scene: solves it with the model it needs, saves the arrays, draws the plots."""

from __future__ import annotations

import csv
import json
import sys
import time
from pathlib import Path

import numpy as np

from gyrostat.scene import Scene
from gyrostat.solution import Solution
from gyrostat.solve import solve, torque_free

UNITS = {
    "t": "s",
    "p": "rad/s", "q": "rad/s", "r": "rad/s",
    "q_w": "1", "q_x": "1", "q_y": "1", "q_z": "1",
    "angular_momentum_norm": "kg m^2/s",
    "a": "rad/s", "x": "rad^2/s^2", "y": "rad^2/s^2", "energy": "J",
    "tau": "s", "g": "1", "h": "kg m^2/s^2",
    "kinetic_energy": "J",
    "psi": "rad", "theta": "rad", "phi": "rad",
}
PROGRESS_CHUNKS = 10


def _progress(message: str) -> None:
    print(message, file=sys.stderr, flush=True)


def solve_scene(scene: Scene, progress: bool = True) -> tuple[dict[str, Solution], dict]:
    """Solves a scene with the model(s) it asks for (or the cheapest adequate one); returns the
    solutions by model name ("closed_form", "full", "averaged") and a report."""
    from gyrostat import validity
    from gyrostat.averaged import slow_variables

    choice, reason = scene.choose_model()
    t_eval = np.linspace(scene.t_span[0], scene.t_span[1], scene.n_out)
    started = time.perf_counter()
    solutions: dict[str, Solution] = {}
    checks = []
    if choice == "closed_form":
        solutions["closed_form"] = torque_free(scene.body, scene.omega0, t_eval)
    if choice in ("full", "compare"):
        model = scene.model()
        y0 = np.concatenate([scene.omega0, scene.attitude0 if scene.attitude0 is not None else [1.0, 0, 0, 0]]) \
            if model.attitude else scene.omega0
        solutions["full"] = _solve_in_chunks(scene, model, y0, t_eval, progress)
        checks += validity.check(model, solutions["full"].y, solutions["full"].t, warn=False)
    if choice in ("averaged", "compare"):
        averaged = scene.averaged_model()
        solutions["averaged"] = _solve_in_chunks(scene, averaged, scene.slow0, t_eval, progress)
        checks += validity.check(averaged, solutions["averaged"].y, solutions["averaged"].t, warn=False)
    elapsed = time.perf_counter() - started
    unique = {}
    for assumption in checks:  # torques checked under both models appear once
        unique.setdefault(str(assumption), assumption)
    checks = list(unique.values())
    report = {
        "scene": scene.name,
        "title": scene.title,
        "model": choice,
        "model_reason": reason,
        "seconds": elapsed,
        "runs": {name: _run_report(solution) for name, solution in solutions.items()},
        "assumptions": [dict(part=a.part, statement=a.statement, value=a.value, limit=a.limit, holds=a.holds,
                             note=a.note) for a in checks],
        "broken_assumptions": [str(a) for a in checks if not a.holds],
    }
    if "full" in solutions and "averaged" in solutions:
        a_full, r_full = slow_variables(solutions["full"])
        a_avg, r_avg = slow_variables(solutions["averaged"])
        n = min(len(a_full), len(a_avg))
        report["averaged_vs_full"] = {"max_abs_error_a": float(np.max(np.abs(a_full[:n] - a_avg[:n]))),
                                      "max_abs_error_r": float(np.max(np.abs(r_full[:n] - r_avg[:n])))}
    report["status"] = "success" if all(s.success for s in solutions.values()) else "failed"
    return solutions, report


def _run_report(solution: Solution) -> dict:
    return {
        "method": solution.method,
        "status": solution.status,
        "message": solution.message,
        "stats": solution.stats,
        "invariant_relative_change": {
            name: float((values[-1] - values[0]) / values[0]) if values[0] != 0 else float(values[-1])
            for name, values in solution.invariants.items()
        },
        "notes": solution.notes,
    }


def _solve_in_chunks(scene, model, y0, t_eval, progress) -> Solution:
    """One call for short runs; for long ones, chunks of outputs with progress lines on stderr.
    Each chunk starts from the last state with the last step size, so the step sequence goes on."""
    chunks = np.array_split(np.arange(t_eval.size), PROGRESS_CHUNKS) if t_eval.size >= 200 else [np.arange(t_eval.size)]
    pieces: list[Solution] = []
    state, first_step = y0, 0.0
    for k, idx in enumerate(chunks):
        times = t_eval[idx[0] - (1 if k else 0): idx[-1] + 1]
        piece = solve(model, state, (times[0], times[-1]), method=scene.method, rtol=scene.rtol, atol=scene.atol,
                      t_eval=times, first_step=first_step, check_validity=False)  # checked below, once, on the whole run
        pieces.append(piece if k == 0 else _drop_first(piece))
        if not piece.success or piece.t.size == 0:
            break
        state, first_step = piece.y[-1], piece.stats["last_step"]
        if progress and len(chunks) > 1:
            _progress(f"[{scene.name}] {100 * (k + 1) // len(chunks):3d}%  t = {times[-1]:.6g}")
    return _concatenate(pieces)


def _drop_first(s: Solution) -> Solution:
    return Solution(s.t[1:], s.y[1:], {k: v[1:] for k, v in s.invariants.items()}, s.stats, s.status, s.message,
                    s.method, s.notes)


def _concatenate(pieces: list[Solution]) -> Solution:
    last = pieces[-1]
    stats = {key: sum(p.stats[key] for p in pieces) for key in last.stats if key != "last_step"}
    stats["last_step"] = last.stats["last_step"]
    return Solution(
        t=np.concatenate([p.t for p in pieces]),
        y=np.concatenate([p.y for p in pieces]),
        invariants={k: np.concatenate([p.invariants[k] for p in pieces]) for k in last.invariants},
        stats=stats, status=last.status, message=last.message, method=last.method, notes=last.notes,
    )


def write_columns(columns: dict[str, np.ndarray], folder: Path, stem: str, units: dict | None = None) -> list[Path]:
    """STEM.csv (a column per quantity, its unit in the header) and STEM.npz (the same arrays by
    name, plus their units as JSON). Units from `units`, else UNITS; "1" when unknown."""
    units = UNITS if units is None else {**UNITS, **units}
    folder.mkdir(parents=True, exist_ok=True)
    csv_path = folder / f"{stem}.csv"
    with csv_path.open("w", newline="") as handle:
        writer = csv.writer(handle)
        writer.writerow([f"{name} [{units.get(name, '1')}]" for name in columns])
        writer.writerows(np.column_stack(list(columns.values())).tolist())
    npz_path = folder / f"{stem}.npz"
    np.savez(npz_path, **columns, units=json.dumps({name: units.get(name, "1") for name in columns}))
    return [csv_path, npz_path]


def save(solution: Solution, names: tuple[str, ...], folder: Path, stem: str = "result") -> list[Path]:
    """Writes STEM.csv (a column per quantity, units in the header) and STEM.npz (the same arrays
    by name, plus their units as JSON)."""
    folder.mkdir(parents=True, exist_ok=True)
    columns = {"t": solution.t}
    for i, name in enumerate(names):
        columns[name] = solution.y[:, i]
    columns.update(solution.invariants)
    if solution.y.shape[1] >= 7:
        for name, values in zip(("psi", "theta", "phi"), solution.euler_angles().T):
            columns[name] = values
    if names[:2] == ("a", "r"):
        columns["x"] = solution.y[:, 0] ** 2
        columns["y"] = solution.y[:, 1] ** 2
    return write_columns(columns, folder, stem)


# Scene kinds other than the rigid body / gyrostat of Scene: the top-level key `kind` of a scene
# file names one; its module provides run_scene(path, out_dir, progress) -> report (same keys).
SCENE_KINDS = {"lagrange_top": "gyrostat.lagrange", "orthogonal_torque": "gyrostat.orthogonal"}


def scene_kind(path: str | Path) -> str:
    import tomllib

    with Path(path).open("rb") as handle:
        try:
            return str(tomllib.load(handle).get("kind", "rigid_body"))
        except tomllib.TOMLDecodeError as error:
            raise ValueError(f"{path}: not valid TOML: {error}") from None


def run_scene(path: str | Path, out_dir: str | Path, progress: bool = True) -> dict:
    """Loads, solves, saves and plots one scene; returns its report (also written as
    report.json). Broken assumptions are warned about (gyrostat.ValidityWarning)."""
    import importlib
    import warnings

    from gyrostat import plots
    from gyrostat.validity import ValidityWarning

    kind = scene_kind(path)
    if kind != "rigid_body":
        if kind not in SCENE_KINDS:
            raise ValueError(f"{path}: kind = {kind!r} is not a known scene kind "
                             f"(rigid_body, {', '.join(SCENE_KINDS)})")
        return importlib.import_module(SCENE_KINDS[kind]).run_scene(path, out_dir, progress=progress)
    scene = Scene.from_toml(path)
    solutions, report = solve_scene(scene, progress=progress)
    for broken in report["broken_assumptions"]:
        warnings.warn(f"{scene.name}: {broken}", ValidityWarning, stacklevel=2)
    folder = Path(out_dir) / scene.name
    files: list[Path] = []
    state_names = {"full": ("p", "q", "r", "q_w", "q_x", "q_y", "q_z"), "closed_form": ("p", "q", "r"),
                   "averaged": ("a", "r")}
    for name, solution in solutions.items():
        stem = "result" if len(solutions) == 1 else f"result_{name}"
        files += save(solution, state_names[name][: solution.y.shape[1]], folder, stem)
    reference = None
    main = solutions.get("full", solutions.get("closed_form"))
    if scene.reference == "closed_form" and main is not None:
        reference = torque_free(scene.body, scene.omega0, main.t)
        report["max_error_vs_closed_form"] = float(np.max(np.linalg.norm(main.omega - reference.omega, axis=1)))
    files += plots.draw_scene(scene, solutions, folder, reference=reference)
    json_path = folder / "report.json"
    report["files"] = [str(f) for f in files + [json_path]]
    json_path.write_text(json.dumps(report, indent=2, default=float) + "\n")
    return report
