"""Plots of a scene's results for every scene kind (matplotlib, written to PNG files), drawn from
the states and named outputs the engine recorded."""

from __future__ import annotations

import textwrap
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from gyrostat.averaged import slow_variables  # noqa: E402
from gyrostat.solution import Solution  # noqa: E402

from gyrostat.lagrange import SEPARATRIX_LIMIT  # noqa: E402
from gyrostat.validity import SMALL  # noqa: E402

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


def _finish(fig, path: Path) -> Path:
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


def _keep(fig, path: Path, wanted: bool, files: list[Path]) -> None:
    """Writes a figure the scene asks for (and adds it to files); closes one it does not."""
    if wanted:
        files.append(_finish(fig, path))
    else:
        plt.close(fig)


def omega(solution: Solution, title: str, path: Path, reference: Solution | None = None) -> Path:
    fig, ax = plt.subplots(figsize=(8, 4.5))
    for i, name in enumerate(("p", "q", "r")):
        ax.plot(solution.t, solution.omega[:, i], label=f"{name} ({solution.method})")
        if reference is not None:
            ax.plot(reference.t, reference.omega[:, i], "k:", lw=1, label=f"{name} (closed form)" if i == 0 else None)
    ax.set_xlabel("t [s]")
    ax.set_ylabel("angular velocity in body axes [rad/s]")
    ax.set_title(title)
    ax.legend(loc="upper right", fontsize=LEGEND_SIZE)
    ax.grid(alpha=0.3)
    return _finish(fig, path)


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
    return _finish(fig, path)


