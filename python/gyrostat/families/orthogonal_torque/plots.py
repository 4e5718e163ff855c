"""The orthogonal torque family's plots (:func:`draw`, with :mod:`gyrostat.figures`): ω with
the torque-free gyrostat at τ(t), the invariants, τ(t) and g(t), the angles of G and the
precession, the errors of the nearly spherical approximations."""

from __future__ import annotations

import numpy as np

from gyrostat import figures
from gyrostat.families.orthogonal_torque.free_motion import wrap
from gyrostat.figures import LEGEND_SIZE, keep, legend_outside, mark_singular, plt, unit_label, wrap_angle


def _law_text(spec) -> str:
    if isinstance(spec, (int, float)):
        return f"L = {spec:g}"
    kind = spec.get("kind", "constant")
    if kind == "constant":
        return f"L = {spec['value']:g}"
    if kind == "harmonic":
        terms = " ".join(f"{'+' if a >= 0 else '−'} {abs(a):g} sin({w:g}t)"
                         for a, w in zip(spec.get("amplitudes", []), spec.get("frequencies", [])))
        return f"L = {spec['mean']:g} {terms}"
    return f"L: {kind}"


def draw(scene, solutions: dict, derived: dict, folder) -> list:

    laws = {spec["name"]: spec["law"] for spec in scene.doc["runs"]}
    results = {run.name: (solutions[run.name], derived[run.name]["torque_free"], derived[run.name]["approximations"],
                          laws[run.name]) for run in scene.runs if run.name in derived}
    spherical = scene.kind.spherical(scene.doc)
    wanted = set(scene.plots)
    files = []
    n = len(results)
    if n == 0:
        return files
    # angular velocity with the torque-free solution at τ(t)
    fig, axes = plt.subplots(n, 1, figsize=(8, 3.2 * n), sharex=True, squeeze=False)
    for ax, (name, (sol, zv, _, spec)) in zip(axes[:, 0], results.items()):
        for i, c in enumerate(("p", "q", "r")):
            ax.plot(sol.t, sol.omega[:, i], label=f"{c} (full model)")
            ax.plot(sol.t, zv[:, i], "k:", lw=1, label="ω_ZV(τ(t)) (torque-free)" if i == 0 else None)
        ax.set_ylabel(unit_label(sol, "p", "ω"))
        ax.set_title(f"{scene.title}: {_law_text(spec)}")
        legend_outside(ax)
        ax.grid(alpha=0.3)
    axes[-1, 0].set_xlabel("t [s]")
    keep(fig, folder / "omega.png", "omega" in wanted, files)
    # invariants: relative change
    fig, axes = plt.subplots(2, 1, figsize=(8, 5.5), sharex=True)
    for name, (sol, *_rest) in results.items():
        for ax, key, label in zip(axes, ("angular_momentum_norm", "h"), ("|G|", "h = ω·Jω")):
            v = sol[key]
            ax.plot(sol.t, v / v[0] - 1, label=f"{label}, {name}")
            ax.set_ylabel(f"{label}: relative change [1]")
    for ax in axes:
        ax.grid(alpha=0.3)
        legend_outside(ax)
    axes[0].set_title(f"{scene.title}: invariants (exact for the servo torque)")
    axes[1].set_xlabel("t [s]")
    keep(fig, folder / "invariants.png", "invariants" in wanted, files)
    # τ(t) and g(t)
    fig, axes = plt.subplots(2, 1, figsize=(8, 5.5), sharex=True)
    for name, (sol, *_rest) in results.items():
        axes[0].plot(sol.t, sol["tau"], label=f"τ(t), {name}")
        line, = axes[1].plot(sol.t, sol["g"], label=f"g = 1 − L/|Q|, {name}")
        for c in derived[name]["g_report"]["crossings"]:
            axes[0].plot(c["t"], c["tau"], "o", ms=3, color=line.get_color())
            axes[1].plot(c["t"], 0.0, "o", ms=3, color=line.get_color())
    axes[0].plot(sol.t, sol.t - sol.t[0], "k:", lw=1, label="τ = t (no torque)")
    axes[1].axhline(0.0, color="r", lw=0.8, ls="--", label="g = 0: τ stops")
    axes[0].set_ylabel("τ [s]")
    axes[1].set_ylabel("g = dτ/dt [1]")
    axes[1].set_xlabel("t [s]")
    axes[0].set_title(f"{scene.title}: time change τ(t) (paper (10))")
    for ax in axes:
        ax.grid(alpha=0.3)
        legend_outside(ax)
    axes[0].text(0.99, 0.02, "dots: g = 0 (τ stops, then reverses)", transform=axes[0].transAxes, ha="right",
                 fontsize=LEGEND_SIZE)
    keep(fig, folder / "tau.png", "tau" in wanted, files)
    # the nutation ϑ and azimuth φ_G of G in body axes, the z-x-z precession ψ, with the
    # approximations at τ(t); one legend per row, right of the last column (over no curve)
    fig, axes = plt.subplots(3, n, figsize=(6 * n, 8), sharex=True, squeeze=False)
    for j, (name, (sol, zv, approx, spec)) in enumerate(results.items()):
        ang = np.column_stack([sol["theta_G"], sol["phi_G"]])
        euler = sol.euler_angles()
        ax_psi, ax_th, ax_ph = axes[:, j]
        ax_th.plot(sol.t, ang[:, 0], label="full model")
        ax_ph.plot(sol.t, wrap_angle(ang[:, 1]), label="full model")
        ax_psi.plot(sol.t, wrap_angle(euler[:, 0]), label="full model (quaternion; inertial G moves)")
        styles = {"exact": ("k:", "torque-free ZV at τ(t)"), "zeroth": ("--", "zeroth approx. (21) at τ(t)"),
                  "first": ("-.", "first approx. (21)+μ(22) at τ(t)")}
        for key, a in approx.items():
            st, label = styles[key]
            if key != "exact":
                ax_th.plot(sol.t, a[:, 1], st, label=label)
                ax_ph.plot(sol.t, wrap_angle(a[:, 2]), st, label=label)
            ax_psi.plot(sol.t, wrap_angle(a[:, 0]), st, label=label)
        ax_psi.set_title(f"{_law_text(spec)}")
        mark_singular(ax_th, sol.t, ang[:, 0])
        ax_psi.set_ylabel("ψ precession, z-x-z [rad]")
        ax_th.set_ylabel("ϑ nutation: body z to G [rad]")
        ax_ph.set_ylabel("φ_G azimuth of G in body [rad]")
        ax_ph.set_xlabel("t [s]")
        for ax in axes[:, j]:
            ax.grid(alpha=0.3)
    for ax in axes[:, -1]:
        legend_outside(ax)
    fig.suptitle(f"{scene.title}: G in body axes (nutation ϑ, azimuth φ_G) and the precession ψ", fontsize=10)
    keep(fig, folder / "euler_angles.png", "euler_angles" in wanted, files)
    # errors of the approximations (nearly spherical only)
    if spherical is not None and "approximation_errors" in wanted:
        fig, axes = plt.subplots(1, n, figsize=(6 * n, 4), squeeze=False)
        for ax, (name, (sol, zv, approx, spec)) in zip(axes[0], results.items()):
            ang = np.column_stack([sol["theta_G"], sol["phi_G"]])
            for key, st in (("zeroth", "--"), ("first", "-")):
                a = approx[key]
                ax.semilogy(sol.t, np.maximum(np.abs(ang[:, 0] - a[:, 1]), 1e-16), st, label=f"|Δθ| {key}")
                ax.semilogy(sol.t, np.maximum(np.abs(wrap(approx["exact"][:, 0] - a[:, 0])), 1e-16), st,
                            label=f"|Δψ| {key} (vs ZV ψ at τ(t))")
            ax.set_xlabel("t [s]")
            ax.set_ylabel("error [rad]")
            ax.set_ylim(1e-6, 5.0)
            ax.set_title(f"approximations at τ(t) vs full model, μ = {spherical.mu:g}, {_law_text(spec)}",
                         fontsize=9)
            ax.grid(alpha=0.3, which="both")
            ax.legend(fontsize=LEGEND_SIZE)
        files.append(figures.finish(fig, folder / "approximation_errors.png"))
    return files

