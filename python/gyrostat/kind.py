"""The scene kind every family's kinds derive from, and what all kinds share.

* :class:`Kind`: a scene kind's name, schema, runs, ladder, checks, analysis, output columns and
  plots (each family module subclasses it: ``gyrostat/families/``);
* :data:`KINDS` and :func:`register`: the registry that family modules fill when they are
  imported (:mod:`gyrostat.families` imports them all);
* :class:`Run`: one solve of a scene;
* the schema pieces every kind uses (:func:`title_fields`: ``kind``, ``title``, ``description``,
  ``events``, ``sweep``; ``BODY``; the integration fields ``METHOD``, ``RTOL``, ``ATOL``,
  ``N_OUT``, ``T_SPAN``, ``ACCURACY``, ``PHASE``, ``SPLITTING_FIELDS``; :func:`outputs_field`) and
  the builders from a validated document (:func:`build`, :func:`make_body`, :func:`make_torques`,
  :func:`integration`).
"""

from __future__ import annotations

import contextlib
import threading
from dataclasses import dataclass

import numpy as np

from gyrostat import _core
from gyrostat import ladder as _ladder
from gyrostat.modelbase import ModelBase
from gyrostat.schema import (ArrayOf, Choice, Field, ListOf, Matrix, SceneError, Table, Vector, all_finite, at_least,
                             finite, non_negative, positive, span_order)
from gyrostat import torques as _torques

__all__ = ["Kind", "Run", "KINDS", "register", "default_kind", "title_fields", "outputs_field", "build",
           "make_body", "make_torques", "reusing", "integration", "integration_table", "BODY", "METHOD", "RTOL", "ATOL", "N_OUT", "T_SPAN", "ACCURACY", "PHASE",
           "SPLITTING_FIELDS", "engine_option", "engine_rule", "MAX_STEPS"]


@dataclass
class Run:
    """One solve of a scene: a model, its initial state, the span and the integrator options.

    Parameters
    ----------
    name : str
        The run's name ("full", "averaged", …).
    model : gyrostat.ModelBase
        The model solved.
    y0 : numpy.ndarray
        The initial state, in the model's units.
    t_span : (float, float)
        (t0, t1), in s.
    options : dict
        The keywords of :func:`gyrostat.solve` (method, rtol, atol, n_out, events, …).

    Examples
    --------
    >>> from gyrostat.scene import SCENES, load
    >>> run = load(SCENES / "forced_damped.toml").runs[0]
    >>> run.name, run.t_span, run.options["rtol"]
    ('full', (0.0, 200.0), 1e-10)
    """

    name: str
    model: ModelBase
    y0: np.ndarray
    t_span: tuple[float, float]
    options: dict


class Kind:
    """A scene kind: its schema, the runs it makes, the plots it draws (``plots`` names them).
    The defaults below are those of a kind with one model, no ladder, its models' own checks
    and no analysis or plots of its own; a family's kind overrides what it has."""

    name = ""
    doc = ""
    schema: Table
    plots: tuple[str, ...] = ()
    default = False
    """The kind of a scene that gives no ``kind`` (one kind is)."""
    splits = False
    """Its models split into the free-body flow and a perturbation (``method = "splitting"``)."""

    def runs(self, doc: dict) -> tuple[list[Run], str, str]:
        """(runs, the model chosen, why)."""
        raise NotImplementedError

    def ladder(self, doc: dict) -> list | None:
        """The rungs of the model ladder for ``model = "auto"`` (cheapest first, the scene's most
        complete model last: :mod:`gyrostat.ladder`), or None where the kind has one model."""
        return None

    def initial_assumptions(self, run: Run, warn: bool) -> list:
        """The assumptions of a run's model at its initial state (``gyrostat.validity.check_scene``)."""
        return []

    def assumptions(self, run: Run, solution) -> list:
        """The assumptions of a run's model along its solution (the report's ``assumptions``)."""
        return run.model.check(solution)

    def analyse(self, scene, solutions: dict, report: dict, derived: dict) -> None:
        """The paper's analysis of the solved runs, from their recorded outputs: entries of the
        report, and in ``derived`` what the plots need beside the runs."""

    def extra_columns(self, scene, solution) -> dict | None:
        """Columns written beside a run's own: name → (values, unit) (None: none)."""
        return None

    def draw(self, scene, solutions: dict, derived: dict, folder) -> list:
        """The kind's plots that the scene asks for, as PNG files in ``folder``."""
        return []

    def why_not_drawn(self, doc: dict, plot: str) -> str:
        """Why a plot of this kind asked for was not drawn, where the kind knows ("" otherwise)."""
        return ""