def _curves(t: np.ndarray, curves: dict[str, np.ndarray], ylabel: str, title: str, path: Path,
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
    return _finish(fig, path)


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
        ax.set_ylabel(f"{label} [rad]")
        ax.grid(alpha=0.3)
    if axes[0].get_legend_handles_labels()[0]:
        axes[0].legend(loc="upper right", fontsize=LEGEND_SIZE)
    axes[-1].set_xlabel("t [s]")
    axes[0].set_title(f"{title}: attitude, Euler angles z-x-z")
    return _finish(fig, path)


def error(solution: Solution, reference: Solution, title: str, path: Path) -> Path:
    fig, ax = plt.subplots(figsize=(8, 4))
    err = np.linalg.norm(solution.omega - reference.omega, axis=1)
    ax.semilogy(solution.t, np.maximum(err, 1e-18), label=f"|ω − ω_closed form| ({solution.method})")
    ax.set_xlabel("t [s]")
    ax.set_ylabel("error [rad/s]")
    ax.set_title(f"{title}: error against the closed form")
    ax.legend(fontsize=LEGEND_SIZE)
    ax.grid(alpha=0.3, which="both")
    return _finish(fig, path)


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
        for label, values, color in zip(labels, curves[name], ("tab:blue", "tab:red")):
            style = dict(AVERAGED_STYLE, color=color) if name == "averaged" else FULL_STYLE
            legend = f"{label} (averaged)" if name == "averaged" else ("full model" if label == labels[0] else None)
            ax.plot(solutions[name].t, values, label=legend, **style)
    unit = "[rad²/s²]" if kind == "xy" else "[rad/s]"
    ax.set_ylabel(f"{', '.join(labels)} {unit}")
    ax.set_title(title)
    ax.legend(fontsize=LEGEND_SIZE)
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
    return _finish(fig, path)


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
    return _finish(fig, path)


def mass(solution: Solution, title: str, path: Path) -> Path:
    """The moving mass's displacement u relative to the carrier (the explicit damper model)."""
    return _curves(solution.t, {name: solution[name] for name in ("u_1", "u_2", "u_3")},
                   "displacement of the mass in body axes [m]", f"{title}: moving mass", path)


def _rigid_body(scene, solutions: dict[str, Solution], derived: dict, folder: Path) -> list[Path]:
    files = []
    main = solutions.get("full", solutions.get("closed_form"))
    reference = derived.get("reference")
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
        elif plot == "euler_angles" and "q_w" in main.state_names:
            files.append(euler_angles(main, scene.title, path))
        elif plot == "error" and reference is not None:
            files.append(error(main, reference, scene.title, path))
        elif plot == "mass":
            files.append(mass(main, scene.title, path))
    return files




def _lagrange_top(scene, solutions: dict[str, Solution], derived: dict, folder: Path) -> list[Path]:
    """slow.png (G_z, H, r), roots.png (u1, u2, u3 and cos θ), nutation.png (θ), validity.png; the
    full and the averaged top side by side, or the one the model ladder chose."""
    full, avg, exact_r = solutions.get("full"), solutions.get("averaged"), derived["exact_r"]
    epsilon = scene.doc["torque"]["epsilon"]
    main = full if full is not None else avg
    tau_f = epsilon * full.t if full is not None else None
    tau_a = epsilon * avg.t if avg is not None else None
    case = f"{scene.title} (ε = {epsilon:g})"
    sf = dict(lw=0.6, color="tab:blue", alpha=0.8)
    sa = dict(lw=1.8, ls="--", color="tab:orange")
    files = []
    wanted = set(scene.plots)
    both = full is not None and avg is not None

    fig, axes = plt.subplots(4 if both else 3, 1, figsize=(8, 10 if both else 8), sharex=True)
    for ax, key, label in zip(axes, ("G_z", "H", "r"), ("G_z [kg m²/s]", "H [J]", "r [rad/s]")):
        if full is not None:
            ax.plot(tau_f, full[key], label="full model (ω, quaternion)", **sf)
        if avg is not None:
            ax.plot(tau_a, avg[key], label="averaged over nutation", **sa)
        if key == "r":
            ax.plot(epsilon * main.t[: exact_r.size], exact_r, "k:", lw=1.2, label="exact (3.3)")
        ax.set_ylabel(label)
        ax.grid(alpha=0.3)
        ax.legend(fontsize=LEGEND_SIZE, loc="upper right")
    if both:
        n = min(tau_f.size, tau_a.size)
        for key, color in (("G_z", "tab:blue"), ("H", "tab:red")):
            axes[3].plot(tau_f[:n], full[key][:n] - avg[key][:n], lw=0.6, color=color, label=f"{key}: full − averaged")
        axes[3].set_ylabel("difference [kg m²/s], [J]")
        axes[3].grid(alpha=0.3)
        axes[3].legend(fontsize=LEGEND_SIZE, loc="upper right")
    axes[0].set_title(f"{case}: first integrals")
    axes[-1].set_xlabel("slow time τ = εt [s]")
    _keep(fig, folder / "slow.png", "slow" in wanted, files)

    fig, axes = plt.subplots(2, 1, figsize=(8, 7), sharex=True, gridspec_kw=dict(height_ratios=[1, 1.6]))
    if full is not None:
        axes[0].plot(tau_f, full["u3"], label="u3 (full: roots of its G_z, H, r)", **sf)
        axes[1].plot(tau_f, full["cos_theta"], lw=0.4, color="0.75", label="cos θ (full model)")
    if avg is not None:
        axes[0].plot(tau_a, avg["u3"], label="u3 (averaged)", **sa)
    axes[0].set_ylabel("u3 (≥ 1) [1]")
    for key, color in (("u1", "tab:blue"), ("u2", "tab:green")):
        if full is not None:
            axes[1].plot(tau_f, full[key], lw=0.8, color=color, label=f"{key} (full)")
        if avg is not None:
            axes[1].plot(tau_a, avg[key], lw=1.8, ls="--", color="tab:orange" if key == "u1" else "tab:red",
                         label=f"{key} (averaged)")
    axes[1].set_ylabel("u = cos θ: u1 ≤ cos θ ≤ u2 [1]")
    for ax in axes:
        ax.grid(alpha=0.3)
        ax.legend(fontsize=LEGEND_SIZE, loc="upper right")
    axes[0].set_title(f"{case}: roots of the nutation cubic")
    axes[-1].set_xlabel("slow time τ = εt [s]")
    _keep(fig, folder / "roots.png", "roots" in wanted, files)

    bounds, tau_b = (avg, tau_a) if avg is not None else (full, tau_f)
    fig, ax = plt.subplots(figsize=(8, 4.5))
    if full is not None:
        ax.plot(tau_f, np.degrees(full["theta"]), lw=0.4, color="tab:blue", label="θ (full model)")
    with np.errstate(invalid="ignore"):
        for key, style in (("u1", "--"), ("u2", ":")):
            ax.plot(tau_b, np.degrees(np.arccos(np.clip(bounds[key], -1, 1))), ls=style, lw=1.6, color="tab:orange",
                    label=f"arccos {key}" + (" (averaged)" if bounds is avg else " (full)"))
    ax.set_xlabel("slow time τ = εt [s]")
    ax.set_ylabel("nutation angle θ [deg]")
    ax.set_title(f"{case}: nutation between its bounds")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=LEGEND_SIZE, loc="lower right")
    _keep(fig, folder / "nutation.png", "nutation" in wanted, files)

    fig, ax = plt.subplots(figsize=(8, 4.5))
    if "adiabaticity" in bounds:
        ax.semilogy(tau_b, bounds["adiabaticity"], label="N = rate · T_nut (must be ≪ 1)")
    ax.semilogy(tau_b, np.maximum(1 - bounds["m"], 1e-17), label="1 − k² (separatrix at 0)")
    ax.semilogy(tau_b, np.maximum(bounds["m"], 1e-17), label="k² (regular precession at 0)")
    ax.axhline(SMALL, color="tab:blue", ls=":", lw=1, label=f"limit N = {SMALL}")
    ax.axhline(SEPARATRIX_LIMIT, color="tab:orange", ls=":", lw=1, label=f"limit 1 − k² = {SEPARATRIX_LIMIT}")
    ax.set_xlabel("slow time τ = εt [s]")
    ax.set_ylabel("N, k², 1 − k² [1]")
    ax.set_title(f"{case}: validity of the averaging (along the " + ("averaged" if bounds is avg else "full")
                 + " solution)")
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=LEGEND_SIZE, loc="lower right")
    _keep(fig, folder / "validity.png", "validity" in wanted, files)
    return files


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


