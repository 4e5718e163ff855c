"""Paper 003: a heavy symmetric top (Lagrange case) under a small, slowly varying torque.

Two models, both integrated by the C++ core:

* :class:`LagrangeTop` — the full model. State ``(p, q, r, Q_w, Q_x, Q_y, Q_z)``: angular
  velocity in body axes and the body→space quaternion (z up); the vertical in body axes
  γ = third row of R(Q). No Euler angles are integrated: θ, ψ, φ are outputs only.
* :class:`LagrangeAveraged` — the system averaged over the nutation in the slow variables
  ``(G_z, H, r)`` (the unperturbed first integrals; smooth, no sign bookkeeping), with
  v = ⟨cos θ⟩ = u1 + (u2 − u1)(K − E)/(m K). The roots u1 ≤ u2 ≤ u3 of the nutation cubic are
  reported for every output (the paper's variables).

Both take torques from the library's set; paper 003's (3.1), M = ε(−a(τ)p, −a(τ)q, −b(τ)r),
τ = εt, is :func:`paper_torque` (a ResistiveMedium). Both use the same clock t; the slow time is
τ = εt. The equations, the checks and the discrepancies with the paper are in
docs/papers/003_lagrange_top.md.

Validity of the averaged model (:func:`check`): the nutation period must be short against the
slow time scale, N = rate · T_nut ≪ 1 (rate = max(d/A, d3/C) of the damping), and the motion
must stay away from the separatrix (1 − k² ≳ 1e-3, where K diverges). Broken assumptions are
warned about (:class:`gyrostat.ValidityWarning`) with the number and what to use instead.
"""

from __future__ import annotations

import json
import math
import time
import tomllib
import warnings
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from gyrostat import _core
from gyrostat.solution import Solution
from gyrostat.validity import SMALL, Assumption, ValidityWarning

SEPARATRIX_LIMIT = 1e-3
"""1 − k² below this: near the separatrix (K(k) ≈ ln(4/√(1 − k²)), v has an infinite slope)."""

UNITS = {"t": "s", "tau": "s", "p": "rad/s", "q": "rad/s", "r": "rad/s", "q_w": "1", "q_x": "1", "q_y": "1",
         "q_z": "1", "G_z": "kg m^2/s", "H": "J", "kinetic_energy": "J", "theta": "rad", "psi": "rad", "phi": "rad",
         "u1": "1", "u2": "1", "u3": "1", "m": "1", "v": "1", "T_nut": "s", "cos_theta": "1"}


def paper_torque(epsilon: float, a: Sequence[float] = (1.0, 1.0), b: Sequence[float] = (1.0, 1.0)):
    """Paper 003's (3.1): M = ε(−a(τ) p, −a(τ) q, −b(τ) r), τ = εt, a(τ) = Σ a_k τ^k, b likewise.

    As a polynomial in t: D_k = ε^{k+1} diag(a_k, a_k, b_k) of :class:`gyrostat.ResistiveMedium`."""
    epsilon = float(epsilon)
    if not math.isfinite(epsilon) or epsilon < 0:
        raise ValueError(f"epsilon = {epsilon} must be finite and non-negative")
    n = max(len(a), len(b))
    a = list(a) + [0.0] * (n - len(a))
    b = list(b) + [0.0] * (n - len(b))
    return _core.ResistiveMedium([epsilon ** (k + 1) * np.diag([a[k], a[k], b[k]]) for k in range(n)])


class _TopModel:
    def __init__(self, A: float, C: float, mu: float, torques: Sequence = ()):
        self.A, self.C, self.mu = float(A), float(C), float(mu)
        self.body = _core.Body([self.A, self.A, self.C])
        self.torques = tuple(torques)
        self._core = self._core_type(self.body, self.mu, list(self.torques))

    @property
    def dim(self) -> int:
        return self._core.dim

    def rhs(self, t: float, y) -> np.ndarray:
        return np.asarray(self._core.rhs(float(t), np.asarray(y, float)))

    def __repr__(self) -> str:
        return f"{type(self).__name__}(A={self.A}, C={self.C}, mu={self.mu}, torques={list(self.torques)!r})"


class LagrangeTop(_TopModel):
    """The full heavy symmetric top (A, A, C), μ = m g l > 0, plus torques (C++:
    model/lagrange_top.hpp). State (p, q, r, Q_w, Q_x, Q_y, Q_z); invariants G_z, H, r."""

    kind = "lagrange_top"
    state_names = ("p", "q", "r", "q_w", "q_x", "q_y", "q_z")
    _core_type = _core.LagrangeTopCore