KINDS: dict[str, Kind] = {}
"""The registry of scene kinds, by the name a scene gives as ``kind``, in the order the family
modules registered them (import :mod:`gyrostat.families` to have them all)."""


def register(*kinds: Kind) -> None:
    """Adds a family's kinds to :data:`KINDS` (a family module calls it once, at its end)."""
    for kind in kinds:
        if kind.name in KINDS:
            raise ValueError(f"scene kind {kind.name!r} is registered twice")
        KINDS[kind.name] = kind


def default_kind() -> str:
    """The name of the kind of a scene that gives no ``kind``."""
    return next(name for name, kind in KINDS.items() if kind.default)


# ------------------------------------------------------------------------------------ schema pieces
def _direction(value):
    if value not in (-1, 0, 1):
        raise ValueError("must be -1, 0 or 1")


EVENT = Table({
    "quantity": Field(str, required=True, doc="a state component or a named output of the run's model"),
    "value": Field(float, default=0.0, doc="the value it crosses", check=finite),
    "direction": Field(int, default=0, doc="+1 upward crossings only, -1 downward, 0 both", check=_direction),
    "terminal": Field(int, default=0, doc="0: record; n: stop the run at the n-th crossing", check=non_negative),
    "name": Field(str, default="", doc="a name for the report"),
}, doc="an event: where a quantity crosses a value, located by the engine")

SWEEP_PARAMETER = Table({
    "path": Field(str, doc="the entry of this scene it sets: body.moments[0], torques[1].viscosity, initial.omega[2], "
                           "integration.rtol; a slice body.moments[0:2] sets several entries"),
    "paths": Field(ListOf(str, min_len=1), doc="several entries set to the same value"),
    "name": Field(str, doc="the coordinate's name in sweep.nc (default: the path)"),
    "label": Field(str, default="", doc="text for plots, e.g. A/C"),
    "scale": Field(float, default=1.0, doc="each entry is set to scale * value", check=finite),
    "values": Field(ListOf(float, min_len=1), doc="a grid: these values"),
    "start": Field(float, doc="a grid from start to stop (with num)", check=finite),
    "stop": Field(float, doc="the grid's last value", check=finite),
    "num": Field(int, doc="the grid's number of values", check=at_least(1)),
    "spacing": Field(Choice("linear", "log"), default="linear", doc="the grid's spacing"),
    "distribution": Field(Choice("uniform", "normal", "loguniform"), doc="a dispersion: uniform and loguniform take "
                                                                         "low and high, normal takes mean and std"),
    "low": Field(float, doc="lower bound", check=finite),
    "high": Field(float, doc="upper bound", check=finite),
    "mean": Field(float, doc="mean", check=finite),
    "std": Field(float, doc="standard deviation", check=finite),
}, one_of=[("path", "paths")], doc="a varied parameter: a grid (values, or start, stop, num) or a distribution")
SWEEP_LINE = Table({"label": Field(str, required=True, doc="legend text"),
                    "x": Field(ListOf(float, min_len=2), required=True, doc="first parameter's values"),
                    "y": Field(ListOf(float, min_len=2), required=True, doc="the summary (one parameter) or the second "
                                                                            "parameter's values")},
                   doc="a reference line drawn over the sweep's plot")
