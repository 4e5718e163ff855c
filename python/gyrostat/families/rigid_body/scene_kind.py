"""The rigid body family's scene kinds, registered: ``rigid_body`` (:class:`RigidBody`: the
full model, its closed form or the averaged system; its ladder: closed form (nothing perturbs a
rigid body) -> averaged (a, r) or averaged over the triaxial motion -> full (Euler's
equations)) and ``averaged`` (:class:`Averaged`: the averaged system alone)."""

from __future__ import annotations

import math

import numpy as np

from gyrostat import _core
from gyrostat import ladder as _ladder
from gyrostat.assumptions import SMALL, check
from gyrostat.families.rigid_body.analyses import analyse
from gyrostat.families.rigid_body import orbit_frame
from gyrostat.families.rigid_body.models import AveragedModel, Model, TorqueFreeModel
from gyrostat.families.rigid_body.plots import draw
from gyrostat.families.rigid_body.rungs import (averaged_rung, initial_assumptions, invariant_columns, nearly_symmetric,
                                                slow_columns, triaxial_rung)
from gyrostat.families.rigid_body.triaxial import TriaxialAveragedModel
from gyrostat.kind import (BODY, T_SPAN, Kind, Run, build, integration, integration_table, make_body, make_torques,
                           outputs_field, register, title_fields)
from gyrostat.schema import ArrayOf, Choice, Field, SceneError, Table, Vector, all_finite, finite, non_negative, nonzero_quaternion
from gyrostat.torques import TORQUE


