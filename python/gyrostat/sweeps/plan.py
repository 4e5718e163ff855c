"""What a sweep solves: :class:`Plan` (the scene validated, ``model = "auto"`` resolved once,
the run swept, the parameters and how member i gets its values and its run). Pure data, so that
a chunk solves the same members in this process, in a worker process or on a Dask worker."""

from __future__ import annotations

import copy
from collections.abc import Iterable, Mapping, Sequence
from pathlib import Path

import numpy as np

from gyrostat import _core
from gyrostat.events import labels
from gyrostat.schema import locate
from gyrostat.sweeps.draws import _member_generators
from gyrostat.sweeps.parameters import _assign, _assign_fields, _entry, _parameters, _write_tree, parse_path


def _scene(scene, allow_import=None):
    from gyrostat.scene import Scene

    if isinstance(scene, Scene):
        return scene
    if isinstance(scene, (str, Path)):
        return Scene.from_file(scene, allow_import=allow_import)
    if isinstance(scene, Mapping):
        return Scene.from_dict(dict(scene), allow_import=allow_import)
    raise TypeError(f"scene must be a gyrostat Scene, a scene file or a dict, not {type(scene).__name__}")


class Plan:
    """What a sweep solves: the scene (validated, with ``model = "auto"`` resolved), the run it
    sweeps, the parameters and how member i gets its values. Pure data, so that a chunk solves
    the same members in this process or on a Dask worker.

    Parameters
    ----------
    scene : str, pathlib.Path, dict or gyrostat.scene.Scene
        The scene.
    vary : dict or list of Parameter
        As in :func:`sweep`.
    samples : int, optional
        Members of a dispersion.
    seed : int, optional
        Seed of a dispersion (default: a fresh one, kept in ``seed``).
    run : str, optional
        The scene's run to sweep.
    allow_import : str or list of str, optional
        Modules whose code a scene file or document may name (:meth:`gyrostat.scene.Scene.from_file`);
        the members' user torques are built under the same allowance, on every worker.

    Examples
    --------
    >>> from gyrostat import sweeps
    >>> scene = {"body": {"moments": [2.0, 2.0, 1.0]},
    ...          "torques": [{"type": "linear_damping", "diagonal": [0.1, 0.1, 0.1]}],
    ...          "initial": {"omega": [0.1, 0.0, 1.0]},
    ...          "integration": {"model": "full", "t_span": [0.0, 10.0], "n_out": 11}}
    >>> plan = sweeps.Plan(scene, {"torques[0].diagonal[2]": [0.1, 0.2]})
    >>> plan.size, plan.mode, plan.run
    (2, 'grid', 'full')

    The examples of its attributes use this ``plan``.
    """

    def __init__(self, scene, vary, *, samples: int | None = None, seed: int | None = None, run: str | None = None,
                 allow_import: Iterable[str] | str | None = None):
        scene = _scene(scene, allow_import)
        self.scene_name, self.kind_name = scene.name, scene.kind.name
        doc = copy.deepcopy(scene.doc)
        integration = doc.get("integration", {})
        self.model_choice, self.model_reason = scene.model_choice, scene.model_reason
        if scene.ladder is not None:  # the ladder chooses once, on the scene as written
            from gyrostat import ladder
            from gyrostat.scene import Scene

            template = scene.runs[0]
            choice = ladder.choose(scene.ladder, template.t_span, template.options, integration.get("accuracy") or ladder.ACCURACY)
            integration["model"] = choice.chosen.name
            scene = Scene.from_dict(copy.deepcopy(doc), scene.name)
            self.model_choice, self.model_reason = choice.chosen.name, "the model ladder: " + choice.summary
        elif integration.get("model") == "auto":
            integration["model"] = scene.model_choice
        self.base = doc
        names = [r.name for r in scene.runs]
        if run is None:
            run = names[0] if len(names) == 1 else "full" if "full" in names else None
            if run is None:
                raise ValueError(f"the scene has runs {names}: choose one with run= (on the command line: --run NAME)")
        elif run not in names:
            raise ValueError(f"run = {run!r} is not a run of the scene ({', '.join(names)})")
        self.run = run
        base = next(r for r in scene.runs if r.name == run)
        self.state_names = tuple(base.model.state_names)
        self.output_names = tuple(base.model.output_names)
        self.units = base.model.units  # as the C++ model declares them
        self.event_labels = tuple(labels(base.options.get("events", ())))
        self.sensitivities = tuple(base.options.get("sensitivities") or ())  # each member's d(final)/d(name)
        self.n_out = int(base.options.get("n_out", _core.Options().n_out))
        self.parameters = _parameters(vary)
        self._targets()  # every path checked now, before any member runs
        grid = [p.values is not None for p in self.parameters]
        if all(grid):
            if samples is not None:
                raise ValueError("samples= is for dispersions; a grid's size is the product of its value lists")
            self.mode, self.shape = "grid", tuple(len(p.values) for p in self.parameters)
            self.seed = None
        elif not any(grid):
            if isinstance(samples, bool) or not isinstance(samples, (int, np.integer)) or samples < 1:
                raise ValueError(f"a dispersion needs samples = the number of members (a positive integer), "
                                 f"got {samples!r}")
            if seed is None:
                seed = int(np.random.SeedSequence().entropy % 2**63)
            if isinstance(seed, bool) or not isinstance(seed, (int, np.integer)) or seed < 0:
                raise ValueError(f"seed = {seed!r} must be a non-negative integer")
            self.mode, self.shape, self.seed = "dispersion", (int(samples),), int(seed)
        else:
            raise ValueError("vary mixes grid values and distributions: give all as value lists (a grid) or all as "
                             "distributions (a dispersion)")
        self.size = int(np.prod(self.shape))

    # -- paths
    def _targets(self):
        from gyrostat.families import KINDS

        schema, targets = KINDS[self.kind_name].schema, []
        for parameter in self.parameters:
            for text in parameter.paths:
                parts = parse_path(text)
                located = locate(schema, self.base, parts, self.scene_name)
                value = self.base
                for part in located.field_parts:
                    value = value[part]
                _entry(value, located.inner, text)
                if located.field_parts[-1] == "n_out" and located.field_parts[0] == "integration":
                    self.varies_n_out = True
                targets.append((parameter, parts, located))
        return targets

    def __getstate__(self):
        return {k: v for k, v in self.__dict__.items() if k not in ("_located", "_made_writes", "_fields")}

    @property
    def located(self):
        """Each parameter's paths, parsed and located in the scene's schema (made once).

        Examples
        --------
        >>> plan.located[0][1]
        ('torques', 0, 'diagonal', 2)
        """
        try:
            return self._located
        except AttributeError:
            self._located = self._targets()
            return self._located

    # -- members
    def values(self, i: int) -> tuple[float, ...]:
        """Member i's parameter values (grid: row-major over the parameters; dispersion: drawn
        from the member's own stream), in the units of the entries they set.

        Parameters
        ----------
        i : int
            The member, 0 ≤ i < ``size``.

        Examples
        --------
        >>> plan.values(1)
        (0.2,)
        """
        if not 0 <= i < self.size:
            raise IndexError(f"member {i} of a sweep of {self.size}")
        return self.values_range(i, i + 1)[0]

    def values_range(self, start: int, stop: int) -> list[tuple[float, ...]]:
        """:meth:`values` of members ``start`` … ``stop - 1``, made together (a dispersion's
        streams are computed for the whole range at once: the same numbers).

        Parameters
        ----------
        start, stop : int
            The members, ``range(start, stop)``.

        Examples
        --------
        >>> plan.values_range(0, 2)
        [(0.1,), (0.2,)]
        """
        if not 0 <= start <= stop <= self.size:
            raise IndexError(f"members {start} … {stop - 1} of a sweep of {self.size}")
        if self.mode == "grid":
            return [tuple(p.values[k] for p, k in zip(self.parameters, np.unravel_index(i, self.shape)))
                    for i in range(start, stop)]
        return [tuple(p.distribution.draw(rng) for p in self.parameters)
                for rng in _member_generators(self.seed, start, stop)]

    def document(self, values: Sequence[float]) -> dict:
        """The scene document with ``values`` set, each changed key checked as in a scene file.

        Parameters
        ----------
        values : sequence of float
            One value per parameter.

        Examples
        --------
        >>> plan.document([0.2])["torques"][0]["diagonal"]
        [0.1, 0.1, 0.2]
        """
        updates = []
        for located, raw, writes in self._writes:  # each changed field: its numbers set, then validated
            alone = True
            for k, scale, inner in writes:
                number = scale * values[k]
                raw = _assign(raw, inner, number) if inner else number
                alone = alone and located.accepts_number(number)
            # a valid value with numbers set that pass the field's elementwise checks each is valid
            # (schema.Located.accepts_number): ~1 us instead of ~9 for a vector
            updates.append(raw if alone else located.validate(raw))
        return _assign_fields(self.base, self._fields, updates)

    @property
    def _writes(self) -> list[tuple]:
        """What :meth:`document` writes, made once: per changed field, where it is located, its
        value in the scene and the numbers set inside it, (parameter index, scale, indices inside
        the value), in the order of the paths."""
        try:
            return self._made_writes
        except AttributeError:
            index = {id(parameter): k for k, parameter in enumerate(self.parameters)}
            fields: dict[tuple, tuple] = {}
            for parameter, parts, located in self.located:
                if located.field_parts not in fields:
                    value = self.base
                    for part in located.field_parts:
                        value = value[part]
                    fields[located.field_parts] = (located, value, [])
                fields[located.field_parts][2].append((index[id(parameter)], parameter.scale, located.inner))
            self._fields = _write_tree(list(fields))
            self._made_writes = list(fields.values())
            return self._made_writes

    def member(self, values: Sequence[float]):
        """The run (model, initial state, span, options) of the member with these values; raises
        SceneError or ValueError naming the value when the physics refuses it.

        Parameters
        ----------
        values : sequence of float
            One value per parameter, as :meth:`values` gives them.

        Returns
        -------
        gyrostat.kind.Run
            The run the sweep solves for this member.

        Examples
        --------
        >>> plan.member([0.2]).model
        Model(Body(A1=2, A2=2, A3=1, k=[0, 0, 0]), torques=[LinearDamping(matrix=[[0.1, 0, 0], [0, 0.1, 0], [0, 0, 0.2]])], attitude=False)
        """
        from gyrostat.families import KINDS
        from gyrostat.scene import add_events

        doc = self.document(values)
        runs, _, _ = KINDS[self.kind_name].runs(doc)
        add_events(doc, runs)
        return next(r for r in runs if r.name == self.run)

    def scene(self, i: int):
        """Member i as a whole validated :class:`gyrostat.scene.Scene` (to rerun it alone).

        Parameters
        ----------
        i : int
            The member.

        Examples
        --------
        >>> plan.scene(1).name
        'scene_member1'
        """
        from gyrostat.scene import Scene

        return Scene.from_dict(self.document(self.values(i)), name=f"{self.scene_name}_member{i}")

    @property
    def names(self) -> tuple[str, ...]:
        """The swept run's state components and outputs.

        Examples
        --------
        >>> plan.names
        ('p', 'q', 'r', 'angular_momentum_norm', 'kinetic_energy', 'nutation_angle')
        """
        return self.state_names + self.output_names

    def describe(self) -> dict:
        """The plan as recorded in the Dataset's ``attrs["plan"]``.

        Examples
        --------
        >>> plan.describe()["shape"], plan.describe()["parameters"][0]["values"]
        ([2], [0.1, 0.2])
        """
        return {"scene": self.scene_name, "kind": self.kind_name, "run": self.run, "mode": self.mode,
                "shape": list(self.shape), "seed": self.seed, "parameters": [p.describe() for p in self.parameters]}