SWEEP = Field(Table({
    "vary": Field(ArrayOf(SWEEP_PARAMETER), required=True, doc="the varied parameters"),
    "run": Field(str, doc="the run of the scene to sweep (default: its only run, or full)"),
    "samples": Field(int, doc="members of a dispersion", check=at_least(1)),
    "seed": Field(int, doc="seed of a dispersion (default: a fresh one, recorded in sweep.nc)", check=non_negative),
    "trajectories": Field(bool, default=False, doc="keep every member's trajectory in sweep.nc"),
    "summary": Field(str, default="", doc="what the plot shows: a variable of sweep.nc or an expression such as "
                                          "final_x / final_y (default: the first final value)"),
    "contour": Field(float, doc="draw where the summary equals this value", check=finite),
    "lines": Field(ArrayOf(SWEEP_LINE), default=[], doc="reference lines over the plot"),
}), doc="a sweep of this scene, run by gyrostat sweep (and gyrostat run): a grid or a seeded dispersion of its "
        "numeric entries")


EXPECTED_BROKEN = Table({
    "assumption": Field(str, required=True, doc="the start of the broken assumption as the report prints it "
                                                "(part: statement), e.g. 'viscous cavity: Reynolds number'"),
    "why": Field(str, required=True, doc="why the scene breaks it (the paper's own parameters) and what holds anyway"),
}, doc="an assumption the scene breaks on purpose")


def title_fields() -> dict[str, Field]:
    """The top-level keys every kind has: kind, title, description, expected_broken, events and sweep."""
    return {
        "kind": Field(str, default=default_kind(), doc="scene kind: " + ", ".join(KINDS)),
        "title": Field(str, default="", doc="a title for plots and reports"),
        "description": Field(str, default="", doc="what the scene shows"),
        "expected_broken": Field(ArrayOf(EXPECTED_BROKEN), default=[],
                                 doc="assumptions of its models the scene breaks on purpose (a paper's own parameters): "
                                     "reported as expected, with the reason and the measured agreement, not as a "
                                     "warning; one that holds is reported as a stale marker"),
        "events": Field(ArrayOf(EVENT), default=[], doc="events to locate in every run that has the quantity"),
        "sweep": SWEEP,
    }


_DEFAULT = _core.Options()  # the engine's defaults: the one place where they live


def engine_rule(name: str):
    """The engine's own rule for the scalar option ``name`` (C++ ``Options::check``), as a schema
    check: a scene is refused with the same words as the engine would use, at its key."""
    def check(value) -> None:
        try:
            _core.Options.check(name, value)
        except ValueError as error:  # "rtol = 2 must be below 1": the key and value are named by the schema
            text = str(error)
            raise ValueError(text.split(" ", 3)[3] if text.startswith(f"{name} = ") else text) from None
    return check


class Unstated(float):
    """A tolerance's default that the scene did not state (``integration.rtol``, ``atol``): with
    ``integration.accuracy`` given, the run chooses its tolerances instead (a value the scene
    states is a plain float, and wins)."""

    def __repr__(self) -> str:
        return repr(float(self))


def engine_option(name: str, type_, doc: str, default=None, why: str = "", **extra) -> Field:
    """A scene field for the engine option ``name``: its default (the engine's, unless a family
    gives its own with the reason ``why``, which the field's doc then states) and its rule, both
    from C++ (:class:`gyrostat.Options`, ``Options.check``)."""
    if default is None:
        default = getattr(_DEFAULT, name)
    elif not why:
        raise ValueError(f"a family's own default for {name} needs its reason")
    made = Field(type_, default=default, doc=doc + (f" (default {default:g}: {why})" if why else ""),
                 check=engine_rule(name), **extra)
    if name in ("rtol", "atol"):
        made.default = Unstated(made.default)
    return made


METHOD = Field(Choice(*_core.methods()), default="auto",
               doc="integrator (gyrostat.METHODS); auto: DOP853 or CVODE BDF by the stiffness measured along the run")