class RigidBody(Kind):
    name = "rigid_body"
    doc = ("A rigid body or gyrostat under perturbation torques: the full model, its closed form when nothing "
           "perturbs it, or the system averaged over the symmetric Euler-Poinsot motion in (a, r).")
    plots = ("omega", "invariants", "euler_angles", "error", "xy", "slow", "phase", "nutation", "ladder", "orbit_angles",
             "precession")
    models = ("auto", "full", "closed_form", "averaged", "averaged_triaxial", "compare")
    default = True
    splits = True

    @property
    def schema(self) -> Table:
        return Table({
            **title_fields(),
            "body": Field(Table({**BODY.fields, "inertia_ratios": orbit_frame.INERTIA_RATIOS},
                                one_of=[("moments", "inertia", "inertia_ratios")]), required=True, doc="the body"),
            "torques": Field(ArrayOf(TORQUE), default=[], doc="perturbation torques; they add up"),
            "orbit": orbit_frame.ORBIT,
            "initial": Field(Table({
                "omega": Field(Vector(3), required=True, doc="angular velocity in body axes (frame = 'orbit': relative "
                                                             "to the orbit frame)", unit="rad/s", check=all_finite),
                "attitude": Field(Vector(4), doc="attitude quaternion (w, x, y, z), body to inertial (frame = 'orbit': "
                                                 "body to orbit frame); giving it integrates the attitude",
                                  check=nonzero_quaternion),
                "frame": Field(Choice("inertial", "orbit"), default="inertial",
                               doc="what omega and attitude are relative to: inertial axes, or the orbit frame of "
                                   "[orbit] (x along track, y minus the orbit normal, z nadir; omega = [0, 0, 0] "
                                   "with the default attitude: at rest in it)"),
            }), required=True, doc="the initial state"),
            "integration": integration_table(
                Field(Choice(*self.models), default="auto",
                      doc="auto: the cheapest model that meets the accuracy (the model ladder); averaged: over the "
                          "symmetric motion in (a, r); averaged_triaxial: over the triaxial motion in (|G|^2, p_b, s, "
                          "phase); compare: full and averaged side by side (the triaxial averaged model for a body far "
                          "from symmetric)"),
                t_span=T_SPAN, max_steps=True, splitting=True),
            "outputs": outputs_field(self.plots, ["omega", "invariants"],
                                reference=Field(Choice("closed_form"), doc="draw and measure against the closed form")),
        })

    def needs_attitude(self, doc: dict) -> bool:
        """The attitude is integrated only when the scene asks for it (an initial quaternion, an
        Euler-angle plot, or an orbit)."""
        return "attitude" in doc["initial"] or "euler_angles" in doc["outputs"]["plots"] or "orbit" in doc

    def choose(self, doc: dict, body, torques) -> tuple[str, str]:
        """The cheapest model that answers the scene, and the reason for the choice."""
        choice = doc["integration"]["model"]
        free = not torques and not np.any(np.asarray(body.rotor)) and "orbit" not in doc
        attitude = self.needs_attitude(doc)
        if choice == "closed_form":
            if not free:
                raise SceneError("[integration] model = 'closed_form' needs a rigid body (rotor k = 0) with no torque")
            return choice, "asked for by the scene"
        if choice != "auto":
            return choice, "asked for by the scene"
        if free:
            return "closed_form", ("no torque, no rotor: the exact flow (elliptic functions" +
                                   (", attitude included" if attitude else "") + ") needs no integration")
        reasons = [f"{len(torques)} torque(s)"] if torques else []
        if np.any(np.asarray(body.rotor)):
            reasons.append("a rotor (k != 0)")
        if "orbit" in doc:
            reasons.append("an orbit (the attitude relative to its frame)")
        elif attitude:
            reasons.append("attitude asked for")
        return "full", "full model: " + ", ".join(reasons)

    # plots an averaged model can draw: functions of its slow variables
    slow_plots = ("xy", "slow", "phase", "invariants", "ladder")

    def start(self, doc: dict, attitude: bool, model=None) -> np.ndarray:
        """The full model's initial state: ω, followed with ``attitude`` by the initial quaternion
        normalised (the identity when the scene gives none); with ``frame = "orbit"`` both given
        relative to the orbit frame of ``model`` (a :class:`Model` on an orbit) at t0."""
        initial = doc["initial"]
        if initial.get("frame") == "orbit":
            if model is None or getattr(model, "orbit", None) is None:
                raise SceneError("[initial] frame = 'orbit' needs an [orbit] table (or an orbit torque with its orbit)")
            return model.state_in_orbit_frame(initial.get("attitude", (1.0, 0.0, 0.0, 0.0)), initial["omega"],
                                              doc["integration"]["t_span"][0])
        if not attitude:
            return np.array(initial["omega"], float)
        q = _core.unit_vector(initial.get("attitude", (1.0, 0.0, 0.0, 0.0)), "[initial] attitude")
        return np.array([*initial["omega"], *q], float)

    def ladder(self, doc):
        body, torques = orbit_frame.body_of(doc, make_body), make_torques(doc)
        omega = np.asarray(doc["initial"]["omega"], float)
        attitude = self.needs_attitude(doc)
        model = build("torques", Model, body, torques, attitude, orbit_frame.make_orbit(doc))
        y0 = self.start(doc, attitude, model)
        free = not torques and not np.any(np.asarray(body.rotor)) and model.orbit is None
        closed = _ladder.Rung("closed_form", TorqueFreeModel(body, attitude) if free else None, y0,
                              "the exact torque-free flow (elliptic functions)",
                              blocked="" if free else "torques, a rotor or an orbit frame", run="closed_form")
        full = _ladder.Rung("full", model, y0,
                            "Euler's equations" + (" with the attitude" if attitude else ""),
                            compare=slow_columns)
        triaxial = triaxial_rung(doc, body, torques, omega, attitude)
        if triaxial.model is not None:  # a body far from symmetric: the top is compared in |G| and T
            full.compare = invariant_columns
        return [closed, averaged_rung(doc, body, torques, omega, self.slow_plots, attitude), triaxial, full]

    def runs(self, doc):
        body, torques = orbit_frame.body_of(doc, make_body), make_torques(doc)
        choice, reason = self.choose(doc, body, torques)
        omega = np.asarray(doc["initial"]["omega"], float)
        t_span = tuple(doc["integration"]["t_span"])
        options = integration(doc, self)
        runs = []
        attitude = self.needs_attitude(doc)
        if choice == "closed_form":
            runs.append(Run("closed_form", build("body", TorqueFreeModel, body, attitude), self.start(doc, attitude),
                            t_span, options))
        if choice in ("full", "compare"):
            model = build("torques", Model, body, torques, attitude, orbit_frame.make_orbit(doc))
            runs.append(Run("full", model, self.start(doc, attitude, model), t_span, options))
        triaxial = choice == "averaged_triaxial" or (choice == "compare" and nearly_symmetric(body) > SMALL)
        if triaxial:
            model = build("torques", TriaxialAveragedModel, body, torques)
            runs.append(Run("averaged", model, np.asarray(model._core.initial_state(omega)), t_span, options))
        elif choice in ("averaged", "compare"):
            model = build("torques", AveragedModel, body, torques)
            runs.append(Run("averaged", model, np.array([math.hypot(omega[0], omega[1]), omega[2]]), t_span, options))
        return runs, choice, reason

    def initial_assumptions(self, run, warn):
        return initial_assumptions(run, warn)

    def assumptions(self, run, solution):
        return check(run.model, solution.y, solution.t, warn=False, outputs=solution.outputs)

    def analyse(self, scene, solutions, report, derived):
        analyse(scene, solutions, report, derived)
        full = solutions.get("full")
        if full is not None and getattr(full.model, "orbit", None) is not None:
            orbit_frame.analyse(full, report)

    def draw(self, scene, solutions, derived, folder):
        full = solutions.get("full")
        on_orbit = full is not None and getattr(full.model, "orbit", None) is not None
        own = {"orbit_angles": lambda sol, title, path: orbit_frame.orbit_angles(sol, title, path),
               "precession": lambda sol, title, path: orbit_frame.precession(
                   sol, orbit_frame.precession_rate(sol)[1], title, path)} if on_orbit else None
        return draw(scene, solutions, derived, folder, own)

    def why_not_drawn(self, doc, plot):
        if plot in ("orbit_angles", "precession") and "orbit" not in doc:
            return "it needs an [orbit] table: the angles are relative to the orbit frame"
        if plot == "error" and doc["outputs"].get("reference") is None:
            return ("it needs a reference: [outputs] reference = \"closed_form\" (a rigid body with neither torques "
                    "nor a rotor)")
        return ""


