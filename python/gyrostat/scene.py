"""Scenes: a body, its torques, an initial state, a horizon, an integrator and outputs, as TOML.

One pipeline for every model family: the top-level key ``kind`` picks a scene kind from
:data:`KINDS` (``rigid_body`` when absent), each kind declares its strict schema
(:mod:`gyrostat.schema`: an unknown or misspelled key, a wrong type or a missing key is a
one-line error naming the key, its table and the nearest valid key) and turns the validated
document into runs (a model, an initial state, a span, integrator options). :mod:`gyrostat.runner`
solves the runs with :func:`gyrostat.solve`, writes the results and the report, and draws the
kind's plots. ``python -m gyrostat scene-format`` prints the reference of every kind.

A rigid-body scene looks like::

    title = "Damped body under a constant torque"
    [body]
    moments = [1.0, 2.0, 3.0]        # principal moments A1, A2, A3 [kg m^2]
    rotor = [0.0, 0.0, 0.0]          # gyrostatic momentum k [kg m^2/s], optional
    [[torques]]
    type = "constant"                # M = (M1, M2, M3) [N m]
    moment = [0.0, 0.0, 0.05]
    [[torques]]
    type = "linear_damping"          # M = -D omega
    matrix = [[0.02, 0, 0], [0, 0.02, 0], [0, 0, 0.01]]
    [initial]
    omega = [1.0, 0.5, -0.3]         # [rad/s]
    attitude = [1.0, 0.0, 0.0, 0.0]  # optional quaternion (w, x, y, z): integrates the attitude
    [integration]
    model = "auto"                   # auto | full | closed_form | averaged | compare
    method = "dop853"
    rtol = 1e-10
    atol = 1e-12
    t_span = [0.0, 100.0]            # [s]
    n_out = 2001
    [outputs]
    plots = ["omega", "invariants", "euler_angles"]
    reference = "closed_form"        # optional: draw and measure against the closed form
"""

from __future__ import annotations

import math
import tomllib
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from gyrostat import _core, lagrange, orthogonal, validity
from gyrostat import ladder as _ladder
from gyrostat.model import AveragedModel, Model, ModelBase, MovingMassModel, TorqueFreeModel
from gyrostat.schema import (ArrayOf, Choice, Field, ListOf, Matrix, OneOf, SceneError, Table, Variants, Vector,
                             at_least, describe, increasing, non_negative, positive, validate)
from gyrostat.solve import check_run

__all__ = ["Scene", "Run", "SceneError", "KINDS", "SCENES", "load", "scene_format"]


# ------------------------------------------------------------------------------------ pieces
def _finite(value, _=None):
    if not math.isfinite(value):
        raise ValueError("must be finite")


def _all_finite(values):
    if not np.all(np.isfinite(np.asarray(values, float))):
        raise ValueError("must be finite numbers")


def _span_order(values):
    if not (math.isfinite(values[0]) and math.isfinite(values[1])):
        raise ValueError("must be two finite times")


def _nonzero_quaternion(values):
    q = np.asarray(values, float)
    if not np.all(np.isfinite(q)) or not np.any(q):
        raise ValueError("must be a finite, non-zero quaternion (w, x, y, z)")


TITLE = {
    "kind": Field(str, default="rigid_body", doc="scene kind: " + ", ".join(
        ("rigid_body", "averaged", "moving_mass", "lagrange_top", "orthogonal_torque"))),
    "title": Field(str, default="", doc="a title for plots and reports"),
    "description": Field(str, default="", doc="what the scene shows"),
}


def _splitting_order(value):
    if value not in (2, 4, 6):
        raise ValueError("must be 2, 4 or 6")


def _direction(value):
    if value not in (-1, 0, 1):
        raise ValueError("must be -1, 0 or 1")


EVENT = Table({
    "quantity": Field(str, required=True, doc="a state component or a named output of the run's model"),
    "value": Field(float, default=0.0, doc="the value it crosses", check=_finite),
    "direction": Field(int, default=0, doc="+1 upward crossings only, -1 downward, 0 both", check=_direction),
    "terminal": Field(int, default=0, doc="0: record; n: stop the run at the n-th crossing", check=non_negative),
    "name": Field(str, default="", doc="a name for the report"),
}, doc="an event: where a quantity crosses a value, located by the engine")
TITLE["events"] = Field(ArrayOf(EVENT), default=[], doc="events to locate in every run that has the quantity")

SWEEP_PARAMETER = Table({
    "path": Field(str, doc="the entry of this scene it sets: body.moments[0], torques[1].viscosity, initial.omega[2], "
                           "integration.rtol; a slice body.moments[0:2] sets several entries"),
    "paths": Field(ListOf(str, min_len=1), doc="several entries set to the same value"),
    "name": Field(str, doc="the coordinate's name in sweep.nc (default: the path)"),
    "label": Field(str, default="", doc="text for plots, e.g. A/C"),
    "scale": Field(float, default=1.0, doc="each entry is set to scale * value", check=_finite),
    "values": Field(ListOf(float, min_len=1), doc="a grid: these values"),
    "start": Field(float, doc="a grid from start to stop (with num)", check=_finite),
    "stop": Field(float, doc="the grid's last value", check=_finite),
    "num": Field(int, doc="the grid's number of values", check=at_least(1)),
    "spacing": Field(Choice("linear", "log"), default="linear", doc="the grid's spacing"),
    "distribution": Field(Choice("uniform", "normal", "loguniform"), doc="a dispersion: uniform and loguniform take "
                                                                         "low and high, normal takes mean and std"),
    "low": Field(float, doc="lower bound", check=_finite),
    "high": Field(float, doc="upper bound", check=_finite),
    "mean": Field(float, doc="mean", check=_finite),
    "std": Field(float, doc="standard deviation", check=_finite),
}, one_of=[("path", "paths")], doc="a varied parameter: a grid (values, or start, stop, num) or a distribution")
SWEEP_LINE = Table({"label": Field(str, required=True, doc="legend text"),
                    "x": Field(ListOf(float, min_len=2), required=True, doc="first parameter's values"),
                    "y": Field(ListOf(float, min_len=2), required=True, doc="the summary (one parameter) or the second "
                                                                            "parameter's values")},
                   doc="a reference line drawn over the sweep's plot")
