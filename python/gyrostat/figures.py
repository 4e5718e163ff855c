"""The drawing helpers every plot uses (matplotlib, written to PNG files): the plots of any run
(:func:`omega`, :func:`invariants`, :func:`euler_angles`, :func:`error` against a reference,
:func:`curves` of named quantities), angle wrapping and the shading of singular Euler angles,
and :func:`finish` / :func:`keep` (titles wrapped, plain time axes, the PNG written); ``plt`` is
matplotlib's pyplot on the Agg backend. Below the
families, so that each family's own plots are drawn with them; :mod:`gyrostat.plots` draws a
scene (and re-exports these)."""

from __future__ import annotations

import textwrap
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from gyrostat.solution import Solution  # noqa: E402

LEGEND_SIZE = 9  # points: legends readable at the figure's default size
PI_TICKS = {"−π": -np.pi, "−π/2": -np.pi / 2, "0": 0.0, "π/2": np.pi / 2, "π": np.pi}
SINGULAR_SIN_THETA = 0.05  # z-x-z Euler angles: ψ and φ are ill-defined where sin θ is below this


def wrap_angle(angle: np.ndarray) -> np.ndarray:
    """An angle wrapped to [−π, π), with NaN where it wraps so that no line crosses the plot."""
    wrapped = np.mod(np.asarray(angle, dtype=float) + np.pi, 2 * np.pi) - np.pi
    wrapped[1:][np.abs(np.diff(wrapped)) > np.pi] = np.nan
    return wrapped


def mark_singular(ax, t: np.ndarray, theta: np.ndarray) -> None:
    """Shades the times where the z-x-z angles are singular (θ near 0 or π: ψ and φ degenerate)."""
    near = np.abs(np.sin(theta)) < SINGULAR_SIN_THETA
    if near.any():
        ax.fill_between(t, 0, 1, where=near, transform=ax.get_xaxis_transform(), color="tab:gray", alpha=0.3,
                        label=f"singular: |sin θ| < {SINGULAR_SIN_THETA}")


def relative_change(values: np.ndarray) -> np.ndarray:
    """x(t)/x(0) − 1 (x(0) = 0: the absolute change x(t) − x(0))."""
    values = np.asarray(values, dtype=float)
    return (values - values[0]) / (abs(values[0]) if values[0] != 0 else 1.0)


CONSERVED = 1e-2  # an invariant that changes less than this is drawn as |change| on a log scale


def finish(fig, path: Path) -> Path:
    for ax in fig.axes:  # long scene titles wrap instead of running off the figure
        title = ax.get_title()
        if len(title) > 60:
            ax.set_title(textwrap.fill(title, 60), fontsize=10)
    for ax in fig.axes:  # time axes show plain numbers, never a hidden offset
        if ax.get_xscale() == "linear":
            ax.ticklabel_format(axis="x", useOffset=False)
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)
    return path


def keep(fig, path: Path, wanted: bool, files: list[Path]) -> None:
    """Writes a figure the scene asks for (and adds it to files); closes one it does not."""
    if wanted:
        files.append(finish(fig, path))
    else:
        plt.close(fig)


_SUPERSCRIPTS = str.maketrans("0123456789-", "⁰¹²³⁴⁵⁶⁷⁸⁹⁻")


def unit_label(solution, name: str, text: str | None = None) -> str:
    """``text [unit]`` for an axis: the unit of ``name`` as its C++ model declares it
    (:attr:`gyrostat.Solution.units`), with powers as superscripts (kg m^2/s → kg m²/s)."""
    unit = solution.units[name]
    pretty = "".join(part.translate(_SUPERSCRIPTS) if i % 2 else part
                     for i, part in enumerate(_split_powers(unit)))
    return f"{text or name} [{pretty}]"


def _split_powers(unit: str) -> list[str]:
    """"kg m^2/s" → ["kg m", "2", "/s"]: the odd items are exponents."""
    import re

    return re.split(r"\^\(?(-?\d+)\)?", unit)


def omega(solution: Solution, title: str, path: Path, reference: Solution | None = None) -> Path:
    fig, ax = plt.subplots(figsize=(8, 4.5))
    for i, name in enumerate(("p", "q", "r")):
        ax.plot(solution.t, solution.omega[:, i], label=f"{name} ({solution.method})")
        if reference is not None:
            ax.plot(reference.t, reference.omega[:, i], "k:", lw=1, label=f"{name} (closed form)" if i == 0 else None)
    ax.set_xlabel(unit_label(solution, "t"))
    ax.set_ylabel(unit_label(solution, "p", "angular velocity in body axes"))
    ax.set_title(title)
    ax.legend(loc="upper right", fontsize=LEGEND_SIZE)
    ax.grid(alpha=0.3)
    return finish(fig, path)