RTOL = engine_option("rtol", float, "relative tolerance")
ATOL = engine_option("atol", float, "absolute tolerance")
N_OUT = engine_option("n_out", int, "number of evenly spaced output times (0: t0 and t1 only)")
MAX_STEPS = engine_option("max_steps", int, "the most steps a run may take (one that needs more stops there, keeps "
                                            "what it computed and says so): raise it for long horizons of the full model")
T_SPAN = Field(Vector(2), required=True, doc="(t0, t1)", unit="s", check=span_order)
ACCURACY = Field(float, default=None, check=positive,
                 doc="the largest relative error accepted on the quantities the runs report (gyrostat.accuracy): "
                     "every run then meets it, rtol and atol chosen to meet it unless the scene gives them, and "
                     "says so when it cannot; model = 'auto' takes the cheapest model whose measured error "
                     f"estimate is below it (left out: the runs keep rtol and atol, model = 'auto' takes "
                     f"{_ladder.ACCURACY:g}); each run reports its measured error either way")
SENSITIVITIES = Field(ListOf(str, min_len=1), default=None,
                      doc="forward sensitivities to integrate with each run (gyrostat.sensitivity): initial state "
                          "components by name and parameters ('moments[0]', 'ViscousCavity.viscosity', "
                          "'LinearDamping.matrix[0,1]', ...); written beside the state as d_<component>__d_<name> "
                          "(method 'auto' then runs dop853, the one the variational equations take)")
SENSITIVITY_ERROR_CONTROL = Field(bool, default=_DEFAULT.sensitivity_error_control,
                                  doc="with sensitivities: whether their errors join the state's in the step-size "
                                      "control (false: the plain run's steps, each sensitivity's error measured and "
                                      "reported; true: held to rtol and atol too, at the cost of more steps)")
PHASE = Field(float, default=0.0, unit="rad", check=finite,
              doc="model = 'auto': the fast phase at which a switch up the ladder lifts the slow variables")

BODY = Table({
    "moments": Field(Vector(3), doc="principal moments A1, A2, A3", unit="kg m^2", check=all_finite),
    "inertia": Field(Matrix(3, 3), doc="instead of moments: the inertia tensor in the scene's body frame (rows; "
                                       "symmetric, products of inertia off the diagonal); the run happens in its "
                                       "principal axes, states and body-axes torque parameters stay in this frame",
                     unit="kg m^2", check=all_finite),
    "rotor": Field(Vector(3), default=[0.0, 0.0, 0.0], doc="gyrostatic momentum k of the rotors",
                   unit="kg m^2/s", check=all_finite),
}, one_of=[("moments", "inertia")])



SPLITTING_FIELDS = {
    "step": Field(float, doc="fixed step of method 'splitting' (left out: chosen from rtol by the splitting's own "
                        "error estimate)", unit="s", check=[positive, engine_rule("step")]),
    "splitting_order": engine_option("splitting_order", int, "order of the splitting composition: 2, 4 or 6"),
}



def integration_table(model: Field | None = None, *, rtol: Field = RTOL, atol: Field = ATOL, n_out: Field = N_OUT,
                      max_steps: bool = False, splitting: bool = False, required: bool = True, doc: str = "the run",
                      **own: Field) -> Field:
    """A kind's [integration] table, written once: ``model`` (a kind with a model ladder: its
    choices, with ``phase``), ``accuracy`` (every kind: the contract of :mod:`gyrostat.accuracy`),
    ``method``, ``rtol``, ``atol`` (a family's own defaults given as fields), the kind's ``own``
    fields in order (``t_span``, ``tau_end``, ...), ``n_out``, then ``max_steps`` and the splitting's
    fields where the kind offers them."""
    fields = {"model": model} if model is not None else {}
    fields["accuracy"] = ACCURACY
    if model is not None:
        fields["phase"] = PHASE
    fields.update(method=METHOD, rtol=rtol, atol=atol, **own, n_out=n_out, sensitivities=SENSITIVITIES,
                  sensitivity_error_control=SENSITIVITY_ERROR_CONTROL)
    if max_steps:
        fields["max_steps"] = MAX_STEPS
    if splitting:
        fields.update(SPLITTING_FIELDS)
    return Field(Table(fields), required=required, doc=doc) if required else Field(Table(fields), default={}, doc=doc)