TITLE["sweep"] = Field(Table({
    "vary": Field(ArrayOf(SWEEP_PARAMETER), required=True, doc="the varied parameters"),
    "run": Field(str, doc="the run of the scene to sweep (default: its only run, or full)"),
    "samples": Field(int, doc="members of a dispersion", check=at_least(1)),
    "seed": Field(int, doc="seed of a dispersion (default: a fresh one, recorded in sweep.nc)", check=non_negative),
    "trajectories": Field(bool, default=False, doc="keep every member's trajectory in sweep.nc"),
    "summary": Field(str, default="", doc="what the plot shows: a variable of sweep.nc or an expression such as "
                                          "final_x / final_y (default: the first final value)"),
    "contour": Field(float, doc="draw where the summary equals this value", check=_finite),
    "lines": Field(ArrayOf(SWEEP_LINE), default=[], doc="reference lines over the plot"),
}), doc="a sweep of this scene, run by gyrostat sweep (and gyrostat run): a grid or a seeded dispersion of its "
        "numeric entries")

_DEFAULT = _core.Options()  # the engine's defaults: the one place where they live
METHOD = Field(Choice(*_core.methods()), default="auto",
               doc="integrator (gyrostat.METHODS); auto: DOP853 or CVODE BDF by the stiffness measured along the run")
RTOL = Field(float, default=_DEFAULT.rtol, doc="relative tolerance", check=positive)
ATOL = Field(float, default=_DEFAULT.atol, doc="absolute tolerance", check=non_negative)
N_OUT = Field(int, default=_DEFAULT.n_out, doc="number of evenly spaced output times", check=at_least(2))
T_SPAN = Field(Vector(2), required=True, doc="(t0, t1)", unit="s", check=_span_order)
ACCURACY = Field(float, default=_ladder.ACCURACY, check=positive,
                 doc="model = 'auto': the largest relative error accepted on the quantities the outputs need; "
                     "the cheapest model whose measured error estimate is below it is taken")
PHASE = Field(float, default=0.0, unit="rad", check=_finite,
              doc="model = 'auto': the fast phase at which a switch up the ladder lifts the slow variables")

BODY = Table({
    "moments": Field(Vector(3), required=True, doc="principal moments A1, A2, A3", unit="kg m^2",
                     check=_all_finite),
    "rotor": Field(Vector(3), default=[0.0, 0.0, 0.0], doc="gyrostatic momentum k of the rotors",
                   unit="kg m^2/s", check=_all_finite),
})

# The one registration table of the torques a scene may name: the schema of each, and how to
# build it from the validated table.
TORQUES: dict[str, tuple[Table, callable]] = {
    "constant": (
        Table({"moment": Field(Vector(3), required=True, doc="M in body axes", unit="N m", check=_all_finite)},
              doc="a constant torque in body axes"),
        lambda s: _core.ConstantTorque(s["moment"])),
    "linear_damping": (
        Table({"matrix": Field(Matrix(3, 3), doc="D (M = -D omega)", unit="N m s"),
               "diagonal": Field(Vector(3), doc="the diagonal of D", unit="N m s")},
              one_of=[("matrix", "diagonal")], doc="M = -D omega"),
        lambda s: _core.LinearDamping(np.asarray(s["matrix"]) if "matrix" in s else np.diag(s["diagonal"]))),
    "resistive_medium": (
        Table({"coefficients": Field(ListOf(Matrix(3, 3), min_len=1), required=True,
                                     doc="D_0, D_1, ...: D(t) = sum D_k t^k (M = -D(t) omega)")},
              doc="a resistive medium whose resistance varies with time"),
        lambda s: _core.ResistiveMedium([np.asarray(c) for c in s["coefficients"]])),
    "viscous_cavity": (
        Table({"density": Field(float, required=True, doc="rho", unit="kg/m^3", check=positive),
               "viscosity": Field(float, required=True, doc="kinematic viscosity nu", unit="m^2/s", check=positive),
               "radius": Field(float, doc="radius of a spherical cavity", unit="m", check=positive),
               "p0": Field(float, doc="P0 of the cavity tensor P = P0 I", unit="m^5", check=positive)},
              one_of=[("radius", "p0")], doc="a cavity filled with a highly viscous fluid"),
        lambda s: (_core.ViscousCavity.sphere(s["density"], s["viscosity"], s["radius"]) if "radius" in s
                   else _core.ViscousCavity(s["density"], s["viscosity"], s["p0"]))),
    "moving_mass_damper": (
        Table({"mass": Field(float, required=True, doc="mass m", unit="kg", check=positive),
               "arm": Field(float, required=True, doc="distance rho of the mass on the z axis", unit="m",
                            check=positive),
               "frequency": Field(float, required=True, doc="Omega = sqrt(c/m)", unit="rad/s", check=positive),
               "damping": Field(float, required=True, doc="lambda = delta/m", unit="1/s", check=positive)},
              doc="Chernousko's quasi-static moving-mass damper"),
        lambda s: _core.MovingMassDamper(s["mass"], s["arm"], s["frequency"], s["damping"])),
}
TORQUE = Variants("type", {name: table for name, (table, _) in TORQUES.items()}, doc="a perturbation torque")