class LagrangeAveraged(_TopModel):
    """The top averaged over the nutation (C++: model/lagrange_averaged.hpp). State
    (G_z, H, r); invariants u1, u2, u3. Torques of the paper's class (2.3) only: resistive media
    and linear damping with D = diag(d, d, d3), axial constant torques."""

    kind = "lagrange_averaged"
    state_names = ("G_z", "H", "r")
    _core_type = _core.LagrangeAveragedCore

    def rate(self, t) -> np.ndarray:
        """max(|d(t)|/A, |d3(t)|/C): the relaxation rate of the slow variables."""
        return np.array([self._core.rate(float(s)) for s in np.atleast_1d(t)])


def initial_state(omega, theta: float, phi: float = 0.0, psi: float = 0.0) -> np.ndarray:
    """(p, q, r, Q) from ω and the z-x-z Euler angles (radians): Q = q_z(ψ) ⊗ q_x(θ) ⊗ q_z(φ)."""
    omega = np.asarray(omega, float).ravel()
    if omega.size != 3 or not np.all(np.isfinite(omega)):
        raise ValueError(f"omega must be 3 finite numbers, got {omega!r}")

    def mul(a, b):
        w1, x1, y1, z1 = a
        w2, x2, y2, z2 = b
        return np.array([w1 * w2 - x1 * x2 - y1 * y2 - z1 * z2, w1 * x2 + x1 * w2 + y1 * z2 - z1 * y2,
                         w1 * y2 - x1 * z2 + y1 * w2 + z1 * x2, w1 * z2 + x1 * y2 - y1 * x2 + z1 * w2])

    qz = lambda a: np.array([math.cos(a / 2), 0.0, 0.0, math.sin(a / 2)])  # noqa: E731
    qx = lambda a: np.array([math.cos(a / 2), math.sin(a / 2), 0.0, 0.0])  # noqa: E731
    return np.concatenate([omega, mul(mul(qz(psi), qx(theta)), qz(phi))])


def vertical(y) -> np.ndarray:
    """(n, 3) upward vertical γ in body axes from full states (third row of R(Q))."""
    y = np.atleast_2d(np.asarray(y, float))
    w, x, yy, z = (y[:, 3:7] / np.linalg.norm(y[:, 3:7], axis=1, keepdims=True)).T
    return np.column_stack([2 * (x * z - w * yy), 2 * (yy * z + w * x), 1 - 2 * (x * x + yy * yy)])


def slow_variables(model, y) -> np.ndarray:
    """(n, 3) array (G_z, H, r) of full states y ((n, 7) or (7,))."""
    y = np.atleast_2d(np.asarray(y, float))
    g = vertical(y)
    p, q, r = y[:, 0], y[:, 1], y[:, 2]
    Gz = model.A * (p * g[:, 0] + q * g[:, 1]) + model.C * r * g[:, 2]
    H = 0.5 * (model.A * (p * p + q * q) + model.C * r * r) + model.mu * g[:, 2]
    return np.column_stack([Gz, H, r])


def euler_angles(y) -> np.ndarray:
    """(n, 3) z-x-z Euler angles (ψ, θ, φ) of full states; θ = atan2(sin θ, cos θ) (accurate near 0
    and π); ψ and φ are NaN where sin θ = 0 (only ψ ± φ is defined there)."""
    y = np.atleast_2d(np.asarray(y, float))
    w, x, yy, z = (y[:, 3:7] / np.linalg.norm(y[:, 3:7], axis=1, keepdims=True)).T
    r13, r23 = 2 * (x * z + w * yy), 2 * (yy * z - w * x)
    r31, r32 = 2 * (x * z - w * yy), 2 * (yy * z + w * x)
    r33 = 1 - 2 * (x * x + yy * yy)
    sin_theta = np.hypot(r13, r23)
    theta = np.arctan2(sin_theta, r33)
    singular = sin_theta < 1e-14
    psi = np.where(singular, np.nan, np.arctan2(r13, -r23))
    phi = np.where(singular, np.nan, np.arctan2(r31, r32))
    return np.column_stack([psi, theta, phi])


def nutation_table(model, slow) -> dict[str, np.ndarray]:
    """u1, u2, u3, m = k², alpha, v = ⟨cos θ⟩, T_nut = 2K/α for each row (G_z, H, r)."""
    slow = np.atleast_2d(np.asarray(slow, float))
    table = np.asarray(_core.lagrange_nutation_table(model.A, model.C, model.mu, slow[:, 0].tolist(),
                                                     slow[:, 1].tolist(), slow[:, 2].tolist()))
    return {name: table[:, i] for i, name in enumerate(("u1", "u2", "u3", "m", "alpha", "v", "T_nut"))}


