"""Does a scene satisfy the assumptions of the models it uses? Each check names the assumption,
its number and the limit; broken ones are warned about (ValidityWarning) and returned.

Limits: "≪ 1" is taken as ≤ 0.1 (a first-order theory then errs by about that fraction); the
paper's own condition (4) of paper 001, Ω² ≫ λ|ω| ≫ |ω|², is reported as printed with ratios
≥ 10. Where the averaged reduction is exact (symmetric body; cavity, axial constant torque,
axisymmetric diagonal resistance, damper), the fast-frequency condition is not needed and is
reported as such.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass

import numpy as np

from gyrostat import _core

SMALL = 0.1
PAPER_RATIO = 10.0


class ValidityWarning(UserWarning):
    """A scene breaks an assumption of a model it uses."""


@dataclass(frozen=True)
class Assumption:
    part: str
    statement: str
    value: float
    limit: float
    holds: bool
    note: str = ""

    def __str__(self) -> str:
        verdict = "holds" if self.holds else "BROKEN"
        text = f"{self.part}: {self.statement}: {self.value:.3g} (limit {self.limit:.3g}) {verdict}"
        return text + (f"; {self.note}" if self.note else "")


def _omegas(model, states: np.ndarray) -> np.ndarray:
    """(n, 3) angular velocities: for an averaged model ω = (a, 0, r) stands for the motion."""
    if states.shape[1] == 2:
        return np.column_stack([states[:, 0], np.zeros(len(states)), states[:, 1]])
    return states[:, :3]


def exact_reduction(model) -> bool:
    """Whether the (a, r) reduction of a symmetric scene is exact (then r = 0 is no limit)."""
    A1, A2, _ = np.asarray(model.body.moments)
    if A1 != A2 or np.any(np.asarray(model.body.rotor)):
        return False
    for torque in model.torques:
        if isinstance(torque, _core.ConstantTorque) and np.any(np.asarray(torque.moment)[:2]):
            return False
        if isinstance(torque, (_core.LinearDamping, _core.ResistiveMedium)):
            matrices = [np.asarray(torque.matrix)] if isinstance(torque, _core.LinearDamping) else \
                [np.asarray(c) for c in torque.coefficients]
            for D in matrices:
                off = D - np.diag(np.diag(D))
                if np.any(off) or D[0, 0] != D[1, 1]:
                    return False
    return True


def check(model, states, times=None, warn: bool = True, outputs: dict | None = None) -> list[Assumption]:
    """Checks a model's assumptions over the given states (one state or an (n, dim) array, e.g.
    a solution's ``y``; ``times`` for time-dependent coefficients). ``outputs``: what a solve
    recorded at those states (the averaged model's ``slow_to_fast``), used as it is. Returns every
    check; warns for the broken ones when ``warn``."""
    states = np.atleast_2d(np.asarray(states, float))
    times = np.zeros(len(states)) if times is None else np.asarray(times, float)
    omegas = _omegas(model, states)
    J = np.asarray(model.body.moments, float)
    A, C = J[0], J[2]
    speed = float(np.max(np.linalg.norm(omegas, axis=1)))
    results: list[Assumption] = []

    for torque in model.torques:
        if isinstance(torque, _core.ViscousCavity):
            b = torque.equivalent_radius
            reynolds = speed * b * b / torque.viscosity
            results.append(Assumption("viscous cavity", "Reynolds number |ω| b²/ν ≪ 1", reynolds, SMALL,
                                      reynolds <= SMALL, f"b = {b:.4g} (sphere of the same P0)"))
            strength = torque.kappa * speed / J.min()
            results.append(Assumption("viscous cavity", "cavity rate κ|ω|/A_min ≪ 1 (perturbation small)",
                                      strength, SMALL, strength <= SMALL))
        if isinstance(torque, _core.MovingMassDamper):
            omega2 = torque.frequency**2
            nu = np.abs((C - A) * omegas[:, 2] / A)
            lag = float(np.max(torque.damping * nu / omega2))
            results.append(Assumption("moving-mass damper", "λ|ν|/Ω² ≪ 1 (quasi-static lag, ν = (C−A)r/A)", lag,
                                      SMALL, lag <= SMALL))
            G = np.linalg.norm(omegas * J, axis=1)
            inertial = float(np.max(G**2 / (A * A * omega2)))
            results.append(Assumption("moving-mass damper", "|G|²/(A²Ω²) ≪ 1 (inertial corrections)", inertial, SMALL,
                                      inertial <= SMALL))
            first = omega2 / (torque.damping * speed) if torque.damping * speed > 0 else math.inf
            second = torque.damping / speed if speed > 0 else math.inf
            results.append(Assumption("moving-mass damper", "paper 001 condition (4): Ω²/(λ|ω|) ≫ 1", first,
                                      PAPER_RATIO, first >= PAPER_RATIO, "as printed; not needed for (a, r)"))
            results.append(Assumption("moving-mass damper", "paper 001 condition (4): λ|ω|/|ω|² ≫ 1", second,
                                      PAPER_RATIO, second >= PAPER_RATIO, "as printed; not needed for (a, r)"))

    if getattr(model, "kind", "") == "moving_mass":
        # the explicit model: a point mass on a linear spring next to its attachment (C++ output
        # displacement_ratio = |u|/ρ)
        if outputs is not None and "displacement_ratio" in outputs:
            ratios = np.asarray(outputs["displacement_ratio"], float)
        else:
            index = list(model.output_names).index("displacement_ratio")
            ratios = np.array([model._core.outputs_at(float(t), y)[index] for t, y in zip(times, states)])
        worst = int(np.argmax(ratios))
        results.append(Assumption("moving mass", "displacement |u|/ρ ≪ 1 (the mass stays near its attachment)",
                                  float(ratios[worst]), SMALL, ratios[worst] <= SMALL,
                                  f"worst at t = {times[worst]:.4g}, |u| = {ratios[worst] * model.arm:.3g} on an arm "
                                  f"ρ = {model.arm:.3g}"))

    if getattr(model, "kind", "") == "averaged":
        asymmetry = abs(J[1] - J[0]) / J[0]
        results.append(Assumption("averaged model", "near symmetry |B − A|/A ≪ 1", asymmetry, SMALL,
                                  asymmetry <= SMALL))
        if asymmetry > 0:
            # The polhode of the near-symmetric body must stay far from the separatrix D = G²/2T = A
            # compared with the asymmetry; |D − A|/A = C r² |C − A| / (A (A a² + C r²)).
            a, r = states[:, 0], states[:, 1]
            distance = C * r**2 * abs(C - A) / (A * (A * a**2 + C * r**2))
            ratio = asymmetry / np.maximum(distance, 1e-300)
            worst = int(np.argmax(ratio))
            results.append(Assumption("averaged model", "asymmetry against the separatrix distance "
                                      "(|B − A|/A)/(|G²/2T − A|/A) ≪ 1", float(ratio[worst]), SMALL,
                                      ratio[worst] <= SMALL, f"worst at t = {times[worst]:.4g}"))
        if exact_reduction(model):
            results.append(Assumption("averaged model", "fast frequency ≫ slow rates", 0.0, SMALL, True,
                                      "not needed: the (a, r) reduction is exact for this symmetric scene"))
        else:
            if outputs is not None and "slow_to_fast" in outputs:
                ratios = list(outputs["slow_to_fast"])
            else:
                ratios = []
                for t, y in zip(times, states):
                    fast = model.fast_frequency(y[1])
                    ratios.append(math.inf if fast == 0 else model.slow_rate(t, y) / fast)
            worst = int(np.argmax(ratios))
            results.append(Assumption("averaged model", "slow rate / fast frequency |(C−A)r/A| ≪ 1", ratios[worst],
                                      SMALL, ratios[worst] <= SMALL,
                                      f"worst at t = {times[worst]:.4g}, r = {states[worst][1]:.3g}"))

    if warn:
        for assumption in results:
            if not assumption.holds:
                warnings.warn(str(assumption), ValidityWarning, stacklevel=2)
    return results


def check_scene(scene, warn: bool = True) -> list[Assumption]:
    """Checks a scene (a :class:`gyrostat.scene.Scene` or the path of its TOML file) at its
    initial state, for every model the scene uses, without solving it. (`gyrostat run` checks
    along the whole solution.)"""
    from gyrostat.scene import Scene

    if not isinstance(scene, Scene):
        scene = Scene.from_toml(scene)
    results: list[Assumption] = []
    for run in scene.runs:
        if run.model.kind in ("full", "averaged", "moving_mass"):
            results += check(run.model, run.model.initial_state(run.y0), warn=warn)
    return results
