"""Outputs derived from the averaged system: the papers' x, y variables, paper 002's
Lotka–Volterra coefficients and first integral, and the slow variables of a full solution."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from gyrostat import _core
from gyrostat.events import Event
from gyrostat.solution import Solution
from gyrostat.validity import SMALL


def slow_variables(solution: Solution) -> tuple[np.ndarray, np.ndarray]:
    """(a, r) of a solution: the state of the averaged model; a = √(p² + q²) and r of a full one."""
    if solution.state_names[:2] == ("a", "r"):
        return solution["a"], solution["r"]
    return np.hypot(solution["p"], solution["q"]), solution["r"]


def r_zero(direction: int = 0, terminal: bool | int = False) -> Event:
    """The event r = 0 (the axial rate changes sign) of the full or the averaged model: there the
    averaging over the symmetric motion stops being valid (the fast frequency vanishes)."""
    return Event("r", 0.0, direction, terminal, "r = 0")


def averaging_fails(limit: float = SMALL, terminal: bool | int = False) -> Event:
    """The event where the averaged model's slow rate reaches ``limit`` times its fast frequency
    (the output ``slow_to_fast`` rising through ``limit``): past it the averaging is not valid."""
    return Event("slow_to_fast", float(limit), 1, terminal, f"slow/fast reaches {limit:g}")


def xy(solution: Solution) -> tuple[np.ndarray, np.ndarray]:
    """Papers 000/001: x = a², y = r² (paper 002 swaps the names: its x is r², its y is a²)."""
    a, r = slow_variables(solution)
    return a**2, r**2


@dataclass(frozen=True)
class LotkaVolterra:
    """Paper 002, eq. (6): with X = r², Y = a² (the paper's x, y) and no constant torque,
    dX/dt = X (λ1 + μ1 Y), dY/dt = Y (λ2 + μ2 X), where

        λ1 = −2 D33 / C,  λ2 = −(D11 + D22) / A,  μ1 = 2κ (C − A)/(A C),  μ2 = 2κ C (A − C)/A³,

    D the summed linear-resistance matrix (ε included), κ = ρ P0 / ν summed over cavities.
    A² μ2 + C² μ1 = 0 (the cavity keeps |G|)."""

    lambda1: float
    lambda2: float
    mu1: float
    mu2: float

    def first_integral(self, X, Y):
        """Paper 002 eq. (7) in logarithmic form (the exponential form overflows on the paper's
        own scene): Φ = λ2 ln X + μ2 X − λ1 ln Y − μ1 Y, constant along the averaged solution."""
        X, Y = np.asarray(X, float), np.asarray(Y, float)
        return self.lambda2 * np.log(X) + self.mu2 * X - self.lambda1 * np.log(Y) - self.mu1 * Y


def lotka_volterra(model) -> LotkaVolterra:
    """The coefficients of paper 002's system (6) from a model's physical parameters."""
    A, C = float(model.body.moments[0]), float(model.body.moments[2])
    D = np.zeros((3, 3))
    kappa = 0.0
    for torque in model.torques:
        if isinstance(torque, _core.LinearDamping):
            D += np.asarray(torque.matrix)
        elif isinstance(torque, _core.ResistiveMedium):
            D += np.asarray(torque.at(0.0))
        elif isinstance(torque, _core.ViscousCavity):
            kappa += torque.kappa
        elif isinstance(torque, _core.ConstantTorque):
            if np.asarray(torque.moment)[2] != 0.0:
                raise ValueError("paper 002's Lotka-Volterra form has no constant axial torque (M3 = "
                                 f"{np.asarray(torque.moment)[2]!r})")
        else:
            raise ValueError(f"paper 002's Lotka-Volterra form has no term for {type(torque).__name__}")
    return LotkaVolterra(
        lambda1=-2.0 * D[2, 2] / C,
        lambda2=-(D[0, 0] + D[1, 1]) / A,
        mu1=2.0 * kappa * (C - A) / (A * C),
        mu2=2.0 * kappa * C * (A - C) / A**3,
    )