def unperturbed(model, y0, t, t0: float = 0.0) -> tuple[np.ndarray, "_core.LagrangeUnperturbed"]:
    """u(t) = cos θ(t) of the unperturbed top through the initial full state y0 (paper (1.3),
    u = u1 + (u2 − u1) sn²(αt + β | k²)); returns (u, the closed-form object)."""
    y0 = np.asarray(y0, float).ravel()
    exact = _core.LagrangeUnperturbed(model.A, model.C, model.mu, y0[:3], vertical(y0)[0], float(t0))
    return np.asarray(exact.u(np.asarray(t, float).ravel().tolist())), exact


def solve(model, y0, t_span, *, method: str = "dop853", rtol: float = 1e-10, atol: float = 1e-12, t_eval=None,
          n_out: int | None = None, every_step: bool = False, max_steps: int = 1_000_000, first_step: float = 0.0,
          max_step: float = math.inf) -> Solution:
    """Integrates a :class:`LagrangeTop` (y0: 7-state) or a :class:`LagrangeAveraged` (y0: (G_z, H, r)
    or a full 7-state, converted) over t_span; returns a :class:`gyrostat.Solution` (failed runs
    keep their partial trajectory, with status and message)."""
    from gyrostat.solve import _check_method, _output_times, _solution

    _check_method(method)
    t0, t1, times = _output_times(t_span, t_eval, n_out)
    y = np.asarray(y0, float).ravel()
    if isinstance(model, LagrangeAveraged) and y.size == 7:
        y = slow_variables(model, y)[0]
    if y.size != model.dim:
        raise ValueError(f"initial state has {y.size} components; {type(model).__name__} needs {model.dim} "
                         f"({', '.join(model.state_names)})")
    result = model._core.solve(y, t0, t1, method, float(rtol), float(atol), times, bool(every_step), int(max_steps),
                               float(first_step), float(max_step))
    return _solution(result)


def outputs(model, solution: Solution) -> dict[str, np.ndarray]:
    """Named arrays of a solution: G_z, H, r, u1, u2, u3, m, v, T_nut for both models; for the full
    model also θ, ψ, φ, cos θ and the state."""
    out: dict[str, np.ndarray] = {"t": solution.t}
    if isinstance(model, LagrangeTop):
        for i, name in enumerate(model.state_names):
            out[name] = solution.y[:, i]
        slow = slow_variables(model, solution.y)
        angles = euler_angles(solution.y)
        out.update(psi=angles[:, 0], theta=angles[:, 1], phi=angles[:, 2], cos_theta=vertical(solution.y)[:, 2])
        out["kinetic_energy"] = 0.5 * (model.A * (solution.y[:, 0] ** 2 + solution.y[:, 1] ** 2)
                                       + model.C * solution.y[:, 2] ** 2)
    else:
        slow = solution.y
    out.update(G_z=slow[:, 0], H=slow[:, 1], r=slow[:, 2])
    table = nutation_table(model, slow)
    out.update({k: table[k] for k in ("u1", "u2", "u3", "m", "v", "T_nut")})
    return out


