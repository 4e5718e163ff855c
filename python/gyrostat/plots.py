"""Plots of a scene of any kind (matplotlib, written to PNG files): :func:`draw_scene` draws what
the scene asks for through its kind (each family draws its own plots in its family module),
:func:`skipped` says why a plot asked for was not drawn, :func:`ladder` charts the model ladder
and :func:`sweep` a sweep's summary. The plots of any run (:func:`omega`, :func:`invariants`,
:func:`euler_angles`, :func:`error`, :func:`curves`) live in :mod:`gyrostat.figures` (below the
families, which draw with them) and are importable from here as well."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from gyrostat import figures
from gyrostat.figures import (LEGEND_SIZE, curves, error, euler_angles, invariants, mark_singular, omega,  # noqa: F401
                              plt, relative_change, wrap_angle)
from gyrostat.solution import Solution


def draw_scene(scene, solutions: dict[str, Solution], derived: dict, folder: Path) -> list[Path]:
    """The plots the scene asks for (``scene.plots``), drawn by its kind; ``derived`` holds what the
    kind's analysis computed beside the runs (gyrostat.runner)."""
    files = scene.kind.draw(scene, solutions, derived, folder)
    if "ladder" in derived:
        files.append(ladder(derived["ladder"], f"{scene.title}: the model ladder", folder / "ladder.png",
                            derived["ladder_accuracy"]))
    return files


def skipped(scene, files: list[Path]) -> list[dict]:
    """The plots the scene asks for that :func:`draw_scene` did not draw, each with the reason
    (for the console and report.json: a plot asked for is never left out silently)."""
    drawn = {Path(f).stem for f in files}
    return [{"plot": plot, "reason": _why_not_drawn(scene, plot)} for plot in scene.plots if plot not in drawn]


def _why_not_drawn(scene, plot: str) -> str:
    doc = scene.doc
    if plot == "ladder" and scene.ladder is None:
        return (f"it compares the rungs of the model ladder, which runs only with [integration] model = \"auto\" "
                f"(this scene: model = {doc['integration'].get('model')!r})")
    reason = scene.kind.why_not_drawn(doc, plot)
    if reason:
        return reason
    if plot == "euler_angles":
        return "it needs the attitude: give [initial] attitude (the run then integrates the quaternion)"
    return f"the scene's runs ({', '.join(r.name for r in scene.runs)}) have nothing to draw it from"


def ladder(rows: list[dict], title: str, path: Path, accuracy: float) -> Path:
    """Each rung's cost (seconds for the whole span) against its error measured against the top
    rung, the chosen one ringed, its estimate drawn as an arrow from the measured error, and the
    requested accuracy as a line: which model was cheap enough and accurate enough, at a glance."""
    fig, ax = plt.subplots(figsize=(6.4, 4.8))
    skipped = [r for r in rows if "skipped" in r]
    rows = [r for r in rows if "skipped" not in r]
    floor = min([r["error"] for r in rows if r["error"] > 0] + [accuracy]) * 1e-2
    for row in rows:
        reference = row.get("reference", row["error"] == 0.0 and not row.get("estimate"))
        label = row["rung"] + (f", {row['switches']} switch(es)" if row.get("switches") else "")
        if reference:  # no error of its own: marked on the cost axis, not drawn as a measured error
            ax.plot(row["seconds"], 0.0, "s", ms=9, color="tab:gray", clip_on=False, zorder=5,
                    transform=ax.get_xaxis_transform())
            ax.annotate(f"{label}: the reference (no error of its own)", (row["seconds"], 0.0),
                        xycoords=ax.get_xaxis_transform(), textcoords="offset points", xytext=(8, 6), fontsize=9)
            continue
        error = max(row["error"], floor)
        ax.loglog(row["seconds"], error, "o", ms=9, color="tab:blue")
        ax.annotate(label, (row["seconds"], error), textcoords="offset points", xytext=(8, 6), fontsize=9)
        if row.get("estimate"):
            ax.plot([row["seconds"]] * 2, [error, max(row["estimate"], floor)], color="tab:orange", lw=1.5)
            ax.plot(row["seconds"], max(row["estimate"], floor), "_", ms=14, mew=2, color="tab:orange")
        if row["chosen"]:
            ax.loglog(row["seconds"], error, "o", ms=18, mfc="none", mec="tab:red", mew=2)
    seconds = [r["seconds"] for r in rows]
    ax.plot([min(seconds) / 3.0, max(seconds) * 3.0], [accuracy] * 2, color="tab:red", ls="--", lw=1,
            label=f"requested accuracy {accuracy:g}")
    ax.plot([], [], color="tab:orange", marker="_", lw=1.5, label="error estimate (probe)")
    ax.plot([], [], "o", ms=12, mfc="none", mec="tab:red", mew=2, label="chosen")
    ax.set_xscale("log"), ax.set_yscale("log")
    ax.set_xlabel("cost: time for the whole span [s]")
    if skipped:  # below the axis label, which keeps its unit last
        ax.annotate("\n".join(f"not run: {r['rung']} ({r['skipped']})" for r in skipped), (0.0, 0.0),
                    xycoords="axes fraction", xytext=(0, -42), textcoords="offset points", va="top", fontsize=8)
    ax.set_ylabel("relative error against the most complete model [1]")
    ax.set_title(title)
    ax.legend(fontsize=9, loc="upper left", bbox_to_anchor=(1.02, 1.0), borderaxespad=0)
    ax.grid(True, which="both", alpha=0.3)
    return figures.finish(fig, path)


