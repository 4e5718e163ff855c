"""Plots of a scene's results (matplotlib, written to PNG files)."""

from __future__ import annotations

import textwrap
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from gyrostat.solution import Solution  # noqa: E402


def _finish(fig, path: Path) -> Path:
    for ax in fig.axes:  # long scene titles wrap instead of running off the figure
        title = ax.get_title()
        if len(title) > 60:
            ax.set_title(textwrap.fill(title, 60), fontsize=10)
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)
    return path


def omega(solution: Solution, title: str, path: Path, reference: Solution | None = None) -> Path:
    fig, ax = plt.subplots(figsize=(8, 4.5))
    for i, name in enumerate(("p", "q", "r")):
        ax.plot(solution.t, solution.omega[:, i], label=f"{name} ({solution.method})")
        if reference is not None:
            ax.plot(reference.t, reference.omega[:, i], "k:", lw=1, label=f"{name} (closed form)" if i == 0 else None)
    ax.set_xlabel("t [s]")
    ax.set_ylabel("angular velocity in body axes [rad/s]")
    ax.set_title(title)
    ax.legend(loc="upper right", fontsize=8)
    ax.grid(alpha=0.3)
    return _finish(fig, path)


def invariants(solution: Solution, title: str, path: Path) -> Path:
    fig, axes = plt.subplots(2, 1, figsize=(8, 5.5), sharex=True)
    labels = {"angular_momentum_norm": ("|G|", "kg m²/s"), "kinetic_energy": ("T", "J")}
    for ax, (name, values) in zip(axes, solution.invariants.items()):
        symbol, unit = labels.get(name, (name, "1"))
        ax.plot(solution.t, values, label=symbol)
        ax.set_ylabel(f"{symbol} [{unit}]")
        ax.grid(alpha=0.3)
        ax.legend(loc="upper right", fontsize=8)
    axes[-1].set_xlabel("t [s]")
    axes[0].set_title(f"{title}: invariants")
    return _finish(fig, path)


def euler_angles(solution: Solution, title: str, path: Path) -> Path:
    angles = np.unwrap(solution.euler_angles(), axis=0)
    fig, ax = plt.subplots(figsize=(8, 4.5))
    for i, name in enumerate(("ψ (precession)", "θ (nutation)", "φ (proper rotation)")):
        ax.plot(solution.t, angles[:, i], label=name)
    ax.set_xlabel("t [s]")
    ax.set_ylabel("Euler angles z-x-z [rad]")
    ax.set_title(f"{title}: attitude")
    ax.legend(loc="upper left", fontsize=8)
    ax.grid(alpha=0.3)
    return _finish(fig, path)


def error(solution: Solution, reference: Solution, title: str, path: Path) -> Path:
    fig, ax = plt.subplots(figsize=(8, 4))
    err = np.linalg.norm(solution.omega - reference.omega, axis=1)
    ax.semilogy(solution.t, np.maximum(err, 1e-18), label=f"|ω − ω_closed form| ({solution.method})")
    ax.set_xlabel("t [s]")
    ax.set_ylabel("error [rad/s]")
    ax.set_title(f"{title}: error against the closed form")
    ax.legend(fontsize=8)
    ax.grid(alpha=0.3, which="both")
    return _finish(fig, path)


def slow_curves(solutions: dict[str, Solution], title: str, path: Path, kind: str) -> Path:
    """x = a², y = r² (kind "xy") or a and signed r (kind "slow") over time; the averaged model
    solid, the full model's a = √(p²+q²), r thin."""
    from gyrostat.averaged import slow_variables

    fig, ax = plt.subplots(figsize=(8, 4.8))
    styles = {"averaged": dict(lw=2.0), "full": dict(lw=0.8, ls="--")}
    for name in ("full", "averaged"):
        if name not in solutions:
            continue
        a, r = slow_variables(solutions[name])
        first, second = (a**2, r**2) if kind == "xy" else (a, r)
        labels = ("x = a²", "y = r²") if kind == "xy" else ("a", "r")
        ax.plot(solutions[name].t, first, color="tab:blue", label=f"{labels[0]} ({name})", **styles[name])
        ax.plot(solutions[name].t, second, color="tab:red", label=f"{labels[1]} ({name})", **styles[name])
    ax.set_xlabel("t [s]")
    ax.set_ylabel("x = a², y = r² [rad²/s²]" if kind == "xy" else "a, r [rad/s]")
    ax.set_title(title)
    ax.legend(fontsize=8)
    ax.grid(alpha=0.3)
    return _finish(fig, path)


def phase(solutions: dict[str, Solution], title: str, path: Path) -> Path:
    """The phase curve a² against r² (paper 002's y against x)."""
    from gyrostat.averaged import slow_variables

    fig, ax = plt.subplots(figsize=(6.5, 5.5))
    for name, style in (("full", dict(lw=0.8, ls="--")), ("averaged", dict(lw=2.0))):
        if name in solutions:
            a, r = slow_variables(solutions[name])
            ax.plot(r**2, a**2, label=name, **style)
            ax.plot(r[:1] ** 2, a[:1] ** 2, "ko", ms=4)
    ax.set_xlabel("r² (paper 002: x) [rad²/s²]")
    ax.set_ylabel("a² = p² + q² (paper 002: y) [rad²/s²]")
    ax.set_title(f"{title}: phase curve")
    ax.legend(fontsize=8)
    ax.grid(alpha=0.3)
    return _finish(fig, path)


def draw_scene(scene, solutions: dict[str, Solution], folder: Path, reference: Solution | None = None) -> list[Path]:
    files = []
    main = solutions.get("full", solutions.get("closed_form"))
    for plot in scene.plots:
        path = folder / f"{plot}.png"
        if plot in ("xy", "slow"):
            files.append(slow_curves(solutions, scene.title, path, plot))
        elif plot == "phase":
            files.append(phase(solutions, scene.title, path))
        elif main is None:
            continue
        elif plot == "omega":
            files.append(omega(main, scene.title, path, reference))
        elif plot == "invariants":
            files.append(invariants(main, scene.title, path))
        elif plot == "euler_angles" and main.y.shape[1] >= 7:
            files.append(euler_angles(main, scene.title, path))
        elif plot == "error" and reference is not None:
            files.append(error(main, reference, scene.title, path))
    return files