def check(model: LagrangeAveraged, slow, times, warn: bool = True) -> list[Assumption]:
    """The averaged model's assumptions along a trajectory of (G_z, H, r) at `times`:
    adiabaticity N = rate·T_nut ≪ 1, distance from the separatrix 1 − k² ≥ 1e-3, and the regular
    precession limit k² → 0 (reported; the averaging holds there). Warns for broken ones."""
    slow = np.atleast_2d(np.asarray(slow, float))
    times = np.asarray(times, float)
    table = nutation_table(model, slow)
    rate = model.rate(times)
    with np.errstate(invalid="ignore"):
        N = np.where(np.isfinite(table["T_nut"]), rate * table["T_nut"], np.inf)
    worst = int(np.argmax(N))
    results = [Assumption(
        "Lagrange averaged", "nutation period short against the slow time: N = rate·T_nut ≪ 1", float(N[worst]), SMALL,
        bool(N[worst] <= SMALL),
        f"worst at t = {times[worst]:.4g} (T_nut = {table['T_nut'][worst]:.4g}, k² = {table['m'][worst]:.4g}); "
        + ("" if N[worst] <= SMALL else "the averaged model is not accurate there: use the full LagrangeTop "
           "or a smaller epsilon"))]
    gap = 1.0 - table["m"]
    near = int(np.argmin(gap))
    results.append(Assumption(
        "Lagrange averaged", "away from the separatrix: 1 − k² ≥ 1e-3", float(gap[near]), SEPARATRIX_LIMIT,
        bool(gap[near] >= SEPARATRIX_LIMIT),
        f"closest at t = {times[near]:.4g}" + ("" if gap[near] >= SEPARATRIX_LIMIT else
                                               "; K(k) diverges and v has an infinite slope there, the error of "
                                               "averaging degrades to O(ε^½): use the full LagrangeTop")))
    smallest = int(np.argmin(table["m"]))
    results.append(Assumption(
        "Lagrange averaged", "regular precession limit k² → 0 (averaging holds; the roots u1, u2 are "
        "individually ill-conditioned there)", float(table["m"][smallest]), 0.0, True,
        f"smallest at t = {times[smallest]:.4g}; G_z, H, r and v stay accurate, u1 and u2 individually carry "
        "errors up to ~1e-8 (square-root sensitivity of a double root)"))
    if warn:
        for a in results:
            if not a.holds:
                warnings.warn(str(a), ValidityWarning, stacklevel=2)
    return results


def r_exact(r0: float, C: float, epsilon: float, b: Sequence[float], t) -> np.ndarray:
    """Paper (3.3) generalised: r = r0 exp(−(1/C) ∫_0^τ b(s) ds), τ = εt, b(τ) = Σ b_k τ^k."""
    tau = epsilon * np.asarray(t, float)
    integral = sum(bk * tau ** (k + 1) / (k + 1) for k, bk in enumerate(b))
    return r0 * np.exp(-integral / C)


# ---------------------------------------------------------------------------------------------
# Scenes of kind "lagrange_top"
# ---------------------------------------------------------------------------------------------

@dataclass
class LagrangeScene:
    name: str
    title: str
    description: str
    A: float
    C: float
    mu: float
    epsilon: float
    a: list[float]
    b: list[float]
    y0: np.ndarray
    tau_end: float
    n_out: int
    method: str
    rtol: float
    atol: float

    @classmethod
    def from_toml(cls, path) -> "LagrangeScene":
        path = Path(path)
        with path.open("rb") as handle:
            data = tomllib.load(handle)

        def need(table: str, key: str):
            try:
                return data[table][key]
            except KeyError:
                raise ValueError(f"{path}: [{table}] {key} is missing") from None

        A, C, mu = float(need("body", "A")), float(need("body", "C")), float(need("body", "mu"))
        epsilon = float(need("torque", "epsilon"))
        initial = data.get("initial", {})
        omega = need("initial", "omega")
        theta = math.radians(float(initial.get("theta_deg", 0.0)))
        phi = math.radians(float(initial.get("phi_deg", 0.0)))
        psi = math.radians(float(initial.get("psi_deg", 0.0)))
        integration = data.get("integration", {})
        tau_end = float(need("integration", "tau_end"))
        if not (epsilon > 0 and tau_end > 0):
            raise ValueError(f"{path}: epsilon = {epsilon} and tau_end = {tau_end} must be positive")
        return cls(name=path.stem, title=str(data.get("title", path.stem)), description=str(data.get("description", "")),
                   A=A, C=C, mu=mu, epsilon=epsilon, a=[float(x) for x in need("torque", "a")],
                   b=[float(x) for x in need("torque", "b")], y0=initial_state(omega, theta, phi, psi),
                   tau_end=tau_end, n_out=int(integration.get("n_out", 4001)),
                   method=str(integration.get("method", "dop853")), rtol=float(integration.get("rtol", 1e-10)),
                   atol=float(integration.get("atol", 1e-12)))


def _run_report(solution: Solution) -> dict:
    return {"method": solution.method, "status": solution.status, "message": solution.message,
            "stats": solution.stats,
            "invariant_relative_change": {
                name: float((v[-1] - v[0]) / v[0]) if v[0] != 0 else float(v[-1])
                for name, v in solution.invariants.items()},
            "notes": solution.notes}


def _save(columns: dict, folder: Path, stem: str) -> list[Path]:
    from gyrostat.runner import write_columns

    return write_columns(columns, folder, stem, UNITS)