def _orthogonal_torque(scene, solutions: dict[str, Solution], derived: dict, folder: Path) -> list[Path]:
    from gyrostat.orthogonal import wrap

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
        ax.set_ylabel("ω [rad/s]")
        ax.set_title(f"{scene.title}: {_law_text(spec)}")
        ax.legend(loc="upper right", fontsize=LEGEND_SIZE, ncol=2)
        ax.grid(alpha=0.3)
    axes[-1, 0].set_xlabel("t [s]")
    _keep(fig, folder / "omega.png", "omega" in wanted, files)
    # invariants: relative change
    fig, axes = plt.subplots(2, 1, figsize=(8, 5.5), sharex=True)
    for name, (sol, *_rest) in results.items():
        for ax, key, label in zip(axes, ("angular_momentum_norm", "h"), ("|G|", "h = ω·Jω")):
            v = sol[key]
            ax.plot(sol.t, v / v[0] - 1, label=f"{label}, {name}")
            ax.set_ylabel(f"{label}: relative change [1]")
    for ax in axes:
        ax.grid(alpha=0.3)
        ax.legend(loc="upper left", fontsize=LEGEND_SIZE)
    axes[0].set_title(f"{scene.title}: invariants (exact for the servo torque)")
    axes[1].set_xlabel("t [s]")
    _keep(fig, folder / "invariants.png", "invariants" in wanted, files)
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
    for ax, loc in zip(axes, ("upper left", "lower left")):
        ax.grid(alpha=0.3)
        ax.legend(loc=loc, fontsize=LEGEND_SIZE, framealpha=0.8, ncol=2)
    axes[0].text(0.99, 0.02, "dots: g = 0 (τ stops, then reverses)", transform=axes[0].transAxes, ha="right",
                 fontsize=LEGEND_SIZE)
    _keep(fig, folder / "tau.png", "tau" in wanted, files)
    # Euler angles (θ, φ of G in body axes; ψ) with the approximations at τ(t)
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
        ax_psi.set_ylabel("ψ precession [rad]")
        ax_th.set_ylabel("θ nutation (of G in body) [rad]")
        ax_ph.set_ylabel("φ proper rotation [rad]")
        ax_ph.set_xlabel("t [s]")
        for ax in axes[:, j]:
            ax.grid(alpha=0.3)
            ax.legend(loc="best", fontsize=LEGEND_SIZE, framealpha=0.7)
    fig.suptitle(f"{scene.title}: Euler angles z-x-z", fontsize=10)
    _keep(fig, folder / "euler_angles.png", "euler_angles" in wanted, files)
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
        files.append(_finish(fig, folder / "approximation_errors.png"))
    return files


DRAW = {"rigid_body": _rigid_body, "averaged": _rigid_body, "moving_mass": _rigid_body,
        "lagrange_top": _lagrange_top, "orthogonal_torque": _orthogonal_torque}


