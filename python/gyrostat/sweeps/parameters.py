"""What a sweep varies: paths in a scene document (``torques[1].viscosity``,
``body.moments[0:2]``), parsed, checked against the value they select and written into a copy of
the document; :class:`Parameter` (a name, the paths it sets, grid values or a distribution, a
scale) and its makers from a scene's ``[[sweep.vary]]`` table and from the command line."""

from __future__ import annotations

import re
from collections.abc import Mapping, Sequence
from dataclasses import dataclass

import numpy as np

from gyrostat.arguments import shown
from gyrostat.schema import SceneError
from gyrostat.sweeps.draws import DISTRIBUTIONS, Distribution, LogUniform, Normal, Uniform, _number


# ------------------------------------------------------------------------------------ paths
_SEGMENT = re.compile(r"([A-Za-z_][A-Za-z0-9_]*)((?:\[[^\]]*\])*)")
_INDEX = re.compile(r"\[\s*(-?\d+)\s*(?::\s*(-?\d+)\s*)?\]")


def parse_path(text: str) -> tuple:
    """``"torques[1].viscosity"`` → ``("torques", 1, "viscosity")``; a slice ``[0:2]`` only last."""
    if not isinstance(text, str) or not text.strip():
        raise SceneError(f"vary: {text!r} is not a path such as 'body.moments[0]' or 'torques[1].viscosity'")
    parts: list = []
    for segment in text.strip().split("."):
        match = _SEGMENT.fullmatch(segment.strip())
        if not match:
            raise SceneError(f"vary: {text!r} is not a path such as 'body.moments[0]' or 'torques[1].viscosity'")
        parts.append(match.group(1))
        brackets = match.group(2)
        indices = list(_INDEX.finditer(brackets))
        if "".join(m.group(0) for m in indices) != brackets:
            raise SceneError(f"vary: {text!r}: an index is a whole number or a slice such as [0:2]")
        for m in indices:
            parts.append(int(m.group(1)) if m.group(2) is None else slice(int(m.group(1)), int(m.group(2))))
    if any(isinstance(p, slice) for p in parts[:-1]):
        raise SceneError(f"vary: {text!r}: a slice may only end the path")
    return tuple(parts)


def _entry(value, inner: tuple, text: str) -> list:
    """The numbers a path's inner indices select inside a field's value (checked): one number, or
    the entries of a slice; a whole list is refused (a sweep sets one number per path)."""
    sliced = False
    for i, part in enumerate(inner):
        if isinstance(part, str):  # a key of a table inside a value (a law given as a table)
            if not isinstance(value, dict) or part not in value:
                raise SceneError(f"vary: {text!r}: no key {part!r} there"
                                 + (f" (keys: {', '.join(value)})" if isinstance(value, dict) else ""))
            value = value[part]
            continue
        if not isinstance(value, list):
            raise SceneError(f"vary: {text!r}: the value has no entries to index")
        if isinstance(part, slice):
            chosen = range(*part.indices(len(value)))
            if part.start < 0 or part.stop > len(value) or not chosen:
                raise SceneError(f"vary: {text!r}: the slice is outside the {len(value)} entries")
            value, sliced = [value[k] for k in chosen], True
            break
        if not -len(value) <= part < len(value):
            raise SceneError(f"vary: {text!r}: index {part} is outside the {len(value)} entries")
        value = value[part]
    if isinstance(value, list) and not sliced:
        raise SceneError(f"vary: {text!r} is a list ({shown(value)}): a sweep sets one number per path; vary one "
                         f"entry ({text}[0]) or a slice of them ({text}[0:{len(value)}])")
    numbers = value if isinstance(value, list) else [value]
    if not all(isinstance(x, (int, float)) and not isinstance(x, bool) for x in numbers):
        raise SceneError(f"vary: {text!r} is {value!r}, not a number")
    return numbers


def _assign(container, parts: tuple, value):
    """A copy of ``container`` with the entry at ``parts`` set (only the containers on the path
    are copied)."""
    head, rest = parts[0], parts[1:]
    copied = dict(container) if isinstance(container, dict) else list(container)
    if rest:
        copied[head] = _assign(container[head], rest, value)
    elif isinstance(head, slice):
        for k in range(*head.indices(len(copied))):
            copied[k] = value
    else:
        copied[head] = value
    return copied


def _write_tree(paths: list[tuple]) -> dict:
    """The paths as a tree, {key: subtree}, a leaf being the index of the path in ``paths``."""
    tree: dict = {}
    for n, parts in enumerate(paths):
        node = tree
        for part in parts[:-1]:
            node = node.setdefault(part, {})
        node[parts[-1]] = n
    return tree


def _assign_fields(container, tree: dict, values: list):
    """A copy of ``container`` with the value of each leaf of ``tree`` (:func:`_write_tree`) set:
    every container on the paths copied once, the others shared."""
    copied = dict(container) if isinstance(container, dict) else list(container)
    for key, node in tree.items():
        copied[key] = values[node] if isinstance(node, int) else _assign_fields(container[key], node, values)
    return copied


