"""The moving-mass family (paper 001): a carrier and a point mass on a damped spring.

A family module provides its models (``ModelBase`` subclasses with their own assumptions), its
paper helpers and analysis, its plots (drawn with :mod:`gyrostat.figures`), its scene kind(s)
(:class:`gyrostat.kind.Kind`: schema and defaults, runs, ladder rungs, checks, analysis, plots)
and one ``register(...)`` line; see :mod:`gyrostat.families.rigid_body` for the full recipe.

Here: :class:`MovingMassModel` (the explicit model, 9 states; its displacement |u|/ρ ≪ 1
checked), the plot ``mass`` and the kind ``moving_mass``, whose ladder is: averaged (a, r) with
the damper's quasi-static torque -> reduced (the rigid body with the quasi-static damper torque,
Chernousko) -> explicit (carrier, point mass, spring and damper). Its rigid-body plots and the
averaged rung are the rigid body family's.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from pathlib import Path

import numpy as np

from gyrostat import _core
from gyrostat import ladder as _ladder
from gyrostat.assumptions import SMALL, Assumption, check
from gyrostat.families.rigid_body import (Model, averaged_rung, draw, initial_assumptions, invariant_columns, slow_columns,
                                          triaxial_rung)
from gyrostat.figures import curves, unit_label
from gyrostat.kind import (BODY, T_SPAN, Kind, Run, build, integration, integration_table, make_body, make_torques,
                           outputs_field, register, title_fields)
from gyrostat.modelbase import ModelBase, check_body, check_torques, floats
from gyrostat.schema import ArrayOf, Choice, Field, SceneError, Table, Vector, all_finite
from gyrostat.solution import Solution
from gyrostat.torques import BY_KIND, TORQUE, schema


class MovingMassModel(ModelBase):
    """The explicit model behind the damper reduction: a carrier plus a point mass on a spring
    (Ω² = c/μ) with a viscous damper (λ = δ/μ), attached on the z axis at distance ρ.

    State (9): ω (rad/s), the mass's displacement u (m) and its velocity v (m/s) relative to the
    carrier (body axes). ``body`` holds the whole system's moments with the mass at rest; the
    carrier's own are (A1 − μρ², A2 − μρ², A3). Extra torques act on the carrier. Stiff for a
    strong damper: solve it with ``method="cvode_bdf"``. :meth:`quasi_static_state` gives (u, v)
    for a start without free oscillation of the mass. Outputs: |K| (conserved) and the energy E
    (dissipated). :meth:`check` measures the mass's displacement |u|/ρ ≪ 1 and the damper
    torque's assumptions, for the reduction it stands behind.

    Parameters
    ----------
    body : gyrostat.Body
        The system's moments with the mass at rest, in kg m^2.
    mass : float
        The mass μ, in kg.
    arm : float
        Its distance ρ from the centre of mass on the z axis, in m.
    frequency : float
        The spring's frequency Ω = sqrt(c/μ), in rad/s.
    damping : float
        λ = δ/μ, in 1/s.
    torques : sequence of torques, optional
        External torques on the carrier.

    Examples
    --------
    >>> import gyrostat
    >>> model = gyrostat.MovingMassModel(gyrostat.Body([1.5, 1.5, 1.0]), mass=0.01, arm=1.0, frequency=30.0,
    ...                                  damping=10.0)
    >>> model.dim
    9

    The examples of its methods use this ``model``.
    """

    kind = "moving_mass"

    def __init__(self, body: _core.Body, mass: float, arm: float, frequency: float, damping: float,
                 torques: Sequence = ()):
        self.body = check_body(body)
        self.torques = check_torques(torques)
        self._core = _core.moving_mass_model(body, mass, arm, frequency, damping, self.torques)  # checks the numbers
        self.mass, self.arm, self.frequency, self.damping = float(mass), float(arm), float(frequency), float(damping)

    _numbers = ("mass", "arm", "frequency", "damping")  # its own parameters (gyrostat.sensitivity)

    def _arguments(self) -> dict:
        """What it was built from, as its constructor takes it (gyrostat.sensitivity rebuilds from it)."""
        return {"body": self.body, "mass": self.mass, "arm": self.arm, "frequency": self.frequency,
                "damping": self.damping, "torques": self.torques}

    def damper(self) -> _core.MovingMassDamper:
        """The reduced (quasi-static) torque of the same mass, spring and damper.

        Examples
        --------
        >>> model.damper()
        MovingMassDamper(mass=0.01, arm=1, frequency=30, damping=10)
        """
        return _core.MovingMassDamper(self.mass, self.arm, self.frequency, self.damping)

    def quasi_static_state(self, omega) -> np.ndarray:
        """The full state (ω, u, v) with the mass at its quasi-static displacement for this ω: a
        start without free oscillation of the mass.

        Parameters
        ----------
        omega : array_like, shape (3,)
            Angular velocity in body axes, in rad/s.

        Examples
        --------
        >>> model.quasi_static_state([0.1, 0.0, 1.0]).shape
        (9,)
        """
        return np.asarray(self._core.quasi_static_state(floats(omega, "omega")))

    def check(self, solution) -> list:
        return check(self, solution.y, solution.t, warn=False, outputs=solution.outputs)

    def assumptions(self, states, times, outputs=None) -> list:
        """A point mass on a linear spring next to its attachment (C++ output displacement_ratio
        = |u|/ρ).

        Parameters
        ----------
        states, times, outputs
            As in :meth:`gyrostat.ModelBase.assumptions`: (n, 9) states, their times in s, what a
            solve recorded at them.

        Examples
        --------
        >>> state = model.quasi_static_state([0.1, 0.0, 1.0])
        >>> bool(model.assumptions(state[None, :], [0.0])[0].holds)
        True
        """
        results = []
        # the explicit model: a point mass on a linear spring next to its attachment (C++ output
        # displacement_ratio = |u|/ρ)
        if outputs is not None and "displacement_ratio" in outputs:
            ratios = np.asarray(outputs["displacement_ratio"], float)
        else:
            index = list(self.output_names).index("displacement_ratio")
            ratios = np.array([self._core.outputs_at(float(t), y)[index] for t, y in zip(times, states)])
        worst = int(np.argmax(ratios))
        results.append(Assumption("moving mass", "displacement |u|/ρ ≪ 1 (the mass stays near its attachment)",
                                  float(ratios[worst]), SMALL, ratios[worst] <= SMALL,
                                  f"worst at t = {times[worst]:.4g}, |u| = {ratios[worst] * self.arm:.3g} on an arm "
                                  f"ρ = {self.arm:.3g}"))
        return results
    def __repr__(self) -> str:
        return (f"MovingMassModel({self.body!r}, mass={self.mass}, arm={self.arm}, frequency={self.frequency}, "
                f"damping={self.damping}, torques={list(self.torques)!r})")


def mass(solution: Solution, title: str, path: Path) -> Path:
    """The moving mass's displacement u relative to the carrier (the explicit damper model)."""
    return curves(solution.t, {name: solution[name] for name in ("u_1", "u_2", "u_3")},
                   unit_label(solution, "u_1", "displacement of the mass in body axes"), f"{title}: moving mass", path)