class Averaged(RigidBody):
    name = "averaged"
    doc = ("The system averaged over the symmetric Euler-Poinsot motion in the slow variables (a, r) alone "
           "(a rigid_body scene with model = 'averaged'; the initial state may be given as a and r).")
    plots = ("xy", "slow", "phase")
    default = False
    splits = False

    @property
    def schema(self) -> Table:
        return Table({
            **title_fields(),
            "body": Field(BODY, required=True, doc="the (nearly) symmetric body A1 ~ A2, no rotor"),
            "torques": Field(ArrayOf(TORQUE), default=[], doc="perturbation torques; their averages add up"),
            "initial": Field(Table({
                "omega": Field(Vector(3), doc="angular velocity in body axes (gives a = |(p, q)|, r)", unit="rad/s",
                               check=all_finite),
                "a": Field(float, doc="equatorial amplitude a = sqrt(p^2 + q^2)", unit="rad/s", check=non_negative),
                "r": Field(float, doc="axial rate r (signed)", unit="rad/s", check=finite),
            }), required=True, doc="the initial state: omega, or a and r"),
            "integration": integration_table(t_span=T_SPAN),
            "outputs": outputs_field(self.plots, ["xy", "slow"]),
        })

    def runs(self, doc):
        body, torques = make_body(doc), make_torques(doc)
        initial = doc["initial"]
        if "omega" in initial and ("a" in initial or "r" in initial):
            raise SceneError("[initial] give omega, or a and r, not both")
        if "omega" in initial:
            omega = initial["omega"]
            y0 = np.array([math.hypot(omega[0], omega[1]), omega[2]])
        elif "a" in initial and "r" in initial:
            y0 = np.array([initial["a"], initial["r"]])
        else:
            raise SceneError("[initial] needs omega, or both a and r")
        model = build("torques", AveragedModel, body, torques)
        return ([Run("averaged", model, y0, tuple(doc["integration"]["t_span"]), integration(doc, self))], "averaged",
                "asked for by the scene kind")


register(RigidBody(), Averaged())

