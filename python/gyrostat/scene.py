"""Scenes: a body, its torques, an initial state, a horizon, an integrator and outputs, as TOML.

One pipeline for every model family: the top-level key ``kind`` picks a scene kind from
:data:`KINDS` (the registry the family modules fill: :mod:`gyrostat.families`; ``rigid_body``
when absent), each kind declares its strict schema
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

import tomllib
from collections.abc import Iterable
from dataclasses import dataclass, field
from pathlib import Path

from gyrostat.events import Event
from gyrostat.families import KINDS, default_kind
from gyrostat.kind import Kind, Run, build
from gyrostat.scene_code import Allowance, CodeName, allowing, module_names, stand_ins
from gyrostat.schema import Common, SceneError, describe, describe_common, validate
from gyrostat.solve import check_run

__all__ = ["Scene", "Run", "SceneError", "KINDS", "SCENES", "load", "scene_format"]


def add_events(doc: dict, runs: list[Run]) -> None:
    """The scene's [[events]] to every run whose model has the quantity (one that none has is an error)."""
    for i, spec in enumerate(doc["events"]):
        event = build(f"events[{i}]", Event, spec["quantity"], spec["value"], spec["direction"], spec["terminal"],
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
    """A validated scene: its kind, its document (defaults filled in) and its runs.

    Made by :func:`load` (a TOML file) or :meth:`from_dict`; :func:`gyrostat.runner.solve_scene`
    solves it, ``gyrostat run`` solves it and writes its outputs.

    Parameters
    ----------
    name : str
        Its name (the file's stem).
    kind : gyrostat.kind.Kind
        The scene kind (the top-level key ``kind``).
    doc : dict
        The validated document, defaults filled in.
    runs : list of gyrostat.kind.Run
        What is solved: model, initial state, span (s) and options of each run.
    model_choice, model_reason : str
        The model chosen (``model = "auto"``: by the ladder, when solved) and why.
    ladder : list, optional
        With ``model = "auto"``: the kind's rungs (:mod:`gyrostat.ladder`).

    Examples
    --------
    >>> from gyrostat.scene import Scene
    >>> scene = Scene.from_dict({"title": "Damper", "body": {"moments": [12.0, 12.0, 4.0]},
    ...                          "torques": [{"type": "viscous_cavity", "density": 970.0, "viscosity": 2.0,
    ...                                       "radius": 0.25}],
    ...                          "initial": {"omega": [0.05, 0.0, 2.0]},
    ...                          "integration": {"model": "full", "t_span": [0.0, 3600.0]}}, name="satellite")
    >>> [run.name for run in scene.runs], scene.runs[0].t_span
    (['full'], (0.0, 3600.0))

    The examples of its attributes use this ``scene``.
    """

    name: str
    kind: Kind
    doc: dict
    runs: list[Run] = field(default_factory=list)
    model_choice: str = ""
    model_reason: str = ""
    ladder: list | None = None

    @property
    def title(self) -> str:
        """Its ``title``, or its name when it has none.

        Examples
        --------
        >>> scene.title
        'Damper'
        """
        return self.doc["title"] or self.name

    @property
    def description(self) -> str:
        """Its ``description`` (empty when it has none).

        Examples
        --------
        >>> scene.description
        ''
        """
        return self.doc["description"]

    @property
    def plots(self) -> list[str]:
        """The plots its ``[outputs]`` asks for (the kind's defaults when it names none).

        Examples
        --------
        >>> scene.plots
        ['omega', 'invariants']
        """
        return list(self.doc["outputs"]["plots"])

    @classmethod
    def from_dict(cls, data: dict, name: str = "scene", *, allow_import: Iterable[str] | str | None = None,
                  folder: str | Path | None = None) -> "Scene":
        """A scene from its document (a dict as TOML gives it); every problem is a one-line
        :class:`SceneError` naming the key.

        A scene that names code (a ``type = "custom"`` torque) is checked whole first, its code
        neither imported nor called (:mod:`gyrostat.scene_code`); only then are its modules
        imported and its factories called.

        Parameters
        ----------
        data : dict
            The document.
        name : str, optional
            Its name (default "scene").
        allow_import : str or list of str, optional
            Modules (packages) whose code the scene may name, each with the modules below it.
        folder : str or pathlib.Path, optional
            The scene's folder: the modules in it and below it may be named (:meth:`from_file`
            gives the file's folder).

        Examples
        --------
        >>> scene.kind.name
        'rigid_body'
        >>> Scene.from_dict({"body": {}})
        Traceback (most recent call last):
        ...
        gyrostat.schema.SceneError: [body] needs exactly one of 'moments', 'inertia' or 'inertia_ratios'; none is given
        """
        scene = cls.checked(data, name, allow_import=allow_import, folder=folder)
        if not scene.names_code:
            return scene
        return cls._built(scene.name, scene.kind, scene.doc)  # checked whole: now its code runs

    @classmethod
    def checked(cls, data: dict, name: str = "scene", *, allow_import: Iterable[str] | str | None = None,
                folder: str | Path | None = None) -> "Scene":
        """The scene checked as :meth:`from_dict` checks it, without importing or calling any code it
        names: its user torques are stand-ins that refuse to run (``gyrostat check``).

        Parameters
        ----------
        data, name, allow_import, folder
            As in :meth:`from_dict`.

        Examples
        --------
        >>> from gyrostat.schema import SceneError
        >>> doc = {"body": {"moments": [1, 2, 3]}, "initial": {"omega": [1, 0, 0]},
        ...        "integration": {"model": "full", "t_span": [0.0, 1.0]},
        ...        "torques": [{"type": "custom", "function": "os:system"}]}
        >>> try:
        ...     Scene.checked(doc)
        ... except SceneError as error:
        ...     print(str(error)[:76])
        scene 'scene': [torques[0]] function = 'os:system' names code in module 'os'
        >>> Scene.checked(doc, allow_import=["os"]).names_code   # allowed, and still not imported
        True
        """
        if not isinstance(data, dict):
            raise SceneError(f"a scene is a table of keys, got {type(data).__name__}")
        kind_name = data.get("kind", default_kind())
        if kind_name not in KINDS:
            import difflib

            close = difflib.get_close_matches(str(kind_name), list(KINDS), n=1, cutoff=0.6)
            raise SceneError(f"kind = {kind_name!r} is not a scene kind ({', '.join(KINDS)})"
                             + (f"; did you mean {close[0]!r}?" if close else ""))
        kind = KINDS[kind_name]
        try:
            allowance = Allowance(name, str(Path(folder).resolve()) if folder is not None else None,
                                  module_names(allow_import))
        except ValueError as error:
            raise SceneError(str(error)) from None
        with allowing(allowance):
            doc = validate(kind.schema, data)
        if not holds_code(doc):
            return cls._built(name, kind, doc)
        with stand_ins():
            return cls._built(name, kind, doc)

    @classmethod
    def _built(cls, name: str, kind: Kind, doc: dict) -> "Scene":
        """The scene of a validated document: its runs, checked (tolerances, outputs, events)."""
        runs, choice, reason = kind.runs(doc)
        for run in runs:  # tolerances, outputs and their memory: refused now, naming the key, not once running
            build("integration", check_run, run.model, run.t_span, run.options)
        add_events(doc, runs)
        rungs = kind.ladder(doc) if doc.get("integration", {}).get("model") == "auto" else None
        return cls(name=name, kind=kind, doc=doc, runs=runs, model_choice=choice, model_reason=reason, ladder=rungs)

    @property
    def names_code(self) -> bool:
        """Whether the scene names code (a user torque's function) that building it imports and calls.

        Examples
        --------
        >>> scene.names_code
        False
        """
        return holds_code(self.doc)

    @classmethod
    def from_file(cls, path: str | Path, *, allow_import: Iterable[str] | str | None = None,
                  check_only: bool = False) -> "Scene":
        """A scene from its TOML file (:func:`load`): the modules in the file's folder (and below
        it) and those in ``allow_import`` may be named by its user torques.

        Parameters
        ----------
        path : str or pathlib.Path
            The file.
        allow_import : str or list of str, optional
            Modules (packages) the scene may name code in, besides its folder's.
        check_only : bool, optional
            Check it without importing or calling its code (:meth:`checked`).

        Examples
        --------
        >>> from gyrostat.scene import SCENES, Scene
        >>> Scene.from_file(SCENES / "forced_damped.toml").name
        'forced_damped'
        """
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
        make = cls.checked if check_only else cls.from_dict
        return make(data, name=path.stem, allow_import=allow_import, folder=path.resolve().parent)

    @classmethod
    def from_toml(cls, path: str | Path, *, allow_import: Iterable[str] | str | None = None) -> "Scene":
        """:meth:`from_file` (its older name).

        Parameters
        ----------
        path, allow_import
            As in :meth:`from_file`.

        Examples
        --------
        >>> from gyrostat.scene import SCENES, Scene
        >>> Scene.from_toml(SCENES / "forced_damped.toml").name
        'forced_damped'
        """
        return cls.from_file(path, allow_import=allow_import)


def holds_code(doc) -> bool:
    """Whether a validated document holds a name of code (:class:`gyrostat.scene_code.CodeName`)."""
    if isinstance(doc, CodeName):
        return True
    if isinstance(doc, dict):
        return any(holds_code(value) for value in doc.values())
    if isinstance(doc, (list, tuple)):
        return any(holds_code(value) for value in doc)
    return False


SCENES = Path(__file__).resolve().parent / "scenes"
"""The folder of the scenes shipped with the package (``gyrostat examples`` runs them)."""


def load(path: str | Path, *, allow_import: Iterable[str] | str | None = None) -> Scene:
    """Reads and validates a scene file; every problem is a one-line :class:`SceneError`.

    Parameters
    ----------
    path : str or pathlib.Path
        The TOML file.
    allow_import : str or list of str, optional
        Modules (packages) whose code the scene may name besides its folder's (:mod:`gyrostat.scene_code`).

    Examples
    --------
    >>> from gyrostat.scene import SCENES, load
    >>> load(SCENES / "forced_damped.toml").title
    'Damped body under a constant body-fixed torque'
    """
    return Scene.from_file(path, allow_import=allow_import)


def scene_format() -> str:
    """The reference of every scene kind (Markdown), from the schemas themselves: what several
    kinds share (events, sweeps, torques, the common integration keys) once, then each kind.
    ``gyrostat scene-format`` prints it; docs/scenes.md is it.

    Examples
    --------
    >>> from gyrostat.scene import scene_format
    >>> scene_format().splitlines()[0]
    '# Scene files'
    """
    common = Common(kind.schema for kind in KINDS.values())
    parts = ["# Scene files\n", f"The top-level key `kind` selects one of the kinds below (`{default_kind()}` when absent).\n"]
    for kind in KINDS.values():
        parts.append(f"\n## kind = \"{kind.name}\"\n\n{kind.doc}\n\nPlots: {', '.join(kind.plots)}.\n")
        parts.append(describe(kind.schema, title=f"{kind.name}: top level", common=common))
    parts.append("\n" + describe_common(common))
    return "\n".join(parts)