def _outputs(plots: tuple[str, ...], default: list[str], **extra: Field) -> Field:
    """The [outputs] table of a kind: the plots it can draw (and what else it takes)."""
    return Field(Table({"plots": Field(ListOf(str, choices=plots), default=default, doc="plots to draw"), **extra}),
                 default={}, doc="what to draw")


def _build(where: str, make, *args):
    """A core object from validated values; its own ValueError becomes a SceneError naming the table."""
    try:
        return make(*args)
    except ValueError as error:
        raise SceneError(f"[{where}] {error}") from None


def _body(doc: dict) -> _core.Body:
    return _build("body", _core.Body, doc["body"]["moments"], doc["body"]["rotor"])


def _torques(doc: dict) -> list:
    return [_build(f"torques[{i}]", TORQUES[spec["type"]][1], spec) for i, spec in enumerate(doc.get("torques", []))]


@dataclass
class Run:
    """One solve of a scene: a model, its initial state, the span and the integrator options."""

    name: str
    model: ModelBase
    y0: np.ndarray
    t_span: tuple[float, float]
    options: dict


# ------------------------------------------------------------------------------------ kinds
class Kind:
    """A scene kind: its schema, the runs it makes, the plots it draws (``plots`` names them)."""

    name = ""
    doc = ""
    schema: Table
    plots: tuple[str, ...] = ()

    def runs(self, doc: dict) -> tuple[list[Run], str, str]:
        """(runs, the model chosen, why)."""
        raise NotImplementedError

    def ladder(self, doc: dict) -> list | None:
        """The rungs of the model ladder for ``model = "auto"`` (cheapest first, the scene's most
        complete model last: :mod:`gyrostat.ladder`), or None where the kind has one model."""
        return None


SPLITS = ("rigid_body", "lagrange_top", "orthogonal_torque")  # the kinds whose models split


def _integration(doc: dict, kind: str = "rigid_body", **extra) -> dict:
    integ = doc["integration"]
    options = {"method": integ["method"], "rtol": integ["rtol"], "atol": integ["atol"], "n_out": integ["n_out"]}
    if integ["method"] == "splitting":
        if kind not in SPLITS:
            raise SceneError(f"[integration] method = 'splitting' is not offered for {kind} scenes (their models do "
                             f"not split into the free-body flow and a perturbation; it is for {', '.join(SPLITS)})")
        options.update(step=integ.get("step"), splitting_order=integ.get("splitting_order", _DEFAULT.splitting_order))
    options.update(extra)
    return options


def averaged_rung(doc: dict, body, torques, omega, drawable: tuple[str, ...], attitude: bool = False):
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
        return _ladder.Rung("averaged", None, y0, description, blocked=blocked)
    exact = validity.exact_reduction(model)
    fast = model.fast_frequency(y0[1])
    span = doc["integration"]["t_span"]
    # an exact reduction has no fast motion to resolve: its probe is the longest one, a twentieth of the span
    # an exact reduction has no fast oscillation to sample: its probe may be shorter than 20 periods
    share = _ladder.PROBE_FRACTION * abs(span[1] - span[0]) / _ladder.PROBE_PERIODS
    period = 2.0 * math.pi / fast if fast > 0 else math.inf
    period = min(period, share) if exact else period
    watches = () if exact else (_ladder.Watch("slow_to_fast", validity.SMALL, 0.5 * validity.SMALL,
                                              "slow rate / fast frequency << 1", scales_error=True),)
    return _ladder.Rung("averaged", model, y0, description, compare=_ladder.slow_variables, fast_period=period,
                        watches=watches, exact=exact,
                        start_checks=lambda: [a for a in validity.check(model, y0, warn=False)
                                              if a.part == "averaged model"],
                        basis="the (a, r) reduction is exact for this symmetric scene: r = 0 is not a limit" if exact
                        else "")


SPLITTING_FIELDS = {
    "step": Field(float, doc="fixed step of method 'splitting' (left out: chosen from rtol by the splitting's own "
                        "error estimate)", unit="s", check=positive),
    "splitting_order": Field(int, default=_DEFAULT.splitting_order, doc="order of the splitting composition: 2, 4 or 6",
                             check=_splitting_order),
}


