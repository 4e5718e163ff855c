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

import numpy as np

from gyrostat.solution import Solution


class _Pyplot:
    """matplotlib's pyplot on the Agg backend, imported at its first use: ``import gyrostat`` (the
    command line, each sweep worker) does not pay for matplotlib (~0.3 s of ~0.45 s), and a user's
    backend is left alone until gyrostat draws."""

    _module = None

    def __getattr__(self, name: str):
        if _Pyplot._module is None:
            import matplotlib

            matplotlib.use("Agg")
            import matplotlib.pyplot

            _Pyplot._module = matplotlib.pyplot
        return getattr(_Pyplot._module, name)


plt = _Pyplot()

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
ROUNDING = 2.0 ** -52  # double precision's ε: relative changes of a few ε are rounding, not drift
WINDOW_PERIODS = 3  # a long oscillating run's omega plot: windows of about this many periods
BANDS = 40  # periods in one panel beyond which the curves fill it as solid bands


def legend_outside(ax, **extra) -> None:
    """The legend to the right of the axes, where it covers no curve (for panels whose curves
    fill the whole area)."""
    ax.legend(loc="upper left", bbox_to_anchor=(1.01, 1.0), borderaxespad=0.0, fontsize=LEGEND_SIZE, **extra)


def periods(values: np.ndarray) -> float:
    """About how many oscillations a curve makes: half its crossings of its own mean."""
    values = np.asarray(values, dtype=float)
    centred = values - np.mean(values)
    return float(np.count_nonzero(np.diff(np.sign(centred)) != 0)) / 2


def oscillations(columns: np.ndarray) -> float:
    """About how many periods the motion of several curves spans: the fewest oscillations of a
    curve that oscillates (a component such as dn makes two per period of ω, sn and cn one)."""
    counts = [periods(columns[:, i]) for i in range(columns.shape[1])] if len(columns) else []
    counts = [c for c in counts if c > 0]
    return min(counts) if counts else 0.0


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
    """p, q, r against t (and the reference dotted). A run of many periods would fill one panel
    with solid bands: it is drawn instead in two windows of about WINDOW_PERIODS periods, at the
    start and at the end, where each curve and the reference can be told apart (the difference
    over the whole span is error.png)."""
    t = solution.t
    n_periods = oscillations(solution.omega)
    windows = [(t[0], t[-1])] if n_periods <= BANDS else [
        (t[0], t[0] + (t[-1] - t[0]) * WINDOW_PERIODS / n_periods), (t[-1] - (t[-1] - t[0]) * WINDOW_PERIODS / n_periods, t[-1])]
    fig, axes = plt.subplots(len(windows), 1, figsize=(8, 4.5 if len(windows) == 1 else 6.5), squeeze=False)
    for k, (ax, (lo, hi)) in enumerate(zip(axes[:, 0], windows)):
        inside = (t >= lo) & (t <= hi)
        for i, name in enumerate(("p", "q", "r")):
            ax.plot(t[inside], solution.omega[inside, i], label=f"{name} ({solution.method})")
            if reference is not None:
                near = (reference.t >= lo) & (reference.t <= hi)
                ax.plot(reference.t[near], reference.omega[near, i], "k:", lw=1.2,
                        label="closed form" if i == 0 else None)
        ax.set_xlabel(unit_label(solution, "t"))
        ax.set_ylabel(unit_label(solution, "p", "angular velocity in body axes"))
        if len(windows) > 1:
            ax.set_title(f"{'first' if k == 0 else 'last'} {WINDOW_PERIODS} of {n_periods:.0f} periods", fontsize=10)
        legend_outside(ax)
        ax.grid(alpha=0.3)
    fig.suptitle(textwrap.fill(title, 80), fontsize=11)
    return finish(fig, path)


def invariants(solution: Solution, title: str, path: Path) -> Path:
    """Each invariant's relative change from the start, one panel per invariant the model
    records: where it stays small (conserved), the largest |X(t)/X(0) − 1| so far on a log scale
    (a drift reads as a rising line; a change of a few ε as rounding, not as solid blocks of
    noise), with the rounding level ε marked; where the torques change it, X(t)/X(0) − 1 signed on
    a linear scale."""
    items = list(solution.invariants.items())
    fig, axes = plt.subplots(max(len(items), 1), 1, figsize=(8, 2.9 * max(len(items), 1) + 0.3), sharex=True,
                             squeeze=False)
    axes = axes[:, 0]
    symbols = {"angular_momentum_norm": "|G|", "kinetic_energy": "T", "energy": "E"}
    kept = set(solution.kept)
    for ax, (name, values) in zip(axes, items):
        symbol = symbols.get(name, name)
        change = relative_change(values)
        ax.set_title(f"{symbol}: " + ("conserved by the model" if name in kept else
                                      "a first integral of the free body, changed by the torques"), fontsize=9)
        if np.abs(change).max() < CONSERVED:  # kept to rounding or integration error: spans decades
            envelope = np.maximum.accumulate(np.abs(change))
            shown = np.where(envelope > 0, envelope, np.nan)  # exactly kept so far: nothing to draw on a log scale
            ax.semilogy(solution.t, shown, label=f"largest so far; {symbol}(0) = {values[0]:.6g}")
            ax.axhline(ROUNDING, color="0.5", ls=":", lw=1, label="rounding: ε = 2.2e-16")
            top = np.nanmax(shown) if np.isfinite(shown).any() else ROUNDING
            ax.set_ylim(ROUNDING / 10, max(top, ROUNDING) * 10)
            ax.set_ylabel(f"|{symbol}(t)/{symbol}(0) − 1| [1]")
        else:  # changed by the torques: the signed relative change
            ax.plot(solution.t, change, label=f"{symbol}(0) = {values[0]:.6g}")
            ax.set_ylabel(f"{symbol}(t)/{symbol}(0) − 1 [1]")
        ax.grid(alpha=0.3, which="both")
        legend_outside(ax)
    axes[-1].set_xlabel("t [s]")
    fig.suptitle(textwrap.fill(f"{title}: relative change of the first integrals", 80), fontsize=11)
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
    curves = (("precession about inertial z\nψ", wrap_angle(psi), (-np.pi, np.pi)),
              ("body z to inertial z\nθ", theta, (0, np.pi)),
              ("rotation about body z\nφ", wrap_angle(phi), (-np.pi, np.pi)))
    for ax, (label, values, limits) in zip(axes, curves):
        ax.plot(solution.t, values, lw=1.0)
        mark_singular(ax, solution.t, theta)
        ax.set_ylim(limits[0] - 0.1, limits[1] + 0.1)
        ticks = {label: value for label, value in PI_TICKS.items() if value >= limits[0]}
        ax.set_yticks(list(ticks.values()), list(ticks))
        ax.set_ylabel(unit_label(solution, "psi", label))
        ax.grid(alpha=0.3)
    if axes[0].get_legend_handles_labels()[0]:
        legend_outside(axes[0])
    axes[-1].set_xlabel("t [s]")
    axes[0].set_title(f"{title}: attitude, z-x-z Euler angles to the start frame (θ is not the nutation to G)")
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