def outputs_field(plots: tuple[str, ...], default: list[str], **extra: Field) -> Field:
    """The [outputs] table of a kind: the plots it can draw (and what else it takes)."""
    return Field(Table({"plots": Field(ListOf(str, choices=plots), default=default, doc="plots to draw"), **extra}),
                 default={}, doc="what to draw")


def build(where: str, make, *args):
    """A core object from validated values; its own ValueError becomes a SceneError naming the table."""
    try:
        return make(*args)
    except ValueError as error:
        raise SceneError(f"[{where}] {error}") from None


_reuse = threading.local()


@contextlib.contextmanager
def reusing(document: dict):
    """Within it (on this thread), :func:`make_body` and :func:`make_torques` build ``document``'s
    own [body] table and [[torques]] entries once, and return those objects for any document that
    holds these very tables (the same objects, not equal copies). A sweep's members are such
    documents: :meth:`gyrostat.sweeps.Plan.document` copies only the tables a parameter changes,
    so the others are built once per chunk instead of once per member (the body and the torques
    are immutable core objects, which models copy)."""
    previous = getattr(_reuse, "built", None)
    sections = [document.get("body"), *document.get("torques", [])]
    _reuse.built = {id(section): [section, None] for section in sections if section is not None}
    try:
        yield
    finally:
        _reuse.built = previous


def _reused(section, make):
    """``make()``, or the object made before for this very ``section`` inside :func:`reusing`."""
    built = getattr(_reuse, "built", None)
    entry = built.get(id(section)) if built else None
    if entry is None or entry[0] is not section:
        return make()
    if entry[1] is None:
        entry[1] = make()
    return entry[1]


def make_body(doc: dict) -> _core.Body:
    """The scene's [body] as a :class:`gyrostat.Body`."""
    body = doc["body"]
    if "inertia" in body:
        return _reused(body, lambda: build("body", lambda: _core.Body(rotor=body["rotor"], inertia=body["inertia"])))
    return _reused(body, lambda: build("body", _core.Body, body["moments"], body["rotor"]))


def make_torques(doc: dict) -> list:
    """The scene's [[torques]], each built by its core class (:func:`gyrostat.torques.build`)."""
    return [_reused(spec, lambda: build(f"torques[{i}]", _torques.build, spec))
            for i, spec in enumerate(doc.get("torques", []))]


def integration(doc: dict, kind: Kind, **extra) -> dict:
    """The integrator options of a scene of ``kind`` from its [integration] table (and ``extra``)."""
    integ = doc["integration"]
    options = {"method": integ["method"], "rtol": integ["rtol"], "atol": integ["atol"], "n_out": integ["n_out"]}
    if "max_steps" in integ:
        options["max_steps"] = integ["max_steps"]
    if integ["method"] == "splitting":
        if not kind.splits:
            splits = ", ".join(name for name, k in KINDS.items() if k.splits)
            raise SceneError(f"[integration] method = 'splitting' is not offered for {kind.name} scenes (their models "
                             f"do not split into the free-body flow and a perturbation; it is for {splits})")
        options.update(step=integ.get("step"), splitting_order=integ.get("splitting_order", _DEFAULT.splitting_order))
    if integ.get("sensitivities"):
        options["sensitivities"] = list(integ["sensitivities"])
        options["sensitivity_error_control"] = integ["sensitivity_error_control"]
        if options["method"] == "auto":
            options["method"] = "dop853"
    if integ.get("accuracy") is not None:
        options["accuracy"] = integ["accuracy"]
        if isinstance(integ["rtol"], Unstated) and isinstance(integ["atol"], Unstated) and not integ.get("step"):
            del options["rtol"], options["atol"]
    options.update(extra)
    return options