class RigidBody(Kind):
    name = "rigid_body"
    doc = ("A rigid body or gyrostat under perturbation torques: the full model, its closed form when nothing "
           "perturbs it, or the system averaged over the symmetric Euler-Poinsot motion in (a, r).")
    plots = ("omega", "invariants", "euler_angles", "error", "xy", "slow", "phase", "ladder")
    models = ("auto", "full", "closed_form", "averaged", "compare")

    @property
    def schema(self) -> Table:
        return Table({
            **TITLE,
            "body": Field(BODY, required=True, doc="the body"),
            "torques": Field(ArrayOf(TORQUE), default=[], doc="perturbation torques; they add up"),
            "initial": Field(Table({
                "omega": Field(Vector(3), required=True, doc="angular velocity in body axes", unit="rad/s",
                               check=_all_finite),
                "attitude": Field(Vector(4), doc="attitude quaternion (w, x, y, z), body to inertial; "
                                                 "giving it integrates the attitude", check=_nonzero_quaternion),
            }), required=True, doc="the initial state"),
            "integration": Field(Table({
                "model": Field(Choice(*self.models), default="auto",
                               doc="auto: the cheapest model that meets the accuracy (the model ladder); compare: "
                                   "full and averaged side by side"),
                "accuracy": ACCURACY, "phase": PHASE,
                "method": METHOD, "rtol": RTOL, "atol": ATOL, "t_span": T_SPAN, "n_out": N_OUT,
                **SPLITTING_FIELDS,
            }), required=True, doc="the run"),
            "outputs": _outputs(self.plots, ["omega", "invariants"],
                                reference=Field(Choice("closed_form"), doc="draw and measure against the closed form")),
        })

    def needs_attitude(self, doc: dict) -> bool:
        """The attitude is integrated only when the scene asks for it (an initial quaternion or
        an Euler-angle plot)."""
        return "attitude" in doc["initial"] or "euler_angles" in doc["outputs"]["plots"]

    def choose(self, doc: dict, body, torques) -> tuple[str, str]:
        """The cheapest model that answers the scene, and the reason for the choice."""
        choice = doc["integration"]["model"]
        free = not torques and not np.any(np.asarray(body.rotor))
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
        if attitude:
            reasons.append("attitude asked for")
        return "full", "full model: " + ", ".join(reasons)

    # plots an averaged model can draw: functions of its slow variables
    slow_plots = ("xy", "slow", "phase", "invariants", "ladder")

    def ladder(self, doc):
        body, torques = _body(doc), _torques(doc)
        omega = np.asarray(doc["initial"]["omega"], float)
        attitude = self.needs_attitude(doc)
        q0 = np.asarray(doc["initial"].get("attitude", [1.0, 0.0, 0.0, 0.0]), float)
        y0 = np.concatenate([omega, q0 / np.linalg.norm(q0)]) if attitude else omega
        free = not torques and not np.any(np.asarray(body.rotor))
        closed = _ladder.Rung("closed_form", TorqueFreeModel(body, attitude) if free else None, y0,
                              "the exact torque-free flow (elliptic functions)",
                              blocked="" if free else "torques or a rotor perturb the body")
        full = _ladder.Rung("full", _build("torques", Model, body, torques, attitude), y0,
                            "Euler's equations" + (" with the attitude" if attitude else ""),
                            compare=_ladder.slow_variables)
        rungs = [closed, averaged_rung(doc, body, torques, omega, self.slow_plots, attitude), full]
        return rungs

    def runs(self, doc):
        body, torques = _body(doc), _torques(doc)
        choice, reason = self.choose(doc, body, torques)
        omega = np.asarray(doc["initial"]["omega"], float)
        t_span = tuple(doc["integration"]["t_span"])
        options = _integration(doc)
        runs = []
        attitude = self.needs_attitude(doc)
        q0 = np.asarray(doc["initial"].get("attitude", [1.0, 0.0, 0.0, 0.0]), float)
        if choice == "closed_form":
            y0 = np.concatenate([omega, q0 / np.linalg.norm(q0)]) if attitude else omega
            runs.append(Run("closed_form", _build("body", TorqueFreeModel, body, attitude), y0, t_span, options))
        if choice in ("full", "compare"):
            model = _build("torques", Model, body, torques, attitude)
            y0 = np.concatenate([omega, q0 / np.linalg.norm(q0)]) if attitude else omega
            runs.append(Run("full", model, y0, t_span, options))
        if choice in ("averaged", "compare"):
            model = _build("torques", AveragedModel, body, torques)
            runs.append(Run("averaged", model, np.array([math.hypot(omega[0], omega[1]), omega[2]]), t_span, options))
        return runs, choice, reason


class Averaged(RigidBody):
    name = "averaged"
    doc = ("The system averaged over the symmetric Euler-Poinsot motion in the slow variables (a, r) alone "
           "(a rigid_body scene with model = 'averaged'; the initial state may be given as a and r).")
    plots = ("xy", "slow", "phase")

    @property
    def schema(self) -> Table:
        return Table({
            **TITLE,
            "body": Field(BODY, required=True, doc="the (nearly) symmetric body A1 ~ A2, no rotor"),
            "torques": Field(ArrayOf(TORQUE), default=[], doc="perturbation torques; their averages add up"),
            "initial": Field(Table({
                "omega": Field(Vector(3), doc="angular velocity in body axes (gives a = |(p, q)|, r)", unit="rad/s",
                               check=_all_finite),
                "a": Field(float, doc="equatorial amplitude a = sqrt(p^2 + q^2)", unit="rad/s", check=non_negative),
                "r": Field(float, doc="axial rate r (signed)", unit="rad/s", check=_finite),
            }), required=True, doc="the initial state: omega, or a and r"),
            "integration": Field(Table({"method": METHOD, "rtol": RTOL, "atol": ATOL, "t_span": T_SPAN,
                                        "n_out": N_OUT}), required=True, doc="the run"),
            "outputs": _outputs(self.plots, ["xy", "slow"]),
        })

    def runs(self, doc):
        body, torques = _body(doc), _torques(doc)
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
        model = _build("torques", AveragedModel, body, torques)
        return ([Run("averaged", model, y0, tuple(doc["integration"]["t_span"]), _integration(doc, "averaged"))], "averaged",
                "asked for by the scene kind")


