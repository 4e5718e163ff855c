"""The base of the validity checks: :class:`Assumption` (a check with its number and limit),
:class:`ValidityWarning`, the limit :data:`SMALL`, the torques' own checks and :func:`check`,
which adds each model's own (``ModelBase.assumptions``, in its family module). Each check names
the assumption, its number and the limit; broken ones are warned about and returned.
:mod:`gyrostat.validity` is what users call (it adds ``check_scene``).

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
    a solution's ``y``; ``times`` for time-dependent coefficients): its torques' first, then the
    model's own (``model.assumptions``). ``outputs``: what a solve recorded at those states (the
    averaged model's ``slow_to_fast``), used as it is. Returns every check; warns for the broken
    ones when ``warn``."""
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

    results += model.assumptions(states, times, outputs)

    if warn:
        for assumption in results:
            if not assumption.holds:
                warnings.warn(str(assumption), ValidityWarning, stacklevel=2)
    return results
