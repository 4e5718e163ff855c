"""The rigid body family's ladder rungs and what they compare: the averaged (a, r) rung and the
triaxial averaged rung (which the moving-mass family's ladder takes too), the columns the
ladder compares, and the assumptions of a run's model at its initial state."""

from __future__ import annotations

import math

import numpy as np

from gyrostat import ladder as _ladder
from gyrostat.assumptions import SMALL, check
from gyrostat.families.rigid_body.analyses import carried_omega
from gyrostat.families.rigid_body.averaged_outputs import slow_variables
from gyrostat.families.rigid_body.models import AveragedModel
from gyrostat.families.rigid_body.triaxial import TriaxialAveragedModel
from gyrostat.kind import Run


def slow_columns(solution) -> np.ndarray:
    """(a, r) of a rigid-body solution, full or averaged: (n, 2) (what the ladder compares)."""
    return np.column_stack(slow_variables(solution))


def initial_assumptions(run: Run, warn: bool) -> list:
    """The assumptions of a run's model at its initial state (the full, averaged and moving-mass
    models: their torques' and their own)."""
    if run.model.kind in ("full", "averaged", "moving_mass"):
        return check(run.model, run.model.initial_state(run.y0), warn=warn)
    return []



def averaged_rung(doc: dict, body, torques, omega, drawable: tuple[str, ...], attitude: bool = False) -> _ladder.Rung:
    """The averaged (a, r) rung of the ladder of a rigid body or, with the damper's quasi-static
    torque among ``torques``, of the moving-mass family. Blocked when the scene's outputs need
    ω(t) (plots not in ``drawable``, the attitude, a closed-form reference) or when the torques
    have no average (the model's own message)."""
    y0 = np.array([math.hypot(omega[0], omega[1]), omega[2]])
    description = "the system averaged over the symmetric Euler-Poinsot motion, in (a, r)"
    needs = [p for p in doc["outputs"]["plots"] if p not in drawable]
    blocked = ("the scene integrates the attitude: the averaged model has none" if attitude else
               f"the plots {needs} need omega(t): the averaged model gives a and r only" if needs else
               "the closed-form reference is of omega(t)" if doc["outputs"].get("reference") else "")
    model = None
    if not blocked:
        try:
            model = AveragedModel(body, torques)
        except ValueError as error:
            blocked = f"no averaged model: {error}"
    if blocked:
        return _ladder.Rung("averaged", None, y0, description, blocked=blocked, run="averaged")
    exact = model.exact_reduction
    fast = model.fast_frequency(y0[1])
    span = doc["integration"]["t_span"]
    # an exact reduction has no fast motion to resolve: its probe is the longest one, a twentieth of the span
    # an exact reduction has no fast oscillation to sample: its probe may be shorter than 20 periods
    share = _ladder.PROBE_FRACTION * abs(span[1] - span[0]) / _ladder.PROBE_PERIODS
    period = 2.0 * math.pi / fast if fast > 0 else math.inf
    period = min(period, share) if exact else period
    watches = () if exact else (_ladder.Watch("slow_to_fast", SMALL, 0.5 * SMALL,
                                              "slow rate / fast frequency << 1", scales_error=True),)
    return _ladder.Rung("averaged", model, y0, description, compare=slow_columns, fast_period=period,
                        watches=watches, exact=exact,
                        start_checks=lambda: [a for a in check(model, y0, warn=False)
                                              if a.part == "averaged model"],
                        basis="the (a, r) reduction is exact for this symmetric scene: r = 0 is not a limit" if exact
                        else "", run="averaged")


def invariant_columns(solution) -> np.ndarray:
    """(|G|, T) of a rigid-body solution of any model that records them (the full model, the
    averaged ones, a run joined from both), each over its value at the start: (n, 2) (what the
    ladder compares for the triaxial averaged rung)."""
    G, T = solution["angular_momentum_norm"], solution["kinetic_energy"]
    return np.column_stack([G / G[0], T / T[0]])


def nearly_symmetric(body) -> float:
    """|A2 − A1|/A1 of the principal moments: the asymmetry the (a, r) rung assumes small."""
    J = np.asarray(body.moments, float)
    return abs(J[1] - J[0]) / J[0]


TRIAXIAL_PLOTS = ("invariants", "nutation", "ladder")
"""Plots the triaxial averaged rung draws: functions of its slow variables and of ω at its phase."""


def triaxial_rung(doc: dict, body, torques, omega, attitude: bool = False) -> _ladder.Rung:
    """The triaxial averaged rung (|G|², p_b, s, φ) of a rigid body's or, with the damper's
    quasi-static torque among ``torques``, of the moving-mass family's ladder. Blocked for a
    nearly symmetric body (the (a, r) rung averages it), when the scene's outputs need ω(t)
    exactly (plots not in :data:`TRIAXIAL_PLOTS`, the attitude, a closed-form reference) and when
    the torques have no average (the model's own message). It compares |G| and T with the top and
    watches ``slow_to_fast``: the run switches to the top before the separatrix and back after."""
    description = "the system averaged over the triaxial Euler-Poinsot motion, in (|G|^2, p_b, s, phase)"
    needs = [p for p in doc["outputs"]["plots"] if p not in TRIAXIAL_PLOTS]
    asymmetry = nearly_symmetric(body)
    blocked = (f"a nearly symmetric body (|A2 - A1|/A1 = {asymmetry:.3g} <= {SMALL:g}): the (a, r) rung averages it"
               if asymmetry <= SMALL else
               "the scene integrates the attitude: the averaged model has none" if attitude else
               "the closed-form reference is of omega(t)" if doc["outputs"].get("reference") else "")
    # the plots need omega(t): the rung is built and probed all the same, so that the report can say
    # by how much omega at the carried phase would miss the accuracy (ladder.choose)
    omega_needed = (f"the plots {needs} need omega(t): the averaged model carries its phase only to O(1) at "
                    "t ~ 1/eps") if needs and not blocked else ""
    model, y0 = None, np.asarray(omega, float)
    if not blocked:
        try:
            model = TriaxialAveragedModel(body, torques)
            y0 = np.asarray(model._core.initial_state(np.asarray(omega, float)))
            model._core.outputs_at(0.0, y0)
            model._core.full_state(y0, 0.0)  # refuses a start on the separatrix, naming it
        except ValueError as error:
            blocked, model = f"no triaxial averaged model: {error}", None
    if blocked:
        return _ladder.Rung("averaged_triaxial", None, y0, description, blocked=blocked, run="averaged")
    names = list(model.output_names)
    period = float(model._core.outputs_at(doc["integration"]["t_span"][0], y0)[names.index("period")])
    watches = (_ladder.Watch("slow_to_fast", SMALL, 0.5 * SMALL,
                             "slow rates / fast frequency << 1 (far from the separatrix)", scales_error=True),)
    return _ladder.Rung("averaged_triaxial", model, y0, description, compare=invariant_columns, fast_period=period,
                        watches=watches, fast_compare=lambda solution: carried_omega(model, solution),
                        start_checks=lambda: [a for a in check(model, y0, warn=False) if a.part == "averaged model"],
                        run="averaged", blocked=omega_needed, probe_when_blocked=bool(omega_needed))