class MovingMass(Kind):
    name = "moving_mass"
    doc = ("The explicit moving-mass model (paper 001): a carrier and a point mass on a damped spring, "
           "9 states, stiff for a strong damper (method auto by default: CVODE BDF where it is stiff).")
    plots = ("omega", "invariants", "mass", "ladder")

    @property
    def schema(self) -> Table:
        damper_table, _ = TORQUES["moving_mass_damper"]
        return Table({
            **TITLE,
            "body": Field(BODY, required=True, doc="the system's moments with the mass at rest"),
            "damper": Field(damper_table, required=True, doc="the mass, its arm, spring and damper"),
            "torques": Field(ArrayOf(TORQUE), default=[], doc="external torques on the carrier"),
            "initial": Field(Table({
                "omega": Field(Vector(3), required=True, doc="angular velocity", unit="rad/s", check=_all_finite),
                "start": Field(Choice("quasi_static", "at_rest"), default="quasi_static",
                               doc="quasi_static: the mass on its forced motion; at_rest: u = v = 0"),
            }), required=True, doc="the initial state"),
            "integration": Field(Table({"model": Field(Choice("auto", "explicit", "reduced", "averaged"), default="auto",
                                                       doc="auto: the cheapest model that meets the accuracy; "
                                                           "averaged: (a, r); reduced: the quasi-static damper torque; "
                                                           "explicit: the mass, spring and damper"),
                                        "accuracy": ACCURACY, "phase": PHASE,
                                        "method": METHOD,
                                        "rtol": RTOL, "atol": ATOL, "t_span": T_SPAN, "n_out": N_OUT}),
                                 required=True, doc="the run"),
            "outputs": _outputs(self.plots, ["omega", "invariants", "mass"]),
        })

    def ladder(self, doc):
        body, torques = _body(doc), _torques(doc)
        d = doc["damper"]
        damper = _build("damper", _core.MovingMassDamper, d["mass"], d["arm"], d["frequency"], d["damping"])
        model = _build("damper", MovingMassModel, body, d["mass"], d["arm"], d["frequency"], d["damping"], torques)
        omega = np.asarray(doc["initial"]["omega"], float)
        y0 = model.quasi_static_state(omega) if doc["initial"]["start"] == "quasi_static" else \
            np.concatenate([omega, np.zeros(6)])
        plots = doc["outputs"]["plots"]
        compare = _ladder.rates if "omega" in plots else _ladder.slow_variables
        explicit = _ladder.Rung("explicit", model, y0, "the carrier, the point mass, its spring and damper (9 states)",
                                compare=compare)
        reduced_model = _build("damper", Model, body, [damper, *torques])
        checks = [a for a in validity.check(reduced_model, omega, warn=False)
                  if a.part == "moving-mass damper" and "condition (4)" not in a.statement]
        A, C = body.moments[0], body.moments[2]
        fast = abs((C - A) * omega[2] / A)
        reduced = _ladder.Rung(
            "reduced", reduced_model, omega, "the rigid body under the damper's quasi-static torque (Chernousko)",
            compare=compare, fast_period=2.0 * math.pi / fast if fast > 0 else math.inf,
            phase_compared=compare is _ladder.rates,
            blocked="the plot 'mass' needs the mass's own motion" if "mass" in plots else "",
            start_checks=lambda: checks, small=max(a.value for a in checks),
            basis="; ".join(f"{a.statement} = {a.value:.3g}" for a in checks))
        averaged = averaged_rung(doc, body, [damper, *torques], omega, ("invariants", "ladder"))
        return [averaged, reduced, explicit]

    def runs(self, doc):
        choice = doc["integration"]["model"]
        rungs = {rung.name: rung for rung in self.ladder(doc)}
        rung = rungs["explicit" if choice == "auto" else choice]
        if rung.blocked:
            raise SceneError(f"[integration] model = {choice!r}: {rung.blocked}")
        reason = {"explicit": "the explicit mass, spring and damper", "reduced": "the quasi-static damper torque",
                  "averaged": "the averaged (a, r) system with the damper's torque"}[rung.name]
        return ([Run("averaged" if rung.name == "averaged" else "full", rung.model, rung.y0,
                     tuple(doc["integration"]["t_span"]), _integration(doc, "moving_mass"))], rung.name,
                f"asked for by the scene: {reason}" if choice != "auto" else "the scene's own model (the ladder "
                "chooses when it is solved)")


