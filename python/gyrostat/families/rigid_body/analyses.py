"""The rigid body family's analysis of a scene's runs (from recorded outputs only): paper
002's averaged against the full model, the error against the closed form, the first time the
nutation reaches 90° and the triaxial averaged run's separatrix crossings (:func:`analyse`)."""

from __future__ import annotations

import math

import numpy as np

from gyrostat.families.rigid_body.averaged_outputs import slow_variables
from gyrostat.families.rigid_body.models import torque_free
from gyrostat.solution import Solution


def first_reaching(solution: Solution, name: str, level: float) -> float | None:
    """The first time the output ``name`` reaches ``level`` from below (linear interpolation
    between output times), or None."""
    values = np.asarray(solution[name], float)
    above = np.nonzero(values >= level)[0]
    if not len(above) or above[0] == 0:
        return None
    i = int(above[0])
    t0, t1, v0, v1 = solution.t[i - 1], solution.t[i], values[i - 1], values[i]
    return float(t0 + (level - v0) * (t1 - t0) / (v1 - v0))


def separatrix_crossings(solution: Solution) -> list[float]:
    """The times at which a triaxial averaged run (joined with its full-model pieces) crossed the
    separatrix: where p_b changes sign between output times."""
    pb = np.asarray(solution["pb"], float)
    changes = np.nonzero(np.sign(pb[1:]) != np.sign(pb[:-1]))[0]
    return [float(solution.t[i] - pb[i] * (solution.t[i + 1] - solution.t[i]) / (pb[i + 1] - pb[i])) for i in changes]


def analyse(scene, solutions: dict, report: dict, derived: dict) -> None:
    """Paper 002's averaged against the full model, the error against the closed form, and where
    the runs record a nutation angle the first time it reaches 90° (a spin about the axis of least
    inertia turned flat) and the triaxial averaged run's separatrix crossings."""
    flat = {name: first_reaching(sol, "nutation_angle", 0.5 * math.pi) for name, sol in solutions.items()
            if "nutation_angle" in sol.output_names and len(sol)}
    if any(t is not None for t in flat.values()):
        report["nutation_90_degrees_at"] = flat
        if flat.get("full") and flat.get("averaged"):
            report["nutation_90_degrees_relative_difference"] = abs(flat["averaged"] - flat["full"]) / flat["full"]
    averaged = solutions.get("averaged")
    if averaged is not None and "pb" in averaged.state_names and len(averaged):
        report["separatrix_crossings"] = separatrix_crossings(averaged)
    if "full" in solutions and "averaged" in solutions and "pb" in solutions["averaged"].state_names:
        full, avg = solutions["full"], solutions["averaged"]
        n = min(len(full), len(avg))
        report["averaged_vs_full"] = {
            f"max_relative_error_{name}": float(np.max(np.abs(avg[name][:n] - full[name][:n]) / np.abs(full[name][:n])))
            for name in ("angular_momentum_norm", "kinetic_energy")}
        averaged_run = next(run for run in scene.runs if run.name == "averaged")
        report["averaged_vs_full"]["max_relative_error_omega"] = omega_error(averaged_run.model, full, avg, n)
    elif "full" in solutions and "averaged" in solutions:
        a_full, r_full = slow_variables(solutions["full"])
        a_avg, r_avg = slow_variables(solutions["averaged"])
        n = min(len(a_full), len(a_avg))
        report["averaged_vs_full"] = {"max_abs_error_a": float(np.max(np.abs(a_full[:n] - a_avg[:n]))),
                                      "max_abs_error_r": float(np.max(np.abs(r_full[:n] - r_avg[:n])))}
    main = solutions.get("full", solutions.get("closed_form"))
    if scene.doc["outputs"].get("reference") == "closed_form" and main is not None and len(main):
        reference = torque_free(scene.runs[0].model.body, scene.doc["initial"]["omega"], main.t)
        derived["reference"] = reference
        report["max_error_vs_closed_form"] = float(np.max(np.linalg.norm(main.omega - reference.omega, axis=1)))


def carried_omega(model, averaged: Solution) -> np.ndarray:
    """(n, 3) ω of the free motion at the phase a triaxial averaged run carries, in the body's
    given frame (its outputs p, q, r are in principal axes; NaN at rest and on the separatrix)."""
    carried = np.column_stack([averaged["p"], averaged["q"], averaged["r"]])
    return carried @ np.asarray(model.body.principal_axes).T


def omega_error(model, full: Solution, averaged: Solution, n: int) -> float:
    """The largest |ω_averaged − ω_full| / |ω_full| over the first n outputs: ω at the phase the
    triaxial averaged run carries (:func:`carried_omega`) against the full model's. The phase's
    error is the integral of the O(ε) error of the frequency: this grows to O(1) by t ~ 1/ε where
    the slow variables' stays O(ε)."""
    carried = carried_omega(model, averaged)[:n]
    exact = np.asarray(full.omega[:n], float)
    finite = np.all(np.isfinite(carried), axis=1)  # undefined at rest and on the separatrix
    if not finite.any():
        return math.nan
    apart = np.linalg.norm(carried[finite] - exact[finite], axis=1) / np.linalg.norm(exact[finite], axis=1)
    return float(np.max(apart))

