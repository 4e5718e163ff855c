"""The Lagrange top's plots: the slow variables, the roots of the nutation cubic, the nutation
and the validity numbers, the full and the averaged top side by side (:func:`draw`)."""

from __future__ import annotations

import numpy as np

from gyrostat.assumptions import SMALL
from gyrostat.figures import LEGEND_SIZE, keep, legend_outside, plt, unit_label
from gyrostat.families.lagrange_top.models import SEPARATRIX_LIMIT


def draw(scene, solutions: dict, derived: dict, folder) -> list:
    """slow.png (G_z, H, r), roots.png (u1, u2, u3 and cos θ), nutation.png (θ), validity.png; the
    full and the averaged top side by side, or the one the model ladder chose."""
    full, avg, exact_r = solutions.get("full"), solutions.get("averaged"), derived["exact_r"]
    epsilon = scene.doc["torque"]["epsilon"]
    main = full if full is not None else avg
    # drawn against t [s]; the paper's slow time τ = εt is the top axis (its scale, not a unit)
    t_f = full.t if full is not None else None
    t_a = avg.t if avg is not None else None

    def slow_axis(ax):
        top = ax.secondary_xaxis("top", functions=(lambda t: epsilon * t, lambda tau: tau / epsilon))
        top.set_xlabel(f"slow time τ = εt (ε = {epsilon:g})", fontsize=LEGEND_SIZE)
    case = f"{scene.title} (ε = {epsilon:g})"
    sf = dict(lw=0.6, color="tab:blue", alpha=0.8)
    sa = dict(lw=1.8, ls="--", color="tab:orange")
    files = []
    wanted = set(scene.plots)
    both = full is not None and avg is not None

    fig, axes = plt.subplots(4 if both else 3, 1, figsize=(8, 10 if both else 8), sharex=True)
    for ax, key in zip(axes, ("G_z", "H", "r")):
        if full is not None:
            ax.plot(t_f, full[key], label="full model (ω, quaternion)", **sf)
        if avg is not None:
            ax.plot(t_a, avg[key], label="averaged over nutation", **sa)
        if key == "r":
            ax.plot(main.t[: exact_r.size], exact_r, "k:", lw=1.2, label="exact (3.3)")
        ax.set_ylabel(unit_label(avg if avg is not None else full, key))
        ax.grid(alpha=0.3)
        legend_outside(ax)
    if both:  # G_z and H have different units: their differences relative to each one's start
        n = min(t_f.size, t_a.size)
        for key, color in (("G_z", "tab:blue"), ("H", "tab:red")):
            scale = abs(avg[key][0]) or 1.0
            axes[3].plot(t_f[:n], (full[key][:n] - avg[key][:n]) / scale, lw=0.6, color=color,
                         label=f"{key}: (full − averaged)/|{key}(0)|")
        axes[3].set_ylabel("relative difference [1]")
        axes[3].grid(alpha=0.3)
        legend_outside(axes[3])
    axes[0].set_title(f"{case}: first integrals")
    slow_axis(axes[0])
    axes[-1].set_xlabel("t [s]")
    keep(fig, folder / "slow.png", "slow" in wanted, files)

    fig, axes = plt.subplots(2, 1, figsize=(8, 7), sharex=True, gridspec_kw=dict(height_ratios=[1, 1.6]))
    if full is not None:
        axes[0].plot(t_f, full["u3"], label="u3 (full: roots of its G_z, H, r)", **sf)
        axes[1].plot(t_f, full["cos_theta"], lw=0.4, color="0.75", label="cos θ (full model)")
    if avg is not None:
        axes[0].plot(t_a, avg["u3"], label="u3 (averaged)", **sa)
    axes[0].set_ylabel("u3 (≥ 1) [1]")
    for key, color in (("u1", "tab:blue"), ("u2", "tab:green")):
        if full is not None:
            axes[1].plot(t_f, full[key], lw=0.8, color=color, label=f"{key} (full)")
        if avg is not None:
            axes[1].plot(t_a, avg[key], lw=1.8, ls="--", color="tab:orange" if key == "u1" else "tab:red",
                         label=f"{key} (averaged)")
    axes[1].set_ylabel("u = cos θ: u1 ≤ cos θ ≤ u2 [1]")
    for ax in axes:
        ax.grid(alpha=0.3)
        legend_outside(ax)
    axes[0].set_title(f"{case}: roots of the nutation cubic")
    slow_axis(axes[0])
    axes[-1].set_xlabel("t [s]")
    keep(fig, folder / "roots.png", "roots" in wanted, files)

    bounds, t_b = (avg, t_a) if avg is not None else (full, t_f)
    fig, ax = plt.subplots(figsize=(8, 4.5))
    if full is not None:
        ax.plot(t_f, np.degrees(full["theta"]), lw=0.4, color="tab:blue", label="θ (full model)")
    with np.errstate(invalid="ignore"):  # the bounds in the colours of roots.png: u1 orange, u2 red
        for key, style, color in (("u1", "--", "tab:orange"), ("u2", ":", "tab:red")):
            ax.plot(t_b, np.degrees(np.arccos(np.clip(bounds[key], -1, 1))), ls=style, lw=1.8, color=color,
                    label=f"arccos {key}" + (" (averaged)" if bounds is avg else " (full)"))
    ax.set_xlabel("t [s]")
    slow_axis(ax)
    ax.set_ylabel("θ: symmetry axis to the vertical [deg]")
    ax.set_title(f"{case}: nutation between its bounds")
    ax.grid(alpha=0.3)
    legend_outside(ax)
    keep(fig, folder / "nutation.png", "nutation" in wanted, files)

    fig, ax = plt.subplots(figsize=(8, 4.5))
    if "adiabaticity" in bounds:
        ax.semilogy(t_b, bounds["adiabaticity"], label="N = rate · T_nut (must be ≪ 1)")
    ax.semilogy(t_b, np.maximum(1 - bounds["m"], 1e-17), label="1 − k² (separatrix at 0)")
    ax.semilogy(t_b, np.maximum(bounds["m"], 1e-17), label="k² (regular precession at 0)")
    ax.axhline(SMALL, color="tab:blue", ls=":", lw=1, label=f"limit N = {SMALL}")
    ax.axhline(SEPARATRIX_LIMIT, color="tab:orange", ls=":", lw=1, label=f"limit 1 − k² = {SEPARATRIX_LIMIT}")
    ax.set_xlabel("t [s]")
    slow_axis(ax)
    ax.set_ylabel("N, k², 1 − k² [1]")
    ax.set_title(f"{case}: validity of the averaging (along the " + ("averaged" if bounds is avg else "full")
                 + " solution)")
    ax.grid(alpha=0.3, which="both")
    legend_outside(ax)
    keep(fig, folder / "validity.png", "validity" in wanted, files)
    return files