class LagrangeTopKind(Kind):
    name = "lagrange_top"
    doc = ("Paper 003: the heavy symmetric top under M = eps(-a(tau) p, -a(tau) q, -b(tau) r), tau = eps t: the "
           "full top in (omega, quaternion) next to the system averaged over the nutation in (G_z, H, r).")
    plots = ("slow", "roots", "nutation", "validity", "ladder")

    def ladder(self, doc):
        return _lagrange_ladder(self, doc)

    @property
    def schema(self) -> Table:
        return Table({
            **TITLE,
            "body": Field(Table({"A": Field(float, required=True, doc="equatorial moment", unit="kg m^2",
                                            check=positive),
                                 "C": Field(float, required=True, doc="axial moment", unit="kg m^2", check=positive),
                                 "mu": Field(float, required=True, doc="m g l", unit="N m", check=positive)}),
                          required=True, doc="the top"),
            "torque": Field(Table({"epsilon": Field(float, required=True, doc="eps", check=positive),
                                   "a": Field(ListOf(float, min_len=1), required=True, doc="a_k: a(tau) = sum a_k tau^k"),
                                   "b": Field(ListOf(float, min_len=1), required=True,
                                              doc="b_k: b(tau) = sum b_k tau^k")}),
                            required=True, doc="paper 003's torque (3.1)"),
            "initial": Field(Table({
                "omega": Field(Vector(3), required=True, doc="angular velocity in body axes", unit="rad/s",
                               check=_all_finite),
                "theta_deg": Field(float, default=0.0, doc="nutation angle", unit="deg", check=_finite),
                "phi_deg": Field(float, default=0.0, doc="proper rotation angle", unit="deg", check=_finite),
                "psi_deg": Field(float, default=0.0, doc="precession angle", unit="deg", check=_finite),
            }), required=True, doc="the initial state (z-x-z Euler angles)"),
            "integration": Field(Table({"model": Field(Choice("compare", "auto", "full", "averaged"), default="compare",
                                                       doc="compare: the full and the averaged top side by side; auto: "
                                                           "the cheapest that meets the accuracy (the model ladder)"),
                                        "accuracy": ACCURACY, "phase": PHASE,
                                        "method": METHOD, "rtol": Field(float, default=1e-10, doc="relative tolerance",
                                                                        check=positive),
                                        "atol": Field(float, default=1e-12, doc="absolute tolerance",
                                                      check=non_negative),
                                        "tau_end": Field(float, required=True, doc="end of the slow time tau = eps t",
                                                         unit="s", check=positive),
                                        "n_out": Field(int, default=4001, doc="number of output times",
                                                       check=at_least(2)),
                                        **SPLITTING_FIELDS}),
                                 required=True, doc="the run"),
            "outputs": _outputs(self.plots, ["slow", "roots", "nutation", "validity"]),
        })

    def runs(self, doc):
        b, tq, ini = doc["body"], doc["torque"], doc["initial"]
        torque = _build("torque", lagrange.paper_torque, tq["epsilon"], tq["a"], tq["b"])
        full = _build("body", lagrange.LagrangeTop, b["A"], b["C"], b["mu"], [torque])
        averaged = _build("body", lagrange.LagrangeAveraged, b["A"], b["C"], b["mu"], [torque])
        y0 = lagrange.initial_state(ini["omega"], math.radians(ini["theta_deg"]), math.radians(ini["phi_deg"]),
                                    math.radians(ini["psi_deg"]))
        span = (0.0, doc["integration"]["tau_end"] / tq["epsilon"])
        options = _integration(doc, "lagrange_top")
        choice = doc["integration"]["model"]
        if options["method"] == "splitting" and choice != "full":
            raise SceneError(f"[integration] method = 'splitting' splits the full top only (the averaged top has no "
                             f"free rotation to split on): set model = 'full' (got model = '{choice}')")
        if choice in ("full", "averaged"):
            return ([Run(choice, full if choice == "full" else averaged, y0, span, options)], choice,
                    "asked for by the scene")
        return ([Run("full", full, y0, span, options), Run("averaged", averaged, y0, span, options)],
                "full_and_averaged",
                f"paper 003: full top (omega, quaternion) next to the nutation-averaged (G_z, H, r) system; "
                f"epsilon = {tq['epsilon']:g}, a = {tq['a']}, b = {tq['b']}")


def _lagrange_ladder(kind: "LagrangeTopKind", doc: dict) -> list:
    """The heavy top's rungs: averaged over the nutation in (G_z, H, r), then the full top.
    The averaged one is blocked when a plot needs θ(t) itself; it watches the adiabaticity N and
    the distance from the separatrix 1 − k², switching to the full top where either fails."""
    runs, _, _ = kind.runs({**doc, "integration": {**doc["integration"], "model": "compare"}})
    full, averaged = runs
    slow0 = np.asarray(averaged.model._core.initial_state(full.y0))
    period = float(lagrange.nutation_table(averaged.model, slow0)["T_nut"][0])
    needs = [p for p in doc["outputs"]["plots"] if p == "nutation"]
    top = _ladder.Rung("full", full.model, full.y0, "the full top (omega, quaternion)",
                       compare=_ladder.top_slow_variables)
    limit = lagrange.SEPARATRIX_LIMIT
    lower = _ladder.Rung(
        "averaged", averaged.model, slow0, "the top averaged over the nutation, in (G_z, H, r)",
        compare=_ladder.top_slow_variables, fast_period=period if period > 0 else math.inf,
        blocked=f"the plots {needs} need theta(t): the averaged top gives its bounds only" if needs else "",
        watches=(_ladder.Watch("adiabaticity", validity.SMALL, 0.5 * validity.SMALL,
                               "nutation period short against the slow time, N << 1", scales_error=True),
                 _ladder.Watch("m", 1.0 - limit, 1.0 - 2.0 * limit, "away from the separatrix, 1 - k^2 >= 1e-3")),
        start_checks=lambda: lagrange.check(averaged.model, slow0, [0.0], warn=False))
    return [lower, top]