# ------------------------------------------------------------------------------------ sweeps
def _axis_label(ds, name: str) -> str:
    attrs = ds[name].attrs
    return f"{attrs.get('long_name', name)} [{attrs.get('units') or '1'}]"


def sweep(ds, values, title: str, path: Path, contour: float | None = None,
          lines: list[dict] | None = None) -> Path:
    """A sweep's summary (``values``, as :func:`gyrostat.sweeps.summary` gives it: named by its
    expression, with its units) against its parameters: a line for one grid parameter, a heat map
    for two (with the level line ``summary = contour`` and reference lines), a scatter for a
    dispersion; members that failed are marked x."""
    expression = values.name
    label = f"{expression} [{values.attrs['units']}]"
    failed = ds["status"] != "success"
    plan = __import__("json").loads(ds.attrs["plan"])
    names = [p["name"] for p in plan["parameters"]]
    along = plan["mode"] == "grid" and len(names) == 2 and bool(lines)
    if along:  # the summary along each reference line, below the map: where the eye cannot tell
        fig, (ax, below) = plt.subplots(2, 1, figsize=(7.5, 7.5), gridspec_kw={"height_ratios": [3, 1.3]})
    else:
        fig, ax = plt.subplots(figsize=(7.5, 5.5))
    if plan["mode"] == "grid" and len(names) == 1:
        x = ds[names[0]].values
        ax.plot(x, values.values, "o-", ms=3, label=label)
        if bool(failed.any()):
            ax.plot(x[failed.values], np.zeros(int(failed.sum())), "rx", label="failed members")
        ax.set_xlabel(_axis_label(ds, names[0]))
        ax.set_ylabel(label)
        for line in lines or ():
            ax.plot(line["x"], line["y"], "k--", lw=1.2, label=line["label"])
        ax.legend(fontsize=LEGEND_SIZE)
    elif plan["mode"] == "grid":
        x, y = ds[names[0]].values, ds[names[1]].values
        z = values.transpose(names[0], names[1], ...).values.T  # rows: the second parameter
        finite = z[np.isfinite(z)]
        log = finite.size and np.all(finite > 0) and finite.max() / finite.min() > 100
        from matplotlib.colors import LogNorm  # (matplotlib is imported where gyrostat draws: figures.plt)
        from matplotlib.lines import Line2D

        norm = LogNorm(finite.min(), finite.max()) if log else None
        mesh = ax.pcolormesh(x, y, np.ma.masked_invalid(z), shading="nearest", cmap="viridis", norm=norm)
        fig.colorbar(mesh, ax=ax, label=label)
        handles = []
        # the level line wide and white under the reference lines, narrow and dashed: where they
        # coincide, both stay visible (white on either side of the red dashes and between them)
        if contour is not None and finite.size and finite.min() < contour < finite.max():
            ax.contour(x, y, z, levels=[contour], colors="w", linewidths=4.5, zorder=3)
            handles.append(Line2D([], [], color="w", lw=4.5, label=f"gyrostat: {expression} = {contour:g}"))
        for line in lines or ():
            handles += ax.plot(line["x"], line["y"], color="r", ls=(0, (4, 4)), lw=1.5, label=line["label"], zorder=4)
        bad = failed.transpose(names[0], names[1]).values.T
        if bad.any():
            gx, gy = np.meshgrid(x, y)
            handles += ax.plot(gx[bad], gy[bad], "kx", ms=6, label="failed members")
        ax.set_xlabel(_axis_label(ds, names[0]))
        ax.set_ylabel(_axis_label(ds, names[1]))
        if handles:
            ax.legend(handles=handles, fontsize=LEGEND_SIZE, loc="best", facecolor="0.6")
        for line in lines if along else ():
            inside = x[(x >= min(line["x"])) & (x <= max(line["x"]))]
            on_line = np.interp(inside, line["x"], line["y"])
            column = np.log(z) if log else z  # a map on a log scale is interpolated in log
            sampled = [np.interp(v, y, column[:, i]) for v, i in zip(on_line, np.searchsorted(x, inside))]
            sampled = np.exp(sampled) if log else np.asarray(sampled)
            below.plot(inside, sampled, "r.-", label=f"{expression} along: {line['label']}")
            if contour is not None:
                below.axhline(contour, color="k", lw=0.8, ls=":")
            below.set_xlabel(_axis_label(ds, names[0]))
            below.set_ylabel(label)
            below.legend(fontsize=LEGEND_SIZE)
            below.grid(alpha=0.3)
    else:
        ok = ~failed.values
        x = ds[names[0]].values
        if len(names) == 1:
            ax.plot(x[ok], values.values[ok], ".", ms=4)
            ax.set_ylabel(label)
        else:
            points = ax.scatter(x[ok], ds[names[1]].values[ok], c=values.values[ok], s=8, cmap="viridis")
            fig.colorbar(points, ax=ax, label=label)
            ax.set_ylabel(_axis_label(ds, names[1]))
        ax.set_xlabel(_axis_label(ds, names[0]))
        extra = f"; plotted: {names[0]}, {names[1]}" if len(names) > 2 else ""
        ax.set_title(f"{int(ok.sum())} of {ok.size} members succeeded (seed {ds.attrs.get('seed')}){extra}",
                     fontsize=LEGEND_SIZE)
    fig.suptitle(title, fontsize=11)
    ax.grid(alpha=0.3)
    return figures.finish(fig, path)