def _draw(scene: LagrangeScene, full: dict, avg: dict, exact_r: np.ndarray, folder: Path) -> list[Path]:
    """slow.png (G_z, H, r), roots.png (u1, u2, u3 and cos θ), nutation.png (θ), validity.png."""
    from gyrostat.plots import _finish, plt

    tau_f, tau_a = scene.epsilon * full["t"], scene.epsilon * avg["t"]
    case = f"{scene.title} (ε = {scene.epsilon:g})"
    sf = dict(lw=0.6, color="tab:blue", alpha=0.8)
    sa = dict(lw=1.8, ls="--", color="tab:orange")
    files = []

    fig, axes = plt.subplots(4, 1, figsize=(8, 10), sharex=True)
    for ax, key, label in zip(axes, ("G_z", "H", "r"), ("G_z [kg m²/s]", "H [J]", "r [rad/s]")):
        ax.plot(tau_f, full[key], label="full model (ω, quaternion)", **sf)
        ax.plot(tau_a, avg[key], label="averaged over nutation", **sa)
        if key == "r":
            ax.plot(tau_f[: exact_r.size], exact_r, "k:", lw=1.2, label="exact (3.3)")
        ax.set_ylabel(label)
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8, loc="upper right")
    n = min(tau_f.size, tau_a.size)
    for key, color in (("G_z", "tab:blue"), ("H", "tab:red")):
        axes[3].plot(tau_f[:n], full[key][:n] - avg[key][:n], lw=0.6, color=color, label=f"{key}: full − averaged")
    axes[3].set_ylabel("difference [kg m²/s], [J]")
    axes[3].grid(alpha=0.3)
    axes[3].legend(fontsize=8, loc="upper right")
    axes[0].set_title(f"{case}: first integrals")
    axes[-1].set_xlabel("slow time τ = εt [s]")
    files.append(_finish(fig, folder / "slow.png"))

    fig, axes = plt.subplots(2, 1, figsize=(8, 7), sharex=True, gridspec_kw=dict(height_ratios=[1, 1.6]))
    axes[0].plot(tau_f, full["u3"], label="u3 (full: roots of its G_z, H, r)", **sf)
    axes[0].plot(tau_a, avg["u3"], label="u3 (averaged)", **sa)
    axes[0].set_ylabel("u3 (≥ 1)")
    axes[1].plot(tau_f, full["cos_theta"], lw=0.4, color="0.75", label="cos θ (full model)")
    for key, color in (("u1", "tab:blue"), ("u2", "tab:green")):
        axes[1].plot(tau_f, full[key], lw=0.8, color=color, label=f"{key} (full)")
        axes[1].plot(tau_a, avg[key], lw=1.8, ls="--", color="tab:orange" if key == "u1" else "tab:red",
                     label=f"{key} (averaged)")
    axes[1].set_ylabel("u = cos θ: u1 ≤ cos θ ≤ u2")
    for ax in axes:
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8, loc="upper right")
    axes[0].set_title(f"{case}: roots of the nutation cubic")
    axes[-1].set_xlabel("slow time τ = εt [s]")
    files.append(_finish(fig, folder / "roots.png"))

    fig, ax = plt.subplots(figsize=(8, 4.5))
    ax.plot(tau_f, np.degrees(full["theta"]), lw=0.4, color="tab:blue", label="θ (full model)")
    with np.errstate(invalid="ignore"):
        for key, style in (("u1", "--"), ("u2", ":")):
            ax.plot(tau_a, np.degrees(np.arccos(np.clip(avg[key], -1, 1))), ls=style, lw=1.6, color="tab:orange",
                    label=f"arccos {key} (averaged)")
    ax.set_xlabel("slow time τ = εt [s]")
    ax.set_ylabel("nutation angle θ [deg]")
    ax.set_title(f"{case}: nutation between its bounds")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8, loc="lower right")
    files.append(_finish(fig, folder / "nutation.png"))

    fig, ax = plt.subplots(figsize=(8, 4.5))
    rate = scene.epsilon * np.abs(np.polynomial.polynomial.polyval(tau_a, scene.a)) / scene.A
    rate = np.maximum(rate, scene.epsilon * np.abs(np.polynomial.polynomial.polyval(tau_a, scene.b)) / scene.C)
    ax.semilogy(tau_a, rate * avg["T_nut"], label="N = rate · T_nut (must be ≪ 1)")
    ax.semilogy(tau_a, np.maximum(1 - avg["m"], 1e-17), label="1 − k² (separatrix at 0)")
    ax.semilogy(tau_a, np.maximum(avg["m"], 1e-17), label="k² (regular precession at 0)")
    ax.axhline(SMALL, color="tab:blue", ls=":", lw=1, label=f"limit N = {SMALL}")
    ax.axhline(SEPARATRIX_LIMIT, color="tab:orange", ls=":", lw=1, label=f"limit 1 − k² = {SEPARATRIX_LIMIT}")
    ax.set_xlabel("slow time τ = εt [s]")
    ax.set_ylabel("dimensionless")
    ax.set_title(f"{case}: validity of the averaging (along the averaged solution)")
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=8, loc="lower right")
    files.append(_finish(fig, folder / "validity.png"))
    return files