LAW = Variants("kind", {
    "constant": Table({"value": Field(float, required=True, doc="L", unit="N m", check=_finite)}),
    "polynomial": Table({"coefficients": Field(ListOf(float, min_len=1), required=True, doc="c_i: L = sum c_i t^i")}),
    "harmonic": Table({"mean": Field(float, required=True, doc="L0", unit="N m"),
                       "amplitudes": Field(ListOf(float), default=[], doc="A_i", unit="N m"),
                       "frequencies": Field(ListOf(float), default=[], doc="w_i", unit="rad/s"),
                       "phases": Field(ListOf(float), doc="phi_i (default 0)", unit="rad")}),
    "tabulated": Table({"times": Field(ListOf(float, min_len=2), required=True, doc="t_i", unit="s",
                                       check=increasing),
                        "values": Field(ListOf(float, min_len=2), required=True, doc="L_i", unit="N m"),
                        "interpolation": Field(Choice("linear", "cubic"), default="linear", doc="between points")}),
}, doc="the magnitude law L(t)")


class OrthogonalTorqueKind(Kind):
    name = "orthogonal_torque"
    doc = ("Paper 004: a gyrostat under the servo torque L(t) Q/|Q|, Q = omega x G, one run per magnitude law, "
           "compared with the torque-free gyrostat at tau(t) and, for a nearly spherical body, with the "
           "approximations of section 4.")
    plots = ("omega", "invariants", "tau", "euler_angles", "approximation_errors")

    @property
    def schema(self) -> Table:
        return Table({
            **TITLE,
            "body": Field(BODY, doc="a gyrostat (or give [nearly_spherical])"),
            "nearly_spherical": Field(Table({
                "J": Field(float, required=True, doc="mean moment", unit="kg m^2", check=positive),
                "Jj": Field(Vector(3), required=True, doc="A_j = J + mu J_j", unit="kg m^2"),
                "mu": Field(float, required=True, doc="small parameter mu"),
                "rotor": Field(Vector(3), default=[0.0, 0.0, 0.0], doc="rotor momentum k", unit="kg m^2/s"),
                "G": Field(float, default=1.0, doc="|G|", unit="kg m^2/s", check=positive),
                "theta0": Field(float, default=1.0, doc="initial nutation of G in body axes", unit="rad"),
                "phi0": Field(float, default=0.0, doc="initial proper rotation", unit="rad"),
                "psi0": Field(float, default=0.0, doc="initial precession", unit="rad"),
            }), doc="a nearly spherical gyrostat A_j = J + mu J_j, its initial state from G and the Euler angles"),
            "initial": Field(Table({
                "omega": Field(Vector(3), doc="angular velocity (with [body])", unit="rad/s", check=_all_finite),
                "attitude": Field(Vector(4), doc="quaternion (w, x, y, z); default: inertial z along G(0)",
                                  check=_nonzero_quaternion),
            }), default={}, doc="the initial state (with [body])"),
            "runs": Field(ArrayOf(Table({"name": Field(str, required=True, doc="the run's name"),
                                         "law": Field(OneOf(float, LAW), required=True,
                                                      doc="L(t): a number, or a table with its kind")})),
                          required=True, doc="one run per magnitude law"),
            "integration": Field(Table({"method": METHOD,
                                        "rtol": Field(float, default=1e-10, doc="relative tolerance", check=positive),
                                        "atol": Field(float, default=1e-12, doc="absolute tolerance",
                                                      check=non_negative),
                                        "t_span": Field(Vector(2), default=[0.0, 60.0], doc="(t0, t1)", unit="s",
                                                        check=_span_order),
                                        "n_out": Field(int, default=1201, doc="number of output times",
                                                       check=at_least(2)),
                                        "eta": Field(float, default=orthogonal.ETA,
                                                     doc="regularisation: delta = eta |omega| |G|", check=positive),
                                        **SPLITTING_FIELDS}),
                                 default={}, doc="the runs' integration"),
            "outputs": _outputs(self.plots, list(self.plots)),
        })

    def spherical(self, doc: dict):
        s = doc.get("nearly_spherical")
        if s is None:
            return None
        return _build("nearly_spherical", orthogonal.NearlySpherical, s["J"], s["Jj"], s["mu"], s["rotor"], s["G"],
                      s["theta0"], s["phi0"], s["psi0"])

    def runs(self, doc):
        if ("body" in doc) == ("nearly_spherical" in doc):
            raise SceneError("needs exactly one of [body] or [nearly_spherical]"
                             + ("; both are given" if "body" in doc else "; none is given"))
        spherical = self.spherical(doc)
        if spherical is not None:
            body = spherical.body()
            omega0, q0 = spherical.initial_state()
            if doc["initial"]:
                raise SceneError("[initial] is not used with [nearly_spherical] (the state follows from G and the angles)")
        else:
            body = _body(doc)
            if "omega" not in doc["initial"]:
                raise SceneError("[initial] is missing required key 'omega' (angular velocity in body axes [rad/s])")
            omega0 = np.asarray(doc["initial"]["omega"], float)
            if "attitude" in doc["initial"]:
                q0 = np.asarray(doc["initial"]["attitude"], float)
                q0 = q0 / np.linalg.norm(q0)
            else:  # inertial z3 along G(0), ψ0 = 0: the Euler angles of (15)-(16)
                q0 = orthogonal.attitude_along_momentum(np.asarray(body.moments) * omega0 + np.asarray(body.rotor))
        integ = doc["integration"]
        runs = []
        for i, spec in enumerate(doc["runs"]):
            law = _build(f"runs[{i}].law", orthogonal.law_from_spec, spec["law"])
            model = _build(f"runs[{i}]", orthogonal.OrthogonalModel, body, law, (), True, integ["eta"])
            runs.append(Run(spec["name"], model, np.concatenate([omega0, q0, [0.0]]), tuple(integ["t_span"]),
                            _integration(doc, "orthogonal_torque", events=orthogonal.g_zero())))
        names = [r.name for r in runs]
        if len(set(names)) != len(names):
            raise SceneError(f"[runs] names must differ; got {names}")
        return (runs, "orthogonal_torque", "full model in t with tau and the attitude quaternion (paper 004); the "
                "torque-free (Zhukovsky-Volterra) solution at tau(t) and, for a nearly spherical body, the "
                "approximations of section 4 for comparison")