class MovingMass(Kind):
    name = "moving_mass"
    doc = ("The explicit moving-mass model (paper 001): a carrier and a point mass on a damped spring, "
           "9 states, stiff for a strong damper (method auto by default: CVODE BDF where it is stiff).")
    plots = ("omega", "invariants", "mass", "ladder")

    @property
    def schema(self) -> Table:
        damper_table = schema(BY_KIND["moving_mass_damper"])
        return Table({
            **title_fields(),
            "body": Field(BODY, required=True, doc="the system's moments with the mass at rest"),
            "damper": Field(damper_table, required=True, doc="the mass, its arm, spring and damper"),
            "torques": Field(ArrayOf(TORQUE), default=[], doc="external torques on the carrier"),
            "initial": Field(Table({
                "omega": Field(Vector(3), required=True, doc="angular velocity", unit="rad/s", check=all_finite),
                "start": Field(Choice("quasi_static", "at_rest"), default="quasi_static",
                               doc="quasi_static: the mass on its forced motion; at_rest: u = v = 0"),
            }), required=True, doc="the initial state"),
            "integration": integration_table(
                Field(Choice("auto", "explicit", "reduced", "averaged", "averaged_triaxial"), default="auto",
                      doc="auto: the cheapest model that meets the accuracy; averaged: (a, r); averaged_triaxial: "
                          "(|G|^2, p_b, s, phase) for a body far from symmetric; reduced: the quasi-static damper "
                          "torque; explicit: the mass, spring and damper"),
                t_span=T_SPAN),
            "outputs": outputs_field(self.plots, ["omega", "invariants", "mass"]),
        })

    def ladder(self, doc):
        body, torques = make_body(doc), make_torques(doc)
        d = doc["damper"]
        damper = build("damper", _core.MovingMassDamper, d["mass"], d["arm"], d["frequency"], d["damping"])
        model = build("damper", MovingMassModel, body, d["mass"], d["arm"], d["frequency"], d["damping"], torques)
        omega = np.asarray(doc["initial"]["omega"], float)
        y0 = model.quasi_static_state(omega) if doc["initial"]["start"] == "quasi_static" else \
            np.concatenate([omega, np.zeros(6)])
        plots = doc["outputs"]["plots"]
        triaxial = triaxial_rung(doc, body, [damper, *torques], omega)
        # a body far from symmetric: compared in |G| and T (the triaxial rung's slow variables)
        compare = _ladder.rates if "omega" in plots else invariant_columns if triaxial.model is not None else slow_columns
        # switched up from a lower rung (which assumes the mass follows quasi-statically): the mass
        # starts at its quasi-static displacement for the lifted ω
        explicit = _ladder.Rung("explicit", model, y0, "the carrier, the point mass, its spring and damper (9 states)",
                                compare=compare, complete=model.quasi_static_state)
        reduced_model = build("damper", Model, body, [damper, *torques])
        checks = [a for a in check(reduced_model, omega, warn=False)
                  if a.part == "moving-mass damper" and "condition (4)" not in a.statement]
        principal = reduced_model._core.principal_states(omega[np.newaxis, :])  # ω in principal axes
        fast = _core.Motion(body.moments, principal).axial_frequency  # |(C − A) r / A|, from C++
        reduced = _ladder.Rung(
            "reduced", reduced_model, omega, "the rigid body under the damper's quasi-static torque (Chernousko)",
            compare=compare, fast_period=2.0 * math.pi / fast if fast > 0 else math.inf,
            phase_compared=compare is _ladder.rates,
            blocked="the plot 'mass' needs the mass's own motion" if "mass" in plots else "",
            start_checks=lambda: checks, small=max(a.value for a in checks),
            basis="; ".join(f"{a.statement} = {a.value:.3g}" for a in checks))
        averaged = averaged_rung(doc, body, [damper, *torques], omega, ("invariants", "ladder"))
        return [averaged, triaxial, reduced, explicit]

    def runs(self, doc):
        choice = doc["integration"]["model"]
        rungs = {rung.name: rung for rung in self.ladder(doc)}
        rung = rungs["explicit" if choice == "auto" else choice]
        if rung.blocked:
            raise SceneError(f"[integration] model = {choice!r}: {rung.blocked}")
        reason = {"explicit": "the explicit mass, spring and damper", "reduced": "the quasi-static damper torque",
                  "averaged": "the averaged (a, r) system with the damper's torque",
                  "averaged_triaxial": "the system averaged over the triaxial motion with the damper's torque"}[rung.name]
        return ([Run(rung.run, rung.model, rung.y0, tuple(doc["integration"]["t_span"]), integration(doc, self))],
                rung.name,
                f"asked for by the scene: {reason}" if choice != "auto" else "the scene's own model (the ladder "
                "chooses when it is solved)")

    def initial_assumptions(self, run, warn):
        return initial_assumptions(run, warn)

    def assumptions(self, run, solution):
        return check(run.model, solution.y, solution.t, warn=False, outputs=solution.outputs)

    def draw(self, scene, solutions, derived, folder):
        return draw(scene, solutions, derived, folder, own={"mass": mass})


register(MovingMass())