def run_scene(path, out_dir, progress: bool = True) -> dict:
    """Runs a scene of kind "lagrange_top": the full top and the averaged system over
    τ = εt ∈ [0, tau_end] on the same output times, r against (3.3), the averaged model's
    validity; writes result.csv/npz (full), result_averaged.csv/npz, report.json and plots
    into out_dir/<scene name>/. Returns the report."""
    import sys

    scene = LagrangeScene.from_toml(path)
    torque = paper_torque(scene.epsilon, scene.a, scene.b)
    full_model = LagrangeTop(scene.A, scene.C, scene.mu, [torque])
    averaged_model = LagrangeAveraged(scene.A, scene.C, scene.mu, [torque])
    t_end = scene.tau_end / scene.epsilon
    t = np.linspace(0.0, t_end, scene.n_out)
    started = time.perf_counter()
    if progress:
        print(f"[{scene.name}] full model, t in [0, {t_end:.6g}]", file=sys.stderr, flush=True)
    full = solve(full_model, scene.y0, (0.0, t_end), t_eval=t, method=scene.method, rtol=scene.rtol, atol=scene.atol)
    if progress:
        print(f"[{scene.name}] averaged model", file=sys.stderr, flush=True)
    averaged = solve(averaged_model, scene.y0, (0.0, t_end), t_eval=t, method=scene.method, rtol=scene.rtol,
                     atol=scene.atol)
    elapsed = time.perf_counter() - started
    out_full = outputs(full_model, full)
    out_avg = outputs(averaged_model, averaged)
    n = min(full.t.size, averaged.t.size)
    exact_r = r_exact(scene.y0[2], scene.C, scene.epsilon, scene.b, t[:n])
    checks = check(averaged_model, averaged.y, averaged.t, warn=False)
    broken = [str(a) for a in checks if not a.holds]
    for text in broken:
        warnings.warn(f"{scene.name}: {text}", ValidityWarning, stacklevel=2)
    table0 = nutation_table(full_model, slow_variables(full_model, scene.y0))
    report = {
        "scene": scene.name,
        "title": scene.title,
        "model": "full_and_averaged",
        "model_reason": (f"paper 003: full top (omega, quaternion) next to the nutation-averaged (G_z, H, r) system; "
                         f"epsilon = {scene.epsilon:g}, a = {scene.a}, b = {scene.b}, tau in [0, {scene.tau_end:g}]"),
        "seconds": elapsed,
        "runs": {"full": _run_report(full), "averaged": _run_report(averaged)},
        "assumptions": [dict(part=a.part, statement=a.statement, value=a.value, limit=a.limit, holds=a.holds,
                             note=a.note) for a in checks],
        "broken_assumptions": broken,
        "initial_nutation": {k: float(v[0]) for k, v in table0.items()},
        "averaged_vs_full_slow": {f"max_abs_error_{k}": float(np.max(np.abs(out_full[k][:n] - out_avg[k][:n])))
                             for k in ("G_z", "H", "r", "u1", "u2", "u3", "v")},
        "r_vs_exact_3_3": {"full": float(np.max(np.abs(out_full["r"][:n] - exact_r))),
                           "averaged": float(np.max(np.abs(out_avg["r"][:n] - exact_r)))},
    }
    report["status"] = "success" if full.success and averaged.success else "failed"
    folder = Path(out_dir) / scene.name
    tau = scene.epsilon * full.t
    files = _save({"t": full.t, **{k: out_full[k] for k in out_full if k != "t"}, "tau": tau}, folder, "result")
    tau_avg = scene.epsilon * averaged.t
    files += _save({"t": averaged.t, **{k: out_avg[k] for k in out_avg if k != "t"}, "tau": tau_avg}, folder,
                   "result_averaged")
    files += _draw(scene, out_full, out_avg, exact_r, folder)
    json_path = folder / "report.json"
    report["files"] = [str(f) for f in files + [json_path]]
    json_path.write_text(json.dumps(report, indent=2, default=float) + "\n")
    return report