KINDS: dict[str, Kind] = {kind.name: kind for kind in (RigidBody(), Averaged(), MovingMass(), LagrangeTopKind(),
                                                       OrthogonalTorqueKind())}
"""The registry of scene kinds, by the name a scene gives as ``kind``."""


def _add_events(doc: dict, runs: list[Run]) -> None:
    """The scene's [[events]] to every run whose model has the quantity (one that none has is an error)."""
    from gyrostat.events import Event

    for i, spec in enumerate(doc["events"]):
        event = _build(f"events[{i}]", Event, spec["quantity"], spec["value"], spec["direction"], spec["terminal"],
                       spec["name"] or None)
        users = [r for r in runs if spec["quantity"] in r.model.state_names + r.model.output_names]
        if not users:
            names = sorted({n for r in runs for n in r.model.state_names + r.model.output_names})
            raise SceneError(f"[events[{i}]] quantity = {spec['quantity']!r} is neither a state component nor an output "
                             f"of the scene's models ({', '.join(names)})")
        for run in users:
            run.options = {**run.options, "events": list(run.options.get("events", [])) + [event]}


# ------------------------------------------------------------------------------------ scenes
@dataclass
class Scene:
    """A validated scene: its kind, its document (defaults filled in) and its runs."""

    name: str
    kind: Kind
    doc: dict
    runs: list[Run] = field(default_factory=list)
    model_choice: str = ""
    model_reason: str = ""
    ladder: list | None = None
    """With model = "auto": the kind's rungs (gyrostat.ladder), chosen among when the scene is solved."""

    @property
    def title(self) -> str:
        return self.doc["title"] or self.name

    @property
    def description(self) -> str:
        return self.doc["description"]

    @property
    def plots(self) -> list[str]:
        return list(self.doc["outputs"]["plots"])

    @classmethod
    def from_dict(cls, data: dict, name: str = "scene") -> "Scene":
        if not isinstance(data, dict):
            raise SceneError(f"a scene is a table of keys, got {type(data).__name__}")
        kind_name = data.get("kind", "rigid_body")
        if kind_name not in KINDS:
            import difflib

            close = difflib.get_close_matches(str(kind_name), list(KINDS), n=1, cutoff=0.6)
            raise SceneError(f"kind = {kind_name!r} is not a scene kind ({', '.join(KINDS)})"
                             + (f"; did you mean {close[0]!r}?" if close else ""))
        kind = KINDS[kind_name]
        doc = validate(kind.schema, data)
        runs, choice, reason = kind.runs(doc)
        for run in runs:  # tolerances, outputs and their memory: refused now, naming the key, not once running
            _build("integration", check_run, run.model, run.t_span, run.options)
        _add_events(doc, runs)
        rungs = kind.ladder(doc) if doc.get("integration", {}).get("model") == "auto" else None
        return cls(name=name, kind=kind, doc=doc, runs=runs, model_choice=choice, model_reason=reason, ladder=rungs)

    @classmethod
    def from_toml(cls, path: str | Path) -> "Scene":
        path = Path(path)
        try:
            with path.open("rb") as handle:
                data = tomllib.load(handle)
        except tomllib.TOMLDecodeError as error:
            raise SceneError(f"not valid TOML: {error}") from None
        except UnicodeDecodeError as error:
            raise SceneError(f"not a UTF-8 text file (byte {error.object[error.start]:#04x} at position "
                             f"{error.start}): a scene is a TOML text file") from None
        except OSError as error:
            raise SceneError(f"cannot read the scene: {error.strerror}") from None
        return cls.from_dict(data, name=path.stem)


SCENES = Path(__file__).resolve().parent / "scenes"
"""The folder of the scenes shipped with the package (``gyrostat examples`` runs them)."""


def load(path: str | Path) -> Scene:
    """Reads and validates a scene file; every problem is a one-line :class:`SceneError`."""
    return Scene.from_toml(path)


def scene_format() -> str:
    """The reference of every scene kind (Markdown), from the schemas themselves."""
    parts = ["# Scene files\n", "The top-level key `kind` selects one of the kinds below (`rigid_body` when absent).\n"]
    for kind in KINDS.values():
        parts.append(f"\n## kind = \"{kind.name}\"\n\n{kind.doc}\n\nPlots: {', '.join(kind.plots)}.\n")
        parts.append(describe(kind.schema, title=f"{kind.name}: top level"))
    parts.append("\n## Torques (`[[torques]]`, by `type`)\n")
    parts.append(describe(Table({"torques": Field(ArrayOf(TORQUE), doc="torques")}), title="torques"))
    return "\n".join(parts)