def draw_scene(scene, solutions: dict[str, Solution], derived: dict, folder: Path) -> list[Path]:
    """The plots the scene asks for (``scene.plots``), by its kind; ``derived`` holds what the
    kind's analysis computed beside the runs (gyrostat.runner)."""
    files = DRAW[scene.kind.name](scene, solutions, derived, folder)
    if "ladder" in derived:
        files.append(ladder(derived["ladder"], f"{scene.title}: the model ladder", folder / "ladder.png",
                            scene.doc["integration"]["accuracy"]))
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
    if plot == "error" and doc["outputs"].get("reference") is None:
        return ("it needs a reference: [outputs] reference = \"closed_form\" (a rigid body with neither torques "
                "nor a rotor)")
    if plot == "approximation_errors" and getattr(scene.kind, "spherical", lambda _: None)(doc) is None:
        return "the zeroth and first approximations are for a nearly spherical body ([nearly_spherical]), not [body]"
    if plot == "euler_angles":
        return "it needs the attitude: give [initial] attitude (the run then integrates the quaternion)"
    return f"the scene's runs ({', '.join(r.name for r in scene.runs)}) have nothing to draw it from"


def ladder(rows: list[dict], title: str, path: Path, accuracy: float) -> Path:
    """Each rung's cost (seconds for the whole span) against its error measured against the top
    rung, the chosen one ringed, its estimate drawn as an arrow from the measured error, and the
    requested accuracy as a line: which model was cheap enough and accurate enough, at a glance."""
    fig, ax = plt.subplots(figsize=(6.4, 4.4))
    floor = min([r["error"] for r in rows if r["error"] > 0] + [accuracy]) * 1e-2
    for row in rows:
        error = max(row["error"], floor)
        reference = row["error"] == 0.0 and not row.get("estimate")
        ax.loglog(row["seconds"], error, "s" if reference else "o", ms=9, color="tab:gray" if reference else "tab:blue")
        label = row["rung"] + (" (reference)" if reference else "") + \
            (f", {row['switches']} switch(es)" if row.get("switches") else "")
        ax.annotate(label, (row["seconds"], error), textcoords="offset points", xytext=(8, 6), fontsize=9)
        if row.get("estimate"):
            ax.plot([row["seconds"]] * 2, [error, max(row["estimate"], floor)], color="tab:orange", lw=1.5)
            ax.plot(row["seconds"], max(row["estimate"], floor), "_", ms=14, mew=2, color="tab:orange")
        if row["chosen"]:
            ax.loglog(row["seconds"], error, "o", ms=18, mfc="none", mec="tab:red", mew=2)
    ax.axhline(accuracy, color="tab:red", ls="--", lw=1, label=f"requested accuracy {accuracy:g}")
    ax.plot([], [], color="tab:orange", marker="_", lw=1.5, label="error estimate (probe)")
    ax.plot([], [], "o", ms=12, mfc="none", mec="tab:red", mew=2, label="chosen")
    ax.set_xlabel("cost: time for the whole span [s]")
    ax.set_ylabel("error against the most complete model [1] (relative)")
    ax.set_title(title)
    ax.legend(fontsize=9, loc="best")
    ax.grid(True, which="both", alpha=0.3)
    return _finish(fig, path)


# ------------------------------------------------------------------------------------ sweeps
def _axis_label(ds, name: str) -> str:
    attrs = ds[name].attrs
    return f"{attrs.get('long_name', name)} [{attrs.get('units') or '1'}]"


def sweep(ds, expression: str, title: str, path: Path, contour: float | None = None,
          lines: list[dict] | None = None) -> Path:
    """A sweep's summary against its parameters: a line for one grid parameter, a heat map for
    two (with the level line ``summary = contour`` and reference lines), a scatter for a
    dispersion; members that failed are marked x."""
    from gyrostat.sweeps import summary

    values = summary(ds, expression)
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
        norm = matplotlib.colors.LogNorm(finite.min(), finite.max()) if log else None
        mesh = ax.pcolormesh(x, y, np.ma.masked_invalid(z), shading="nearest", cmap="viridis", norm=norm)
        fig.colorbar(mesh, ax=ax, label=label)
        handles = []
        if contour is not None and finite.size and finite.min() < contour < finite.max():
            ax.contour(x, y, z, levels=[contour], colors="w", linewidths=2)
            handles.append(matplotlib.lines.Line2D([], [], color="w", lw=2,
                                                   label=f"gyrostat: {expression} = {contour:g}"))
        for line in lines or ():
            handles += ax.plot(line["x"], line["y"], "r--", lw=2, label=line["label"])
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
    return _finish(fig, path)