# ------------------------------------------------------------------------------------ parameters
_NAME = re.compile(r"[A-Za-z_][^\s/]*")


@dataclass(frozen=True)
class Parameter:
    """A varied parameter of a sweep: its name (a coordinate of the Dataset), the scene paths it
    sets (each to ``scale * value``), and either grid ``values`` or a ``distribution``.

    Parameters
    ----------
    name : str
        The coordinate's name (no spaces or '/').
    paths : str or sequence of str
        Scene paths it sets (``"torques[0].p0"``, ``"body.moments[0:2]"``).
    values : sequence of float, optional
        Grid values, in the unit of the entries it sets (divided by ``scale``).
    distribution : Uniform, Normal or LogUniform, optional
        A dispersion instead of a grid.
    scale : float, optional
        Each path is set to ``scale * value`` (default 1).
    label : str, optional
        Text for plots and tables (default: the name).

    Examples
    --------
    >>> import gyrostat
    >>> gyrostat.Parameter("A", ["body.moments[0]", "body.moments[1]"], values=[3.0, 4.0]).describe()["paths"]
    ['body.moments[0]', 'body.moments[1]']
    """

    name: str
    paths: tuple[str, ...]
    values: tuple[float, ...] | None = None
    distribution: Distribution | None = None
    scale: float = 1.0
    label: str = ""

    def __post_init__(self):
        if not isinstance(self.name, str) or not _NAME.fullmatch(self.name):
            raise ValueError(f"parameter name {self.name!r} must start with a letter or '_' and hold no spaces or '/'"
                             " (it names a NetCDF variable; use label= for text such as 'A/C')")
        paths = (self.paths,) if isinstance(self.paths, str) else tuple(self.paths)
        if not paths:
            raise ValueError(f"parameter {self.name!r} sets no path")
        object.__setattr__(self, "paths", paths)
        _number(self.scale, f"parameter {self.name!r}: scale")
        if (self.values is None) == (self.distribution is None):
            raise ValueError(f"parameter {self.name!r}: give values (a grid) or a distribution, not "
                             + ("both" if self.values is not None else "neither"))
        if self.values is not None:
            values = np.asarray(self.values, dtype=float).ravel() if not isinstance(self.values, (str, bytes)) \
                else np.array([np.nan])
            if values.size == 0 or not np.all(np.isfinite(values)):
                raise ValueError(f"parameter {self.name!r}: values must be finite numbers, got {self.values!r}")
            object.__setattr__(self, "values", tuple(float(v) for v in values))
        elif not isinstance(self.distribution, (Uniform, Normal, LogUniform)):
            raise ValueError(f"parameter {self.name!r}: distribution must be gyrostat.Uniform, Normal or LogUniform, "
                             f"not {self.distribution!r}")

    def describe(self) -> dict:
        """What the parameter is, as recorded in a sweep's ``attrs["plan"]``.

        Examples
        --------
        >>> import gyrostat
        >>> gyrostat.Parameter("fill", "torques[0].p0", values=[1.0, 2.0], scale=1e-4).describe()
        {'name': 'fill', 'label': 'fill', 'paths': ['torques[0].p0'], 'scale': 0.0001, 'values': [1.0, 2.0]}
        """
        spec = {"values": list(self.values)} if self.values is not None else {
            "distribution": type(self.distribution).__name__, **self.distribution.__dict__}
        return {"name": self.name, "label": self.label or self.name, "paths": list(self.paths), "scale": self.scale,
                **spec}