def invariants(solution: Solution, title: str, path: Path) -> Path:
    """Each invariant's relative change from the start: |X(t)/X(0) − 1| on a log scale where it
    stays small (conserved), X(t)/X(0) − 1 on a linear scale where the torques change it."""
    fig, axes = plt.subplots(2, 1, figsize=(8, 5.5), sharex=True)
    symbols = {"angular_momentum_norm": "|G|", "kinetic_energy": "T", "energy": "E"}
    for ax, (name, values) in zip(axes, solution.invariants.items()):
        symbol = symbols.get(name, name)
        change = relative_change(values)
        if np.abs(change).max() < CONSERVED:  # kept to rounding or integration error: spans decades
            ax.semilogy(solution.t, np.maximum(np.abs(change), 1e-17), label=f"{symbol}(0) = {values[0]:.6g}")
            ax.set_ylabel(f"|{symbol}(t)/{symbol}(0) − 1| [1]")
        else:  # changed by the torques: the signed relative change
            ax.plot(solution.t, change, label=f"{symbol}(0) = {values[0]:.6g}")
            ax.set_ylabel(f"{symbol}(t)/{symbol}(0) − 1 [1]")
        ax.grid(alpha=0.3, which="both")
        ax.legend(loc="lower right", fontsize=LEGEND_SIZE)
    axes[-1].set_xlabel("t [s]")
    axes[0].set_title(f"{title}: relative change of the invariants")
    return finish(fig, path)


def curves(t: np.ndarray, curves: dict[str, np.ndarray], ylabel: str, title: str, path: Path,
            legend: str = "upper right") -> Path:
    """Curves against t on one axis."""
    fig, ax = plt.subplots(figsize=(8, 4.5))
    for label, values in curves.items():
        ax.plot(t, values, label=label)
    ax.set_xlabel("t [s]")
    ax.set_ylabel(ylabel)
    ax.set_title(title)
    ax.legend(loc=legend, fontsize=LEGEND_SIZE)
    ax.grid(alpha=0.3)
    return finish(fig, path)


def euler_angles(solution: Solution, title: str, path: Path) -> Path:
    """ψ and φ wrapped to [−π, π), θ in [0, π], the singular times (sin θ ≈ 0) shaded."""
    psi, theta, phi = solution.euler_angles().T
    fig, axes = plt.subplots(3, 1, figsize=(8, 7), sharex=True)
    curves = (("ψ (precession)", wrap_angle(psi), (-np.pi, np.pi)), ("θ (nutation)", theta, (0, np.pi)),
              ("φ (proper rotation)", wrap_angle(phi), (-np.pi, np.pi)))
    for ax, (label, values, limits) in zip(axes, curves):
        ax.plot(solution.t, values, lw=1.0)
        mark_singular(ax, solution.t, theta)
        ax.set_ylim(limits[0] - 0.1, limits[1] + 0.1)
        ticks = {label: value for label, value in PI_TICKS.items() if value >= limits[0]}
        ax.set_yticks(list(ticks.values()), list(ticks))
        ax.set_ylabel(unit_label(solution, "psi", label))
        ax.grid(alpha=0.3)
    if axes[0].get_legend_handles_labels()[0]:
        axes[0].legend(loc="upper right", fontsize=LEGEND_SIZE)
    axes[-1].set_xlabel("t [s]")
    axes[0].set_title(f"{title}: attitude, Euler angles z-x-z")
    return finish(fig, path)


def error(solution: Solution, reference: Solution, title: str, path: Path) -> Path:
    fig, ax = plt.subplots(figsize=(8, 4))
    err = np.linalg.norm(solution.omega - reference.omega, axis=1)
    ax.semilogy(solution.t, np.maximum(err, 1e-18), label=f"|ω − ω_closed form| ({solution.method})")
    ax.set_xlabel("t [s]")
    ax.set_ylabel(unit_label(solution, "p", "error"))
    ax.set_title(f"{title}: error against the closed form")
    ax.legend(fontsize=LEGEND_SIZE)
    ax.grid(alpha=0.3, which="both")
    return finish(fig, path)


