"""What a run leaves on disk: CSV/NPZ writers (each column with the unit its C++ model declares),
the report (report.json), and the output folder's claim."""

from __future__ import annotations

import csv
import json
import math
import shutil
from pathlib import Path

import numpy as np



def write_columns(columns: dict[str, np.ndarray], units: dict[str, str], folder: Path, stem: str) -> list[Path]:
    """STEM.csv (a column per quantity, its unit in the header) and STEM.npz (the same arrays by
    name, plus their units as JSON under ``units``); ``units`` gives each column's unit."""
    folder.mkdir(parents=True, exist_ok=True)
    csv_path = folder / f"{stem}.csv"
    with csv_path.open("w", newline="") as handle:
        writer = csv.writer(handle)
        writer.writerow([f"{name} [{units[name]}]" for name in columns])
        writer.writerows(np.column_stack([np.asarray(v, float) for v in columns.values()]).tolist())
    npz_path = folder / f"{stem}.npz"
    np.savez(npz_path, **columns, units=json.dumps({name: units[name] for name in columns}))
    return [csv_path, npz_path]


def write_solution(solution, folder: Path, stem: str = "result", extra: dict | None = None) -> list[Path]:
    """t, the state and every output of a :class:`gyrostat.Solution` with their declared units,
    plus ``extra`` columns (name → (values, unit))."""
    columns, units = solution.columns(), solution.units
    for name, (values, unit) in (extra or {}).items():
        columns[name], units[name] = values, unit
    return write_columns(columns, units, folder, stem)


def _number(x):
    """JSON has no NaN or infinity: they are written as null (and said so in the report)."""
    x = float(x)
    return x if math.isfinite(x) else None


def change(values: np.ndarray, conserved: bool) -> dict:
    """Start, end and the change of a recorded quantity; the relative change only for a
    conserved quantity whose start is not negligible against its range (|start| > 1e-12 of
    max |values|): a relative change of a quantity that starts at zero means nothing."""
    values = np.asarray(values, float)
    entry = {"start": _number(values[0]), "end": _number(values[-1]),
             "max_abs_change": _number(np.max(np.abs(values - values[0])))}
    scale = float(np.max(np.abs(values))) if values.size else 0.0
    if conserved and abs(values[0]) > 1e-12 * scale and values[0] != 0:
        entry["relative_change"] = _number((values[-1] - values[0]) / values[0])
    return entry


def run_report(solution) -> dict:
    """The part of the report for one run: method, status, statistics, where it stopped (t_last,
    y_last, h_next: what a continuation starts from), and the change (relative where it means
    something) of each first integral: under ``conserved`` those this model keeps with its
    torques, under ``changed_by_torques`` those its torques change (a forced energy), as the C++
    model declares (``Solution.kept``); plus the notes."""
    report = {"method": solution.method, "status": solution.status, "success": bool(solution.success),
              "message": solution.message, "stats": solution.stats, "notes": list(solution.notes),
              "t_last": solution.t_last, "y_last": solution.y_last, "h_next": solution.h_next,  # to continue
              "options": solution.options.to_dict(), "conserved": {}, "changed_by_torques": {}}
    estimate = getattr(solution, "estimate", None)
    report["error_estimate"] = estimate.as_dict() if estimate is not None else None
    switches = getattr(solution, "method_switches", [])
    if switches or solution.method == "auto":  # method 'auto': which integrators, switched where
        report["methods_used"] = list(getattr(solution, "methods_used", ()))
        report["method_switches"] = [{"t": t, "to": to, "reason": why} for t, to, why in switches]
    if len(solution):
        outputs = solution.outputs
        kept = set(solution.kept)
        for name in solution.conserved:
            report["conserved" if name in kept else "changed_by_torques"][name] = change(outputs[name], True)
    if solution.event_names:
        report["events"] = {name: [float(t) for t in times] for name, times in zip(solution.event_names, solution.t_events)}
        if solution.terminal_event is not None:
            report["terminal_event"] = solution.event_names[solution.terminal_event]
    return report


def assumption_entry(a) -> dict:
    return {"part": a.part, "statement": a.statement, "value": _number(a.value), "limit": _number(a.limit),
            "holds": bool(a.holds), "note": a.note}


def clean(value):
    """Plain JSON values: numpy scalars and arrays to Python numbers and lists, NaN to null,
    booleans kept as booleans."""
    if isinstance(value, dict):
        return {str(k): clean(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [clean(v) for v in value]
    if isinstance(value, np.ndarray):
        return [clean(v) for v in value.tolist()]
    if isinstance(value, (bool, np.bool_)):
        return bool(value)
    if isinstance(value, (int, np.integer)):
        return int(value)
    if isinstance(value, (float, np.floating)):
        return _number(value)
    return value


def write_report(report: dict, folder: Path) -> Path:
    path = folder / "report.json"
    path.write_text(json.dumps(clean(report), indent=2) + "\n")
    return path


class FolderInUse(ValueError):
    """An output folder holds an earlier run (and --overwrite was not given)."""


SWEEP_FILES = ("sweep.nc", "sweep.json", "sweep.png")


def claim_folder(folder: Path, overwrite: bool, what: str = "run") -> None:
    """Makes ``folder`` ready for one scene's results: one run per folder, never the files of an
    earlier run left beside new ones. ``what = "run"``: the folder must be empty or absent, or,
    with ``overwrite``, hold only what gyrostat writes (it is then cleared). ``what = "sweep"``:
    the folder must hold no earlier sweep (with ``overwrite`` its sweep files are removed; a
    scene run's files beside it are kept)."""
    folder = Path(folder)
    if not folder.exists():
        return
    if not folder.is_dir():
        raise FolderInUse(f"{folder} is a file, not a folder")
    names = {p.name for p in folder.iterdir()}
    earlier = names & set(SWEEP_FILES) if what == "sweep" else names
    if not earlier:
        return
    if not overwrite:
        raise FolderInUse(f"{folder} holds an earlier {what} ({', '.join(sorted(earlier)[:4])}"
                          f"{', ...' if len(earlier) > 4 else ''}): give --overwrite to replace it, or another --out")
    if what == "sweep":
        for name in earlier:
            (folder / name).unlink()
        return
    if not names & {"report.json", "sweep.json"}:
        raise FolderInUse(f"{folder} holds files gyrostat did not write ({', '.join(sorted(names)[:4])}): "
                          "not clearing it; choose another --out")
    shutil.rmtree(folder)