def parameter_from_table(spec: Mapping, where: str = "[sweep.vary]") -> Parameter:
    """A :class:`Parameter` from a scene's validated ``[[sweep.vary]]`` table.

    Parameters
    ----------
    spec : mapping
        The table (path or paths; values, or start, stop, num and spacing; or a distribution).
    where : str, optional
        How an error names the table.

    Examples
    --------
    >>> from gyrostat import sweeps
    >>> sweeps.parameter_from_table({"path": "body.moments[0:2]", "start": 1.0, "stop": 3.0, "num": 3,
    ...                              "spacing": "linear", "scale": 1.0, "label": ""}).values
    (1.0, 2.0, 3.0)
    """
    paths = [spec["path"]] if "path" in spec else list(spec["paths"])
    grid_keys = [k for k in ("values", "start", "stop", "num") if k in spec]
    spread_keys = [k for k in ("distribution", "low", "high", "mean", "std") if k in spec]
    try:
        if grid_keys and spread_keys:
            raise ValueError(f"give a grid ({', '.join(grid_keys)}) or a distribution ({', '.join(spread_keys)}), "
                             "not both")
        if "values" in spec:
            if any(k in spec for k in ("start", "stop", "num")):
                raise ValueError("give values, or start, stop and num, not both")
            given = {"values": spec["values"]}
        elif grid_keys:
            missing = [k for k in ("start", "stop", "num") if k not in spec]
            if missing:
                raise ValueError(f"a grid from start to stop needs {', '.join(missing)}")
            if spec["spacing"] == "log" and not (spec["start"] > 0 and spec["stop"] > 0):
                raise ValueError(f"a log grid needs start > 0 and stop > 0, got {spec['start']!r}, {spec['stop']!r}")
            space = np.geomspace if spec["spacing"] == "log" else np.linspace
            given = {"values": space(spec["start"], spec["stop"], spec["num"])}
        elif "distribution" in spec:
            kind = spec["distribution"]
            needs = ("mean", "std") if kind == "normal" else ("low", "high")
            missing = [k for k in needs if k not in spec]
            extra = [k for k in ("low", "high", "mean", "std") if k in spec and k not in needs]
            if missing or extra:
                raise ValueError(f"distribution = '{kind}' takes {' and '.join(needs)}"
                                 + (f"; missing {', '.join(missing)}" if missing else "")
                                 + (f"; not {', '.join(extra)}" if extra else ""))
            given = {"distribution": DISTRIBUTIONS[kind](*(spec[k] for k in needs))}
        else:
            raise ValueError("needs values, start/stop/num, or a distribution")
        return Parameter(spec.get("name", paths[0]), tuple(paths), scale=spec["scale"], label=spec["label"], **given)
    except ValueError as error:
        raise SceneError(f"{where} {error}") from None


_GRID_TEXT = re.compile(r"\s*([^:]+):([^:]+):(\d+)(?::(lin|log))?\s*")
_DISTRIBUTION_TEXT = re.compile(r"\s*(uniform|normal|loguniform)\s*\(([^,]+),([^)]+)\)\s*", re.IGNORECASE)


def parameter_from_text(text: str) -> Parameter:
    """A parameter from the command line: ``PATH=START:STOP:NUM[:log]``, ``PATH=V1,V2,...``,
    ``PATH~uniform(LOW,HIGH)``, ``PATH~normal(MEAN,STD)``, ``PATH~loguniform(LOW,HIGH)``.

    Parameters
    ----------
    text : str
        The ``--vary`` argument.

    Examples
    --------
    >>> from gyrostat import sweeps
    >>> sweeps.parameter_from_text("torques[0].diagonal[2]=0.1:0.3:3").values
    (0.1, 0.2, 0.3)
    >>> sweeps.parameter_from_text("initial.omega[2]~normal(1.0,0.05)").distribution
    Normal(mean=1.0, std=0.05)
    """
    path, sign, spec = (text.partition("=") if "=" in text and ("~" not in text or text.index("=") < text.index("~"))
                        else text.partition("~"))
    path = path.strip()
    try:
        if sign == "=":
            grid = _GRID_TEXT.fullmatch(spec)
            if grid:
                start, stop, num = float(grid.group(1)), float(grid.group(2)), int(grid.group(3))
                if grid.group(4) == "log":
                    if not (start > 0 and stop > 0):
                        raise ValueError("a log grid needs START > 0 and STOP > 0")
                    return Parameter(path, (path,), values=np.geomspace(start, stop, num))
                return Parameter(path, (path,), values=np.linspace(start, stop, num))
            try:
                values = [float(v) for v in spec.split(",")]
            except ValueError:
                values = None
            if values is not None:
                return Parameter(path, (path,), values=values)
        if sign == "~":
            match = _DISTRIBUTION_TEXT.fullmatch(spec)
            if match:
                distribution = DISTRIBUTIONS[match.group(1).lower()](float(match.group(2)), float(match.group(3)))
                return Parameter(path, (path,), distribution=distribution)
    except ValueError as error:
        raise SceneError(f"--vary {text!r}: {error}") from None
    raise SceneError(f"--vary {text!r}: write PATH=START:STOP:NUM[:log], PATH=V1,V2,... or "
                     "PATH~uniform(LOW,HIGH) / normal(MEAN,STD) / loguniform(LOW,HIGH)")


def _parameters(vary) -> list[Parameter]:
    if isinstance(vary, Parameter):
        vary = [vary]
    if isinstance(vary, Mapping):
        made = []
        for path, spec in vary.items():
            if isinstance(spec, Parameter):
                raise ValueError("give Parameters as a list, not as the values of a dict")
            given = {"distribution": spec} if isinstance(spec, (Uniform, Normal, LogUniform)) else {"values": spec}
            made.append(Parameter(path, (path,), **given))
        vary = made
    if not isinstance(vary, Sequence) or not vary or not all(isinstance(p, Parameter) for p in vary):
        raise ValueError("vary must be a non-empty dict {path: values or distribution} or a list of gyrostat.Parameter")
    names = [p.name for p in vary]
    if len(set(names)) != len(names):
        raise ValueError(f"parameter names must differ; got {names}")
    return list(vary)
