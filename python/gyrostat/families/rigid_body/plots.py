"""The rigid body family's plots (drawn with :mod:`gyrostat.figures`): the slow variables of
the averaged and the full model, the phase curve, the nutation angle, and the plots of any run
(:func:`draw`, which the moving-mass family draws with too)."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from gyrostat import figures
from gyrostat.families.rigid_body.averaged_outputs import slow_variables
from gyrostat.figures import LEGEND_SIZE, error, euler_angles, invariants, omega, plt
from gyrostat.solution import Solution


FULL_STYLE = dict(lw=1.0, ls="--", color="k")  # the full model drawn dashed over the averaged one
AVERAGED_STYLE = dict(lw=3.0, alpha=0.6)


def slow_curves(solutions: dict[str, Solution], title: str, path: Path, kind: str) -> Path:
    """a² and r² (kind "xy") or a and signed r (kind "slow") over time: the averaged model thick
    and solid, the full model's a = √(p²+q²), r dashed over it; when both are there, a lower
    panel shows their difference (where the curves coincide)."""
    both = "full" in solutions and "averaged" in solutions
    fig, axes = plt.subplots(2 if both else 1, 1, figsize=(8, 6.5 if both else 4.8), sharex=True, squeeze=False,
                             gridspec_kw=dict(height_ratios=[2, 1] if both else [1]))
    ax = axes[0, 0]
    labels = ("a²", "r²") if kind == "xy" else ("a", "r")
    curves = {}
    for name in ("averaged", "full"):
        if name not in solutions:
            continue
        a, r = slow_variables(solutions[name])
        curves[name] = (a**2, r**2) if kind == "xy" else (a, r)
        first, second = curves[name]
        # the two curves on top of each other (x = y, as paper 001's claim has it) would read as
        # one: the second is then drawn dashed over the first, and the legend says so
        apart = float(np.max(np.abs(first - second)))
        alike = name == "averaged" and apart <= 0.02 * max(float(np.max(np.abs(first))), 1e-300)  # 2%: one line width
        for label, values, color in zip(labels, curves[name], ("tab:blue", "tab:red")):
            style = dict(AVERAGED_STYLE, color=color) if name == "averaged" else FULL_STYLE
            legend = f"{label} (averaged)" if name == "averaged" else ("full model" if label == labels[0] else None)
            if alike and label == labels[1]:
                style = dict(lw=1.6, ls=(0, (5, 4)), color=color)
                legend += f", dashed: within {apart:.2g} of {labels[0]}"
            ax.plot(solutions[name].t, values, label=legend, **style)
    unit = "[rad²/s²]" if kind == "xy" else "[rad/s]"
    ax.set_ylabel(f"{', '.join(labels)} {unit}")
    ax.set_title(title)
    ax.legend(fontsize=LEGEND_SIZE, loc="best")
    ax.grid(alpha=0.3)
    if both:
        diff = axes[1, 0]
        t_full, t_avg = solutions["full"].t, solutions["averaged"].t
        for label, full, averaged, color in zip(labels, curves["full"], curves["averaged"], ("tab:blue", "tab:red")):
            diff.plot(t_full, full - np.interp(t_full, t_avg, averaged), color=color, lw=1.0, label=f"{label}")
        diff.set_ylabel(f"full − averaged {unit}")
        diff.legend(fontsize=LEGEND_SIZE)
        diff.grid(alpha=0.3)
    axes[-1, 0].set_xlabel("t [s]")
    return figures.finish(fig, path)


def phase(solutions: dict[str, Solution], title: str, path: Path) -> Path:
    """The phase curve a² against r² (paper 002's y against its x): the full model dashed over
    the averaged one, both starting at the black dot."""
    fig, ax = plt.subplots(figsize=(6.5, 5.5))
    for name, style in (("averaged", dict(AVERAGED_STYLE, color="tab:blue")), ("full", FULL_STYLE)):
        if name in solutions:
            a, r = slow_variables(solutions[name])
            ax.plot(r**2, a**2, label=name, **style)
            ax.plot(r[:1] ** 2, a[:1] ** 2, "ko", ms=4)
    ax.set_xlabel("r² [rad²/s²]")
    ax.set_ylabel("a² = p² + q² [rad²/s²]")
    ax.set_title(f"{title}: phase curve")
    ax.legend(fontsize=LEGEND_SIZE)
    ax.grid(alpha=0.3)
    return figures.finish(fig, path)


def nutation(solutions: dict[str, Solution], title: str, path: Path) -> Path:
    """The nutation angle (body z to G, recorded by every rigid-body model) of each run, in
    degrees, with 90° marked: where a spin about the axis of least inertia has turned into a flat
    spin; a run the ladder switched shows where it ran on the full model."""
    fig, ax = plt.subplots(figsize=(8, 3.8))
    for name, style in (("full", FULL_STYLE), ("averaged", dict(AVERAGED_STYLE, color="tab:blue"))):
        sol = solutions.get(name)
        if sol is None or "nutation_angle" not in sol.output_names:
            continue
        ax.plot(sol.t, np.degrees(sol["nutation_angle"]), label=name, **style)
        on_top = np.asarray(sol.rung) > 0 if sol.rung is not None else np.zeros(len(sol), bool)
        if on_top.any():
            ax.plot(sol.t[on_top], np.degrees(sol["nutation_angle"][on_top]), ".", ms=2, color="tab:red",
                    label="switched to the full model")
    ax.axhline(90.0, color="0.5", ls=":", lw=1)
    ax.set_xlabel("t [s]")
    ax.set_ylabel("nutation angle [deg]")
    ax.set_title(f"{title}: nutation angle")
    ax.legend(fontsize=LEGEND_SIZE)
    ax.grid(alpha=0.3)
    return figures.finish(fig, path)


def draw(scene, solutions: dict[str, Solution], derived: dict, folder: Path, own: dict | None = None) -> list[Path]:
    """The plots of a rigid-body scene; ``own``: plot name → f(main solution, title, path) of a
    family that draws these and some of its own (the moving mass)."""
    files = []
    main = solutions.get("full", solutions.get("closed_form"))
    reference = derived.get("reference")
    for plot in scene.plots:
        path = folder / f"{plot}.png"
        if plot in ("xy", "slow"):
            files.append(slow_curves(solutions, scene.title, path, plot))
        elif plot == "phase":
            files.append(phase(solutions, scene.title, path))
        elif plot == "nutation":
            files.append(nutation(solutions, scene.title, path))
        elif plot == "invariants" and main is None and "averaged" in solutions:
            files.append(invariants(solutions["averaged"], scene.title, path))
        elif main is None:
            continue
        elif plot == "omega":
            files.append(omega(main, scene.title, path, reference))
        elif plot == "invariants":
            files.append(invariants(main, scene.title, path))
        elif plot == "euler_angles" and "q_w" in main.state_names:
            files.append(euler_angles(main, scene.title, path))
        elif plot == "error" and reference is not None:
            files.append(error(main, reference, scene.title, path))
        elif own and plot in own:
            files.append(own[plot](main, scene.title, path))
    return files

