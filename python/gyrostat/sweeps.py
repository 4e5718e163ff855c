"""Sweeps and Monte Carlo runs of a scene: parameter grids and seeded dispersions, solved in
chunks on the engine's thread pool or on a Dask cluster, returned as an ``xarray.Dataset``.

A sweep varies numeric entries of a scene by their path in the scene document::

    import gyrostat as g
    ds = g.sweep("p001.toml", {"body.moments[0:2]": np.linspace(1, 3, 21),     # a grid: the product
                               "torques[0].diagonal[0:2]": [0.1, 0.2]}, run="averaged")
    ds = g.sweep(scene, {"initial.omega[2]": g.Normal(1.0, 0.05),             # a dispersion
                         "torques[1].viscosity": g.LogUniform(1e-3, 1e-1)}, samples=10_000, seed=7)

A path is keys and indices (``body.moments[0]``, ``torques[1].viscosity``, ``initial.omega[2]``,
``integration.rtol``, ``runs[0].law.value``); a slice (``body.moments[0:2]``) sets several
entries to one value (A1 = A2 of a symmetric body). :class:`Parameter` names a parameter that
sets several paths, optionally scaled (``Parameter("I1_over_I3", ["torques[0].diagonal[0:2]"],
values, scale=0.1)`` sets ε I1 with ε = 0.1). Every member's document is checked as the scene
file would be (the key's type and checks), and its model built by the scene's kind; a member
whose values the physics refuses (a negative moment of inertia after dispersion) is recorded
with status ``invalid_input`` and the message, never lost and never stopping the others; a
member whose run raises (a user's :class:`gyrostat.CustomTorque` raising for its values) is
recorded with status ``failed`` and its exception, the others with their own results, on every
runner (this process, worker processes, Dask).

``model = "auto"`` is resolved once, from the scene as written (the model ladder's choice, probes
included: :mod:`gyrostat.ladder`), so that every member is solved with the same model, without
switching rungs along its run; one run of the scene is swept (``run=``; the only run, or ``"full"``).

Dispersions draw member i's values from its own stream, ``SeedSequence(seed, spawn_key=(i,))``:
a member is reproducible alone (:meth:`Plan.scene`), and the same seed gives the same members
whatever the chunking, locally or on Dask. The seed is recorded in the Dataset (``attrs``).

The Dataset has the grid's parameter axes (or ``member`` for a dispersion) and ``time``; the
state and named outputs as variables with their units; the varied parameters as coordinates;
per member: ``status``, ``message``, the solver statistics, ``t_final``, the final value of
every quantity (``final_<name>``), extrema of chosen outputs (``min_<name>``, ``max_<name>``
over the output times), and per event the time of its first crossing (``first_<event>``) and
its count (``count_<event>``), and the event that ended the run (``terminal_event``). With
``trajectories=False`` only these summaries are kept; with ``path=`` each chunk is written to a
NetCDF file as it finishes, so that memory stays bounded for any number of members.
"""

from __future__ import annotations

import copy
import gc
import itertools
import json
import math
import os
import re
import signal
import sys
import time
import warnings
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from gyrostat import _core, output
from gyrostat import progress as _bars
from gyrostat.events import labels, variable_name
from gyrostat.kind import reusing
from gyrostat.modelbase import shown
from gyrostat.solution import Solution
from gyrostat.schema import SceneError, locate

__all__ = ["Uniform", "Normal", "LogUniform", "Parameter", "Plan", "sweep", "open_sweep", "summary",
           "solve_chunk", "parameter_from_table", "parameter_from_text", "check_plot", "MEMORY_LIMIT"]

MEMORY_LIMIT = 4 * 2**30
"""Bytes a sweep may keep in memory (trajectories and summaries); beyond it a sweep asks for
``trajectories=False`` or ``path=`` (streaming to a file) before it starts."""

WORKERS_FROM = 10_000
"""Members from which a sweep on this machine runs on worker processes by default (``workers=None``,
where the platform forks): below it, forking the workers and their first chunk cost more than
making members on one helper thread beside the engine's."""

STATS = ("steps", "rhs_evals", "rejected_steps", "jacobian_evals", "nonlinear_conv_failures")


# ------------------------------------------------------------------------------------ distributions
def _number(value, what: str) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float, np.integer, np.floating)) \
            or not math.isfinite(value):
        raise ValueError(f"{what} = {value!r} must be a finite number")
    return float(value)


def _documented_draw(cls):
    """Gives ``cls.draw`` its docstring, the same for every distribution (with its own example)."""
    example = {"Uniform": "Uniform(0.5, 1.5)", "Normal": "Normal(1.0, 0.1)", "LogUniform": "LogUniform(1e-3, 1e-1)"}
    cls.draw.__doc__ = f"""One value drawn from the distribution.

        Parameters
        ----------
        rng : numpy.random.Generator
            The generator (a sweep gives member i ``SeedSequence(seed, spawn_key=(i,))``).

        Examples
        --------
        >>> import numpy as np
        >>> import gyrostat
        >>> value = gyrostat.{example[cls.__name__]}.draw(np.random.default_rng(7))
        >>> value == gyrostat.{example[cls.__name__]}.draw(np.random.default_rng(7))
        True
        """
    return cls


@_documented_draw
@dataclass(frozen=True)
class Uniform:
    """Uniform on [low, high): a distribution of a dispersed scene entry.

    Parameters
    ----------
    low, high : float
        The bounds, in the unit of the entry it disperses.

    Examples
    --------
    >>> import numpy as np
    >>> import gyrostat
    >>> round(gyrostat.Uniform(0.5, 1.5).draw(np.random.default_rng(1)), 6)
    1.011822
    """

    low: float
    high: float

    def __post_init__(self):
        if not _number(self.low, "Uniform low") < _number(self.high, "Uniform high"):
            raise ValueError(f"Uniform({self.low!r}, {self.high!r}): low must be below high")
        object.__setattr__(self, "_affine", (float(self.low), float(self.high) - float(self.low)))

    def draw(self, rng: np.random.Generator) -> float:
        # rng.uniform(low, high) bit for bit (NumPy computes low + (high - low)·u in doubles), ~3x faster
        low, width = self._affine
        return low + width * rng.random()


@_documented_draw
@dataclass(frozen=True)
class Normal:
    """Normal with the given mean and standard deviation.

    Parameters
    ----------
    mean, std : float
        In the unit of the entry it disperses; std > 0.

    Examples
    --------
    >>> import numpy as np
    >>> import gyrostat
    >>> round(gyrostat.Normal(1.0, 0.1).draw(np.random.default_rng(1)), 6)
    1.034558
    """

    mean: float
    std: float

    def __post_init__(self):
        _number(self.mean, "Normal mean")
        if not _number(self.std, "Normal std") > 0:
            raise ValueError(f"Normal({self.mean!r}, {self.std!r}): std must be positive")

    def draw(self, rng: np.random.Generator) -> float:
        # rng.normal(mean, std) bit for bit (NumPy computes mean + std·z in doubles)
        return float(self.mean) + float(self.std) * rng.standard_normal()


@_documented_draw
@dataclass(frozen=True)
class LogUniform:
    """log(value) uniform on [log low, log high): every decade equally likely.

    Parameters
    ----------
    low, high : float
        The bounds, 0 < low < high, in the unit of the entry it disperses.

    Examples
    --------
    >>> import numpy as np
    >>> import gyrostat
    >>> round(gyrostat.LogUniform(1e-3, 1e-1).draw(np.random.default_rng(1)), 6)
    0.010559
    """

    low: float
    high: float

    def __post_init__(self):
        low, high = _number(self.low, "LogUniform low"), _number(self.high, "LogUniform high")
        if not 0 < low < high:
            raise ValueError(f"LogUniform({self.low!r}, {self.high!r}): needs 0 < low < high")
        object.__setattr__(self, "_affine", (math.log(low), math.log(high) - math.log(low)))

    def draw(self, rng: np.random.Generator) -> float:
        # exp(rng.uniform(log low, log high)) bit for bit, the logarithms taken once
        low, width = self._affine
        return math.exp(low + width * rng.random())


DISTRIBUTIONS = {"uniform": Uniform, "normal": Normal, "loguniform": LogUniform}
Distribution = Uniform | Normal | LogUniform


# ------------------------------------------------------------------------------------ members' streams
# Member i of a dispersion draws from default_rng(SeedSequence(seed, spawn_key=(i,))). Made one by
# one, that generator costs ~25 us (NumPy's SeedSequence hashing and PCG64 seeding in Python); a
# chunk's streams are computed here together, NumPy's algorithms word for word on arrays (the
# SeedSequence of NumPy's bit_generator.pyx, PCG64's pcg_setseq_128_srandom_r), and set into one
# PCG64 member by member: the same numbers (tests/test_sweeps.py compares them with default_rng).
_INIT_A, _MULT_A, _INIT_B, _MULT_B = 0x43B0D7E5, 0x931E8875, 0x8B51F9DD, 0x58F38DED
_MIX_L, _MIX_R = 0xCA01F9DD, 0x4973F715
_PCG_MULT = 0x2360ED051FC65DA44385DF649FCCF645
_MASK32, _MASK128 = 0xFFFFFFFF, (1 << 128) - 1


def _words(n: int) -> list[int]:
    """A non-negative integer as 32-bit words, least significant first (0: one word)."""
    out = [n & _MASK32]
    while n > _MASK32:
        n >>= 32
        out.append(n & _MASK32)
    return out


def _pcg64_states(seed: int, members: np.ndarray) -> list[tuple[int, int]]:
    """(state, inc) of PCG64(SeedSequence(seed, spawn_key=(i,))) for each member i < 2**32."""
    u32 = np.uint32
    run = _words(seed)
    run += [0] * (4 - len(run))  # a spawned sequence pads its entropy to the pool size
    count = len(members)
    entropy = [np.full(count, w, u32) for w in run] + [members.astype(u32)]
    hash_a = [_INIT_A]

    def hashmix(value):
        value = value ^ u32(hash_a[0])
        hash_a[0] = (hash_a[0] * _MULT_A) & _MASK32
        value = value * u32(hash_a[0])
        return value ^ (value >> u32(16))

    def mix(x, y):
        result = u32(_MIX_L) * x - u32(_MIX_R) * y
        return result ^ (result >> u32(16))

    with np.errstate(over="ignore"):  # arithmetic modulo 2**32, as in NumPy's C
        pool = [hashmix(entropy[i]) for i in range(4)]
        for source in range(4):
            for target in range(4):
                if source != target:
                    pool[target] = mix(pool[target], hashmix(pool[source]))
        for source in range(4, len(entropy)):
            for target in range(4):
                pool[target] = mix(pool[target], hashmix(entropy[source]))
        hash_b, state = _INIT_B, []
        for k in range(8):  # generate_state(4, uint64): 8 words, pairs (low, high)
            value = pool[k % 4] ^ u32(hash_b)
            hash_b = (hash_b * _MULT_B) & _MASK32
            value = value * u32(hash_b)
            state.append((value ^ (value >> u32(16))).tolist())
    out = []
    for m in range(count):
        seed_high, seed_low, inc_high, inc_low = (state[2 * j][m] | (state[2 * j + 1][m] << 32) for j in range(4))
        inc = ((((inc_high << 64) | inc_low) << 1) | 1) & _MASK128
        current = (((inc + ((seed_high << 64) | seed_low)) & _MASK128) * _PCG_MULT + inc) & _MASK128
        out.append((current, inc))
    return out


def _member_generators(seed: int, start: int, stop: int):
    """Each member's generator in turn, for members start … stop − 1 (one Generator, reseeded)."""
    if stop > 2**32 or stop - start < 8:  # beyond 2**32 a spawn key has two words; a few members: NumPy's own way
        for i in range(start, stop):
            yield np.random.default_rng(np.random.SeedSequence(seed, spawn_key=(i,)))
        return
    bits = np.random.PCG64(0)
    generator = np.random.Generator(bits)
    for current, inc in _pcg64_states(seed, np.arange(start, stop, dtype=np.uint64)):
        bits.state = {"bit_generator": "PCG64", "state": {"state": current, "inc": inc}, "has_uint32": 0,
                      "uinteger": 0}
        yield generator


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


# ------------------------------------------------------------------------------------ the plan
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
            choice = ladder.choose(scene.ladder, template.t_span, template.options, integration["accuracy"])
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


# ------------------------------------------------------------------------------------ a chunk
def _blank(plan: Plan, count: int, trajectories: bool, extrema: tuple[str, ...]) -> dict[str, np.ndarray]:
    """A chunk's arrays before any member is solved: NaN, zero counts, status ``interrupted``."""
    arrays: dict[str, np.ndarray] = {
        "status": np.full(count, "interrupted", dtype=object),
        "message": np.full(count, "not run: the sweep was stopped first", dtype=object),
        "terminal_event": np.full(count, "", dtype=object),
        "broken_assumptions": np.zeros(count, dtype=np.int64),
        "first_broken_assumption": np.full(count, "", dtype=object),
        "accuracy_warning": np.full(count, "", dtype=object),
    }
    for name in STATS:
        arrays[name] = np.zeros(count, dtype=np.int64)
    arrays["last_step"] = np.full(count, np.nan)
    arrays["t_final"] = np.full(count, np.nan)
    for name in plan.names:
        arrays[f"final_{name}"] = np.full(count, np.nan)
    for name in extrema:
        arrays[f"min_{name}"] = np.full(count, np.nan)
        arrays[f"max_{name}"] = np.full(count, np.nan)
    for label in plan.event_labels:
        arrays[f"first_{variable_name(label)}"] = np.full(count, np.nan)
        arrays[f"count_{variable_name(label)}"] = np.zeros(count, dtype=np.int64)
    if trajectories:
        arrays["t"] = np.full((count, plan.n_out), np.nan)
        for name in plan.names:
            arrays[name] = np.full((count, plan.n_out), np.nan)
    for parameter in plan.parameters:
        arrays[parameter.name] = np.full(count, np.nan)
    return arrays


def _record(arrays: dict, j: int, solution, plan: Plan, trajectories: bool, extrema: tuple[str, ...]) -> None:
    arrays["status"][j], arrays["message"][j] = solution.status, solution.message
    stats = solution.stats
    for name in STATS:
        arrays[name][j] = stats[name]
    arrays["last_step"][j] = stats["last_step"]
    n = len(solution)
    if n:
        arrays["t_final"][j] = solution.t[-1]
        if solution.state_names + solution.output_names == plan.names:  # one matrix: no per-name look-ups
            table = np.hstack([solution.y, solution._result.outputs]) if plan.output_names else solution.y
            present = plan.names
        else:  # a member whose model names differ: by name, NaN where it has no such quantity
            present = tuple(name for name in plan.names if name in solution)
            table = np.column_stack([solution[name] for name in present]) if present else np.empty((n, 0))
        for k, name in enumerate(present):
            arrays[f"final_{name}"][j] = table[-1, k]
        if extrema:
            low, high = table.min(axis=0), table.max(axis=0)
            for k, name in enumerate(present):
                if name in extrema:
                    arrays[f"min_{name}"][j], arrays[f"max_{name}"][j] = low[k], high[k]
        if trajectories:
            m = min(n, plan.n_out)
            arrays["t"][j, :m] = solution.t[:m]
            for k, name in enumerate(present):
                arrays[name][j, :m] = table[:m, k]
    for label, times in zip(solution.event_names, solution.t_events):
        if label in plan.event_labels:
            key = variable_name(label)
            arrays[f"count_{key}"][j] = len(times)
            if len(times):
                arrays[f"first_{key}"][j] = times[0]
    if solution.terminal_event is not None:
        arrays["terminal_event"][j] = solution.event_names[solution.terminal_event]


def _record_results(arrays: dict, rows: list[int], results: list, models: list, plan: Plan, trajectories: bool,
                    extrema: tuple[str, ...]) -> list[str]:
    """:func:`_record` for the members of one ensemble call (chunk rows ``rows``, the engine's
    ``Result`` of each and its model, one or one per member), in bulk: for a summaries-only sweep
    without events, status, message, statistics, final values and extrema as columns over the
    members (``_core.summaries``, one pass in C++); a member with a terminal event or other names
    than the plan's, and every member of a sweep that keeps trajectories or events, by
    :func:`_record`. Returns each member's first accuracy warning ("" for none)."""
    model_of = (lambda k: models[0]) if len(models) == 1 else models.__getitem__
    if trajectories or plan.event_labels:
        for k, (j, r) in enumerate(zip(rows, results)):
            _record(arrays, j, Solution(r, model_of(k)), plan, trajectories, extrema)
        return [r.warnings[0] if len(r.warnings) else "" for r in results]
    columns = _core.summaries(results, plan.state_names, plan.output_names, bool(extrema))
    rows = np.asarray(rows, dtype=np.intp)
    arrays["status"][rows] = columns["status"]
    arrays["message"][rows] = columns["message"]
    for name in STATS + ("last_step",):
        arrays[name][rows] = columns[name]
    ran = columns["rows"] > 0
    bulk = ran & columns["named"] & (columns["terminal_event"] < 0)
    for k in np.flatnonzero(ran & ~bulk):  # a terminal event, or a model with other names: by name
        _record(arrays, rows[k], Solution(results[k], model_of(k)), plan, trajectories, extrema)
    chosen = rows[bulk]
    arrays["t_final"][chosen] = columns["t_final"][bulk]
    finals = columns["final"][bulk]
    for c, name in enumerate(plan.names):
        arrays[f"final_{name}"][chosen] = finals[:, c]
        if name in extrema:
            arrays[f"min_{name}"][chosen] = columns["min"][bulk, c]
            arrays[f"max_{name}"][chosen] = columns["max"][bulk, c]
    return columns["warning"]


def _put_values(arrays: dict, plan: Plan, drawn: list[tuple[float, ...]]) -> None:
    """The members' parameter values (one tuple per member) into their columns of a chunk."""
    for k, parameter in enumerate(plan.parameters):
        arrays[parameter.name][:] = [values[k] for values in drawn]


def solve_chunk(plan: Plan, start: int, stop: int, *, threads: int = 0, trajectories: bool = True,
                extrema: Sequence[str] = (), check_validity: bool = True, progress=None) -> dict[str, np.ndarray]:
    """Solves members ``start`` to ``stop - 1`` of a plan and returns their arrays (what a sweep
    keeps of each). Members that share options are one :func:`gyrostat.solve_ensemble` call on
    ``threads`` C++ threads; a member the physics refuses gets status ``invalid_input``, a member
    whose run raises (a user's torque) status ``failed`` and its exception as message; with
    ``check_validity``, the assumptions of an averaged model are checked along each member (the
    count of broken ones and the first, per member). The same on every machine: a Dask task
    runs exactly this.

    Parameters
    ----------
    plan : Plan
        The sweep.
    start, stop : int
        The members, ``range(start, stop)``.
    threads : int, optional
        C++ threads (≤ 0: every core).
    trajectories : bool, optional
        Keep each member's trajectory.
    extrema : sequence of str, optional
        Quantities whose minimum and maximum are kept.
    check_validity : bool, optional
        Check an averaged model's assumptions along each member.
    progress : callable, optional
        Called with the number of members finished.

    Examples
    --------
    >>> from gyrostat import sweeps
    >>> from gyrostat.scene import SCENES
    >>> plan = sweeps.Plan(SCENES / "forced_damped.toml", {"torques[0].moment[2]": [0.05, 0.1]})
    >>> chunk = sweeps.solve_chunk(plan, 0, 2, trajectories=False)
    >>> list(chunk["status"]), chunk["final_r"].round(4)  # r in rad/s at t1
    (['success', 'success'], array([1.4521, 2.9912]))
    """
    return _solve_members(plan, _members(plan, start, stop, trajectories, tuple(extrema)), threads=threads,
                          trajectories=trajectories, extrema=tuple(extrema), check_validity=check_validity,
                          progress=progress)


def _members(plan: Plan, start: int, stop: int, trajectories: bool, extrema: tuple[str, ...]) -> tuple[dict, dict]:
    """The first half of :func:`solve_chunk`, pure Python: the chunk's arrays with every member's
    values (and the refused members' status), and the runs grouped by span, options and events."""
    count = stop - start
    arrays = _blank(plan, count, trajectories, extrema)
    arrays["interrupted"] = np.zeros(1, dtype=bool)
    groups: dict[tuple, list] = {}
    drawn = plan.values_range(start, stop)
    _put_values(arrays, plan, drawn)
    # the members' documents, models and runs are many small containers kept to the chunk's end: the cyclic
    # collector, paused while they are made, would otherwise pass over them again and again (~15% of the time)
    collecting = gc.isenabled()
    gc.disable()
    try:
        with reusing(plan.base):  # the body and torques no parameter changes: built once for the chunk
            for j, values in enumerate(drawn):
                try:
                    run = plan.member(values)
                except (SceneError, ValueError) as error:
                    arrays["status"][j], arrays["message"][j] = "invalid_input", " ".join(str(error).split())
                    continue
                options = tuple(sorted((k, v) for k, v in run.options.items() if k != "events"))
                key = (run.t_span, options, tuple(run.options.get("events", ())))
                groups.setdefault(key, []).append((j, run))
    finally:
        if collecting:
            gc.enable()
    return arrays, groups


def _solve_members(plan: Plan, members_of_chunk: tuple[dict, dict], *, threads: int, trajectories: bool,
                   extrema: tuple[str, ...], check_validity: bool, progress) -> dict[str, np.ndarray]:
    """The second half of :func:`solve_chunk`: the groups solved (one solve_ensemble each, the
    engine's pool with the GIL released) and each member's summary recorded."""
    from gyrostat.modelbase import ModelBase
    from gyrostat.solve import ensemble_results

    arrays, groups = members_of_chunk
    count = len(arrays["status"])
    done = count - sum(len(members) for members in groups.values())
    for (span, options, events), members in groups.items():
        size, share = len(members), len(members) / count

        def report(fraction, before=done / count, share=share):
            progress(before + share * fraction)

        # the engine's results, not a Solution per member: the summaries are made in bulk (_record_results);
        # each member's doubts are recorded (accuracy_warning), not warned about
        models = [run.model for _, run in members]
        starts = [run.y0 for _, run in members]
        if len({len(y0) for y0 in starts}) == 1:
            starts = np.stack(starts)  # one (members, dim) array: converted once, not member by member
        with _interruptible():
            try:
                _, results = ensemble_results(models, starts, span, threads=threads,
                                               events=list(events) or None,
                                               progress=report if progress is not None else False, **dict(options))
            except Exception:  # a member's run raised (a user's torque): each member solved alone
                members, results = _one_by_one(arrays, members, span, events, options, threads,
                                               report if progress is not None else None)
                models = [run.model for _, run in members]
        rows = [j for j, _ in members]
        if rows:
            arrays["accuracy_warning"][rows] = _record_results(arrays, rows, results, models, plan, trajectories,
                                                               extrema)
        checked = {kind: check_validity and kind.check is not ModelBase.check for kind in {type(m) for m in models}}
        for (j, run), result in zip(members, results):
            if checked[type(run.model)] and len(result.t):
                broken = [str(a) for a in run.model.check(Solution(result, run.model)) if not a.holds]  # the averaging's
                arrays["broken_assumptions"][j] = len(broken)
                arrays["first_broken_assumption"][j] = broken[0] if broken else ""
        done += size
        if any(r.status == "interrupted" for r in results):
            arrays["interrupted"][0] = True
            break
    return arrays


def _said(error: BaseException) -> str:
    """An exception as one line of a member's ``message``: its type and its words."""
    return f"{type(error).__name__}: {' '.join(str(error).split())}"


def _one_by_one(arrays: dict, members: list, span, events, options, threads: int, report) -> tuple[list, list]:
    """The members of an ensemble call that raised (the engine raises the first exception a
    member's run raised, a user's torque's, once the members have finished), solved again one
    at a time, so that an exception is its own member's alone: that member gets status
    ``failed`` and the exception as its message, every other member the result of its own run
    (an ensemble of one: the numbers of its lane in the call, bit for bit). Returns the members
    that returned a result and their results; stops at a member Ctrl-C interrupted (the later
    ones stay ``interrupted``)."""
    from gyrostat.solve import ensemble_results

    solved, results = [], []
    for k, (j, run) in enumerate(members):
        try:
            _, (result,) = ensemble_results([run.model], [run.y0], span, threads=threads,
                                            events=list(events) or None, progress=False, **dict(options))
        except Exception as error:  # this member's own: recorded, the others go on
            arrays["status"][j], arrays["message"][j] = "failed", _said(error)
        else:
            solved.append((j, run))
            results.append(result)
            if result.status == "interrupted":
                break
        if report is not None:
            report((k + 1) / len(members))
    return solved, results


# ------------------------------------------------------------------------------------ where results go
class _Memory:
    """Every member's arrays in memory (at most MEMORY_LIMIT bytes)."""

    def __init__(self, plan: Plan, trajectories: bool, extrema: tuple[str, ...]):
        sample = _blank(plan, 1, trajectories, extrema)
        need = plan.size * sum(a.nbytes if a.dtype != object else 64 for a in sample.values())
        if need > MEMORY_LIMIT:
            raise ValueError(f"a sweep of {plan.size} members keeping {'trajectories' if trajectories else 'summaries'} "
                             f"needs about {need / 2**30:.1f} GiB (limit {MEMORY_LIMIT / 2**30:.0f} GiB): keep summaries "
                             "only (trajectories=False), ask for fewer outputs (n_out), or stream to a file (path=)")
        self.arrays = _blank(plan, plan.size, trajectories, extrema)

    def put(self, start: int, chunk: dict) -> None:
        for name, array in self.arrays.items():
            array[start:start + len(chunk[name])] = chunk[name]

    def close(self, plan: Plan, attrs: dict):
        return _dataset(plan, self.arrays, attrs)


class _NetCDF:
    """Each chunk appended to a NetCDF file as it arrives (memory bounded by one chunk)."""

    def __init__(self, plan: Plan, path: Path, trajectories: bool, extrema: tuple[str, ...]):
        import netCDF4

        self.path = Path(path)
        self.path.parent.mkdir(parents=True, exist_ok=True)
        self.file = netCDF4.Dataset(self.path, "w")
        self.file.createDimension("member", plan.size)
        if trajectories:
            self.file.createDimension("time", plan.n_out)
        self.file.createVariable("member", "i8", ("member",))[:] = np.arange(plan.size)
        coordinates = " ".join(p.name for p in plan.parameters)
        for name, array in _blank(plan, 1, trajectories, extrema).items():
            dims = ("member",) if array.ndim == 1 else ("member", "time")
            kind = str if array.dtype == object else array.dtype
            fill = np.nan if array.dtype.kind == "f" else None
            variable = self.file.createVariable(name, kind, dims, fill_value=fill)
            variable.setncatts(_attributes(plan, name))
            if name not in (p.name for p in plan.parameters):
                variable.coordinates = coordinates

    def put(self, start: int, chunk: dict) -> None:
        count = len(chunk["status"])
        for name, variable in self.file.variables.items():
            if name == "member":
                continue
            values = chunk[name]
            variable[start:start + count] = values if values.dtype != object else values.astype(str)

    def close(self, plan: Plan, attrs: dict):
        import xarray as xr

        self.file.setncatts(attrs)
        self.file.close()
        return xr.open_dataset(self.path)


def _attributes(plan: Plan, name: str) -> dict:
    """Units and a description of a variable of the sweep's Dataset."""
    for parameter in plan.parameters:
        if name == parameter.name:
            from gyrostat.families import KINDS

            located = locate(KINDS[plan.kind_name].schema, plan.base, parse_path(parameter.paths[0]), plan.scene_name)
            unit = located.field.unit
            scaled = "" if parameter.scale == 1 else f" / {parameter.scale:g}"
            return {"long_name": parameter.label or parameter.name,
                    "description": f"{', '.join(parameter.paths)}{scaled}",
                    **({"units": unit} if unit and parameter.scale == 1 and not parameter.label else {})}
    for prefix, meaning in (("final_", "at the end of the run"), ("min_", "minimum over the output times"),
                            ("max_", "maximum over the output times")):
        if name.startswith(prefix) and name[len(prefix):] in plan.names:
            return {"units": plan.units[name[len(prefix):]], "description": f"{name[len(prefix):]} {meaning}"}
    if name.startswith("first_"):
        return {"units": "s", "description": "time of the event's first crossing (NaN: none)"}
    if name.startswith("count_"):
        return {"description": "number of crossings of the event"}
    fixed = {"t": {"units": "s", "description": "output times"},
             "t_final": {"units": "s", "description": "time where the run ended"},
             "last_step": {"units": "s", "description": "the last step size"},
             "status": {"description": "success, or why the run stopped (invalid_input: the values were refused; "
                                  "failed: the run raised, or its worker failed)"},
             "message": {"description": "the reason in words"},
             "terminal_event": {"description": "the event that ended the run, or empty"},
             "broken_assumptions": {"description": "how many of the model's assumptions (an averaged model's "
                                                   "validity checks) fail along the member's run"},
             "first_broken_assumption": {"description": "the first of them, in words (empty: all hold)"},
             "accuracy_warning": {"description": "the first doubt the run had about its own answer (the splitting's "
                                                 "estimated error above rtol, BDF over oscillations); empty: none"}}
    if name in fixed:
        return fixed[name]
    if name in STATS:
        return {"description": f"solver statistics: {name}"}
    return {"units": plan.units.get(name, "1")}


def _dataset(plan: Plan, arrays: dict, attrs: dict):
    import xarray as xr

    variables, coords = {}, {"member": ("member", np.arange(plan.size))}
    for name, array in arrays.items():
        dims = ("member",) if array.ndim == 1 else ("member", "time")
        target = coords if name in (p.name for p in plan.parameters) else variables
        target[name] = xr.Variable(dims, array, _attributes(plan, name))
    return xr.Dataset(variables, coords, attrs)


def _finish(ds, plan_description: dict):
    """The Dataset a user sees: a common time axis as the coordinate ``time``; a grid on its
    parameters' axes."""
    if "t" in ds.variables and ds["t"].ndim == 2:
        t = ds["t"].values
        rows = t[np.all(np.isfinite(t), axis=1)]
        if len(rows) and np.all(rows == rows[0]) and np.all(np.isnan(t) | (t == rows[0])):
            ds = ds.drop_vars("t").assign_coords(time=("time", rows[0], {"units": "s", "description": "output times"}))
    if plan_description["mode"] != "grid":
        return ds
    names = [p["name"] for p in plan_description["parameters"]]
    shape = plan_description["shape"]
    out = {}
    for name, variable in ds.data_vars.items():
        values = variable.values.reshape(tuple(shape) + variable.shape[1:])
        out[name] = (tuple(names) + variable.dims[1:], values, variable.attrs)
    coords = {p["name"]: (p["name"], np.asarray(p["values"], float), ds[p["name"]].attrs)
              for p in plan_description["parameters"]}
    if "time" in ds.coords:
        coords["time"] = ds["time"]
    import xarray as xr

    return xr.Dataset(out, coords, ds.attrs)


def open_sweep(path: str | Path):
    """A sweep written with ``path=`` (or by ``gyrostat sweep``), as :func:`sweep` returns it:
    a grid on its parameter axes (loaded into memory), a dispersion along ``member``.

    Parameters
    ----------
    path : str or pathlib.Path
        The NetCDF file.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> import gyrostat
    >>> from gyrostat.scene import SCENES
    >>> path = pathlib.Path(tempfile.mkdtemp()) / "sweep.nc"
    >>> _ = gyrostat.sweep(SCENES / "forced_damped.toml", {"initial.omega[0]": [1.0, 0.5]}, trajectories=False,
    ...                    progress=False, path=path)
    >>> list(gyrostat.sweeps.open_sweep(path).coords)  # the grid's axis, as sweep() returned it
    ['initial.omega[0]']
    """
    import xarray as xr

    ds = xr.open_dataset(path)
    return _finish(ds, json.loads(ds.attrs["plan"]))


# ------------------------------------------------------------------------------------ the sweep
def _chunk_size(plan: Plan, trajectories: bool, extrema: tuple[str, ...], workers: int) -> int:
    per_member = sum(a.nbytes if a.dtype != object else 64 for a in _blank(plan, 1, trajectories, extrema).values())
    by_memory = max(1, (64 * 2**20) // (2 * per_member))  # the chunk's arrays and the engine's results
    by_balance = max(1, math.ceil(plan.size / (4 * workers)))  # a few chunks per worker at least
    return int(min(by_memory, by_balance, 8192))


def sweep(scene, vary, *, samples: int | None = None, seed: int | None = None, run: str | None = None,
          trajectories: bool = True, extrema: Sequence[str] | None = None, chunk_size: int | None = None,
          threads: int = 0, workers: int | None = None, client=None, path: str | Path | None = None,
          check_validity: bool = True, progress=None, allow_import: Iterable[str] | str | None = None):
    """Solves a scene for every member of a grid or a dispersion of its numeric entries.

    Parameters
    ----------
    scene:
        A scene file, a scene document (dict) or a :class:`gyrostat.scene.Scene`; or a
        :class:`Plan` made already (``vary``, ``samples``, ``seed`` and ``run`` are then its own).
    vary:
        ``{path: values}`` (a grid: the product of the value lists), ``{path: distribution}``
        (a dispersion: :class:`Uniform`, :class:`Normal`, :class:`LogUniform`), or a list of
        :class:`Parameter` (a name, several paths, a scale).
    samples, seed:
        The number of members of a dispersion and its seed (None: a fresh seed, recorded in
        ``attrs["seed"]``); member i draws from ``SeedSequence(seed, spawn_key=(i,))``.
    run:
        The scene's run to sweep (default: its only run, or ``"full"``).
    trajectories:
        Keep every member's trajectory (dimension ``time``); False keeps only the summaries.
    extrema:
        Quantities whose minimum and maximum over the output times are kept (default: every
        named output of the run's model).
    chunk_size, threads:
        Members per ensemble call (default: about 64 MB of results, at least 4 chunks per
        worker) and C++ threads per chunk (≤ 0: every core here; 1 per task on Dask).
    workers:
        Processes on this machine, each making its chunks' members and solving them on one C++
        thread (SciPy's convention: ``-1`` one per core). ``1``: this process alone, the next
        chunk's members made on a helper thread while the engine's threads solve the current one;
        Python's lock keeps that helper to one core, so that making members bounds the throughput
        (~30 us a member) whatever the cores. None (default): one per core when the sweep has
        at least :data:`WORKERS_FROM` members, ``threads ≤ 0`` and the platform forks (Linux),
        else 1. Workers are forks of this process (elsewhere spawned: the calling script then
        needs the ``if __name__ == "__main__":`` guard, as with Dask). Ignored with ``client``.
    client:
        A ``dask.distributed.Client``: chunks become tasks on its cluster; the results are
        identical to the local ones.
    path:
        Stream each chunk to this NetCDF file as it finishes (memory bounded by a chunk) and
        return the file opened lazily (along ``member``; :func:`open_sweep` reshapes a grid).
    check_validity:
        Check an averaged model's assumptions along every member (``broken_assumptions``,
        ``first_broken_assumption``): how far to trust each member's answer.
    progress:
        None: a bar over the members in a terminal; True, False, or a callable of the fraction.
    allow_import:
        Modules whose code a scene file or document may name besides the scene file's folder
        (:mod:`gyrostat.scene_code`); the same rule holds on every worker.

    Returns
    -------
    xarray.Dataset
        See the module's documentation. Ctrl-C stops the sweep: the members finished are kept,
        the others have status ``"interrupted"`` (``attrs["interrupted"] = 1``) and a warning
        says how many. Results equal the members solved one by one with :func:`gyrostat.solve`
        bit for bit, except members that :func:`gyrostat.solve_ensemble` integrates in SIMD
        batches (``taylor`` or ``dop853`` on the gyrostat with constant and linear torques,
        ``dop853`` with vectorised compiled user torques besides, the averaged model under
        ``dop853``), which equal them to the tolerance.

    Examples
    --------
    The spin-down of a symmetric body under linear damping over a grid of two damping rates:
    the axial rate r decays as exp(-D t / C), to exp(-1) at t = 10 s for D = 0.1 N m s.

    >>> import gyrostat
    >>> scene = {"body": {"moments": [2.0, 2.0, 1.0]},
    ...          "torques": [{"type": "linear_damping", "diagonal": [0.1, 0.1, 0.1]}],
    ...          "initial": {"omega": [0.1, 0.0, 1.0]},
    ...          "integration": {"model": "full", "t_span": [0.0, 10.0], "n_out": 11}}
    >>> ds = gyrostat.sweep(scene, {"torques[0].diagonal[2]": [0.1, 0.2]}, trajectories=False, progress=False)
    >>> [round(float(r), 4) for r in ds["final_r"].values]
    [0.3679, 0.1353]
    """
    plan = scene if isinstance(scene, Plan) else Plan(scene, vary, samples=samples, seed=seed, run=run,
                                                                allow_import=allow_import)
    if trajectories and getattr(plan, "varies_n_out", False):
        raise ValueError("integration.n_out varies across members: their trajectories differ in length; keep "
                         "summaries only (trajectories=False)")
    if extrema is None:
        extrema = plan.output_names
    extrema = tuple(extrema)
    unknown = [name for name in extrema if name not in plan.names]
    if unknown:
        raise ValueError(f"extrema: {unknown} are not quantities of the run ({', '.join(plan.names)})")
    processes = _processes(workers, threads, plan.size) if client is None else 1
    workers = len(client.scheduler_info()["workers"]) if client is not None else processes
    if chunk_size is None:
        chunk_size = _chunk_size(plan, trajectories, extrema, workers)
    if isinstance(chunk_size, bool) or not isinstance(chunk_size, (int, np.integer)) or chunk_size < 1:
        raise ValueError(f"chunk_size = {chunk_size!r} must be a positive integer")
    if isinstance(threads, bool) or not isinstance(threads, (int, np.integer)) or abs(threads) > 4096:
        raise ValueError(f"threads = {threads!r} must be a whole number of at most 4096 (<= 0: one per core)")
    sink = _NetCDF(plan, path, trajectories, extrema) if path is not None else _Memory(plan, trajectories, extrema)
    ranges = [(s, min(s + chunk_size, plan.size)) for s in range(0, plan.size, chunk_size)]
    bar = _bars.resolve(progress, total=plan.size, unit="member", description=f"sweep {plan.scene_name}")
    started = time.perf_counter()
    options = {"trajectories": trajectories, "extrema": extrema, "check_validity": bool(check_validity)}
    try:
        if client is None and processes > 1:
            finished = _run_processes(plan, ranges, sink, bar, processes, threads, options)
        elif client is None:
            finished = _run_local(plan, ranges, sink, bar, threads, options)
        else:
            finished = _run_dask(plan, ranges, sink, bar, client, threads, options)
    finally:
        _bars.close(bar)
    missing = [r for r in ranges if r not in finished]
    for start, stop in missing:  # never run: written as such, so that no member is lost
        blank = _blank(plan, stop - start, trajectories, extrema)
        _put_values(blank, plan, plan.values_range(start, stop))
        sink.put(start, blank)
    attrs = {"gyrostat_version": _core.__version__, "scene": plan.scene_name, "kind": plan.kind_name,
             "run": plan.run, "model": plan.model_choice, "model_reason": plan.model_reason, "mode": plan.mode,
             "members": plan.size, "seconds": time.perf_counter() - started,
             "interrupted": int(bool(missing) or finished.get("interrupted", False)),
             "plan": json.dumps(plan.describe()), "extrema": json.dumps(list(extrema))}
    if plan.seed is not None:
        attrs["seed"] = plan.seed
    ds = sink.close(plan, attrs)
    if attrs["interrupted"]:
        unfinished = int((ds["status"] == "interrupted").sum())
        warnings.warn(f"sweep interrupted: {plan.size - unfinished} of {plan.size} members finished; the others have "
                      "status 'interrupted'", RuntimeWarning, stacklevel=2)
    return ds if path is not None else _finish(ds, plan.describe())


def _run_local(plan, ranges, sink, bar, threads, options) -> dict:
    """The chunks in turn on this machine. The next chunk's members are made (Python) on a helper
    thread while this thread solves the current one (C++, the GIL released) and records it: the
    same members, values and results as :func:`solve_chunk`, with the Python work beside the
    engine's instead of between its runs. Ctrl-C reaches the engine as in one solve_ensemble call
    (this thread runs it)."""
    from concurrent.futures import ThreadPoolExecutor

    finished: dict = {}
    done = 0
    making = (options["trajectories"], tuple(options["extrema"]))
    solving = {k: v for k, v in options.items() if k not in ("trajectories", "extrema")}
    helper = ThreadPoolExecutor(max_workers=1, thread_name_prefix="gyrostat-sweep-members")
    upcoming = helper.submit(_members, plan, *ranges[0], *making) if ranges else None
    try:
        for index, (start, stop) in enumerate(ranges):
            members = upcoming.result()
            if index + 1 < len(ranges):
                upcoming = helper.submit(_members, plan, *ranges[index + 1], *making)
            report = None if bar is None else (lambda f, d=done, n=stop - start: bar((d + f * n) / plan.size))
            chunk = _solve_members(plan, members, threads=threads, trajectories=making[0], extrema=making[1],
                                   progress=report, **solving)
            sink.put(start, chunk)
            finished[(start, stop)] = True
            done += stop - start
            if bar is not None:
                bar(done / plan.size)
            if chunk["interrupted"][0]:
                finished["interrupted"] = True
                break
    except KeyboardInterrupt:
        finished["interrupted"] = True
    finally:
        helper.shutdown(wait=True, cancel_futures=True)
    return finished


def _cores() -> int:
    try:
        return len(os.sched_getaffinity(0))  # the cores this process may run on (a container's share)
    except AttributeError:
        return os.cpu_count() or 1


def _forks() -> bool:
    import multiprocessing

    return sys.platform.startswith("linux") and "fork" in multiprocessing.get_all_start_methods()


def _daemon() -> bool:
    """Whether this process is a daemon (a Dask worker's, a multiprocessing pool's): it may not
    start processes of its own."""
    import multiprocessing

    return multiprocessing.current_process().daemon


def _processes(workers, threads, members: int) -> int:
    """The worker processes of a sweep run here (:func:`sweep`'s ``workers``); 1: this process."""
    if workers is None:
        return _cores() if members >= WORKERS_FROM and threads <= 0 and _forks() and not _daemon() else 1
    if isinstance(workers, bool) or not isinstance(workers, (int, np.integer)) or workers == 0 or workers < -1 \
            or workers > 4096:
        raise ValueError(f"workers = {workers!r} must be a positive whole number of at most 4096, -1 (one per core) "
                         "or None (chosen from the sweep's size)")
    processes = _cores() if workers == -1 else int(workers)
    if processes > 1 and _daemon():
        raise ValueError(f"workers = {workers!r}: this process is a daemon (a Dask worker's or a process pool's) and "
                         "cannot start processes; use workers=1 (or client= to run the chunks on Dask)")
    return processes


# A worker process's sweep: the plan and the options, set once when the worker starts (a fork
# inherits them; they are not sent with every chunk).
_WORKER: dict = {}


def _worker_start(plan, options: dict, stopping) -> None:
    """A worker process's start: Ctrl-C is the parent's to handle (it sets ``stopping`` and
    forwards the signal; a worker takes it only while the engine runs: :func:`_interruptible`);
    the sweep kept."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    _WORKER.update(plan=plan, options=options, stopping=stopping)


def _worker_chunk(start: int, stop: int) -> dict:
    if _WORKER["stopping"].is_set():  # queued before the sweep was stopped: not run
        raise KeyboardInterrupt
    return solve_chunk(_WORKER["plan"], start, stop, **_WORKER["options"])


def _stop_once(signum, frame):
    """A worker's Ctrl-C: the first stops the engine (KeyboardInterrupt, which the engine takes as
    Ctrl-C: it returns what it computed); a second (the terminal's and the parent's) is ignored,
    so that it cannot strike the results on their way back."""
    if not _WORKER.get("stopped"):
        _WORKER["stopped"] = True
        raise KeyboardInterrupt


class _interruptible:
    """In a worker process, around the engine's run: Ctrl-C (forwarded by the parent) stops the
    engine, which returns what it computed, as in the parent; outside it a worker ignores Ctrl-C, so
    that an idle worker never dies of it. Elsewhere: nothing."""

    def __enter__(self):
        if _WORKER:
            signal.signal(signal.SIGINT, _stop_once)
            if _WORKER["stopping"].is_set() or _WORKER.get("stopped"):  # the sweep was stopped while this chunk's members were made
                raise KeyboardInterrupt

    def __exit__(self, *exc):
        if _WORKER:
            signal.signal(signal.SIGINT, signal.SIG_IGN)
        return False


def _run_processes(plan, ranges, sink, bar, processes, threads, options) -> dict:
    """The chunks on ``processes`` forked worker processes (one C++ thread each, or ``threads``):
    each makes its chunks' members and solves them, :func:`solve_chunk` as on Dask, so that making
    members runs on every core instead of one helper thread. Ctrl-C: the chunks finished are kept,
    the running ones stop and return what they computed (the parent forwards the signal to its
    workers), the others are not run."""
    import multiprocessing
    from concurrent.futures import FIRST_COMPLETED, ProcessPoolExecutor, wait
    from concurrent.futures.process import BrokenProcessPool

    context = multiprocessing.get_context("fork" if _forks() else "spawn")
    per_chunk = threads if threads > 0 else 1
    stopping = context.Event()
    pool = ProcessPoolExecutor(processes, mp_context=context, initializer=_worker_start,
                               initargs=(plan, {**options, "threads": per_chunk}, stopping))
    finished: dict = {}
    queue = iter(ranges)
    running: dict = {}
    done = 0

    def unsolved(start: int, stop: int, error: BaseException) -> dict:
        """A chunk no worker returned: its members' values, and why (Ctrl-C: interrupted)."""
        chunk = _blank(plan, stop - start, options["trajectories"], options["extrema"])
        if isinstance(error, KeyboardInterrupt):
            chunk["interrupted"] = np.ones(1, dtype=bool)
        else:
            chunk["status"][:] = "failed"
            chunk["message"][:] = f"the worker process failed: {_said(error)}"
        _put_values(chunk, plan, plan.values_range(start, stop))
        return chunk

    def submit(count: int) -> None:
        for start, stop in itertools.islice(queue, count):
            try:
                running[pool.submit(_worker_chunk, start, stop)] = (start, stop)
            except BrokenProcessPool as error:  # a worker died (killed, out of memory): no chunk runs any more
                for first, last in [(start, stop), *queue]:
                    put(first, last, unsolved(first, last, error))
                return

    def put(start: int, stop: int, chunk: dict) -> None:
        nonlocal done
        sink.put(start, chunk)
        finished[(start, stop)] = True
        if chunk.get("interrupted", np.zeros(1, bool))[0]:
            finished["interrupted"] = True
        done += stop - start
        if bar is not None:
            bar(done / plan.size)

    def take(future) -> None:
        start, stop = running.pop(future)
        try:
            chunk = future.result()
        except BaseException as error:  # noqa: B036 - a worker lost, or stopped by Ctrl-C before its engine ran
            chunk = unsolved(start, stop, error)
        put(start, stop, chunk)

    try:
        try:
            submit(2 * processes)
            while running and not finished.get("interrupted"):
                completed, _ = wait(list(running), return_when=FIRST_COMPLETED)
                for future in completed:
                    take(future)
                submit(len(completed))
        except KeyboardInterrupt:
            finished["interrupted"] = True
        if finished.get("interrupted"):
            stopping.set()
            for future in list(running):
                if future.cancel():
                    running.pop(future)
            for process in list(getattr(pool, "_processes", {}).values()):  # the workers' engines stop
                try:
                    os.kill(process.pid, signal.SIGINT)
                except OSError:
                    pass
            for future in list(running):  # what the running chunks computed
                take(future)
    finally:
        pool.shutdown(wait=True, cancel_futures=True)
    return finished


def _run_dask(plan, ranges, sink, bar, client, threads, options) -> dict:
    from distributed import as_completed

    finished: dict = {}
    window = 2 * max(1, len(client.scheduler_info()["workers"]))
    per_task = threads if threads > 0 else 1
    queue = iter(ranges)
    futures = {}

    def submit():
        for start, stop in itertools.islice(queue, 1):
            future = client.submit(solve_chunk, plan, start, stop, threads=per_task, pure=False, **options)
            futures[future] = (start, stop)
            return future
        return None

    running = as_completed([f for f in (submit() for _ in range(window)) if f is not None])
    done = 0
    try:
        for future in running:
            start, stop = futures.pop(future)
            try:
                chunk = future.result()
            except Exception as error:  # a worker lost or a task failing: its members say why
                chunk = _blank(plan, stop - start, options["trajectories"], options["extrema"])
                chunk["status"][:] = "failed"
                chunk["message"][:] = f"the Dask task failed: {_said(error)}"
                _put_values(chunk, plan, plan.values_range(start, stop))
            sink.put(start, chunk)
            finished[(start, stop)] = True
            done += stop - start
            if bar is not None:
                bar(done / plan.size)
            following = submit()
            if following is not None:
                running.add(following)
    except KeyboardInterrupt:
        finished["interrupted"] = True
        for future in list(futures):
            future.cancel()
    return finished


# ------------------------------------------------------------------------------------ summaries
def check_plot(plan: Plan, expression: str | None, *, trajectories: bool, extrema: Sequence[str] | None = None,
               contour: float | None = None, lines: Sequence[Mapping] | None = None) -> str:
    """What a sweep's plot will show, checked before any member runs against the variables the
    sweep will have: the summary (None: the first final value; returned), the reference lines
    (as many x as y values) and the contour (drawn on a grid over two parameters).

    Parameters
    ----------
    plan : Plan
        The sweep.
    expression : str or None
        The summary (see :func:`summary`).
    trajectories : bool
        Whether the sweep keeps trajectories.
    extrema : sequence of str, optional
        Quantities with minimum and maximum.
    contour : float, optional
        A value of the summary to draw as a contour.
    lines : sequence of dict, optional
        Reference lines (label, x, y).

    Examples
    --------
    >>> from gyrostat import sweeps
    >>> from gyrostat.scene import SCENES
    >>> plan = sweeps.Plan(SCENES / "forced_damped.toml", {"body.moments[2]": [2.5, 3.0]})
    >>> sweeps.check_plot(plan, "max_kinetic_energy - min_kinetic_energy", trajectories=False)
    'max_kinetic_energy - min_kinetic_energy'
    """
    import xarray as xr

    extrema = plan.output_names if extrema is None else tuple(extrema)
    blank = _blank(plan, 1, trajectories, extrema)
    ds = xr.Dataset({name: (("member",) if a.ndim == 1 else ("member", "time"), a, _attributes(plan, name))
                     for name, a in blank.items()})
    expression = expression if expression is not None else f"final_{plan.names[0]}"
    summary(ds, expression)
    for i, line in enumerate(lines or ()):
        if len(line["x"]) != len(line["y"]):
            raise ValueError(f"lines[{i}] ({line['label']!r}): x has {len(line['x'])} values and y "
                             f"{len(line['y'])}: give as many of each")
    if contour is not None and not (plan.mode == "grid" and len(plan.parameters) == 2):
        raise ValueError(f"contour = {contour!r} is a level line on a grid over two parameters; this sweep is a "
                         f"{plan.mode} over {len(plan.parameters)}")
    return expression


_ALLOWED = re.compile(r"[\sA-Za-z0-9_.+\-*/()]*")


def summary(ds, expression: str):
    """A summary of a sweep by name or by an arithmetic expression of its variables
    (``"final_x / final_y"``, ``"max_kinetic_energy - min_kinetic_energy"``): + - * / ** and
    parentheses over the Dataset's variables, nothing else; its ``units`` follow from theirs.

    Parameters
    ----------
    ds : xarray.Dataset
        A sweep's Dataset.
    expression : str
        A variable's name or an expression of them.

    Examples
    --------
    >>> import gyrostat
    >>> from gyrostat.scene import SCENES
    >>> ds = gyrostat.sweep(SCENES / "forced_damped.toml", {"body.moments[2]": [2.5, 3.0]}, trajectories=False,
    ...                     progress=False)
    >>> twice = gyrostat.sweeps.summary(ds, "final_kinetic_energy * 2")
    >>> twice.values.round(4), twice.attrs["units"]
    (array([5.2713, 6.2761]), 'J')
    """
    import ast

    if not isinstance(expression, str) or not _ALLOWED.fullmatch(expression):
        raise ValueError(f"summary {expression!r}: use variable names, numbers, + - * / ** and parentheses")
    tree = ast.parse(expression, mode="eval")

    def evaluate(node):
        """(value, unit) of a node: units travel with the arithmetic ("1": dimensionless)."""
        if isinstance(node, ast.Expression):
            return evaluate(node.body)
        if isinstance(node, ast.Name):
            if node.id not in ds.variables:
                raise ValueError(f"summary {expression!r}: {node.id!r} is not a variable of the sweep "
                                 f"({', '.join(sorted(map(str, ds.data_vars)))})")
            return ds[node.id], ds[node.id].attrs.get("units", "1")
        if isinstance(node, ast.Constant) and isinstance(node.value, (int, float)):
            return node.value, "1"
        if isinstance(node, ast.UnaryOp) and isinstance(node.op, (ast.USub, ast.UAdd)):
            value, unit = evaluate(node.operand)
            return (-value if isinstance(node.op, ast.USub) else value), unit
        if isinstance(node, ast.BinOp) and isinstance(node.op, (ast.Add, ast.Sub, ast.Mult, ast.Div, ast.Pow)):
            (left, a), (right, b) = evaluate(node.left), evaluate(node.right)
            if isinstance(node.op, (ast.Add, ast.Sub)):
                unit = a if a == b else f"{a} and {b} (mixed)"
                return (left + right if isinstance(node.op, ast.Add) else left - right), unit
            if isinstance(node.op, ast.Mult):
                return left * right, " ".join(u for u in (a, b) if u != "1") or "1"
            if isinstance(node.op, ast.Div):
                return left / right, "1" if a == b else (a if b == "1" else f"{a}/({b})")
            return left**right, a if a == "1" else f"({a})^{ast.unparse(node.right)}"
        raise ValueError(f"summary {expression!r}: use variable names, numbers, + - * / ** and parentheses")

    with np.errstate(divide="ignore", invalid="ignore"):
        result, unit = evaluate(tree)
    if not hasattr(result, "dims"):
        raise ValueError(f"summary {expression!r} names no variable of the sweep")
    return result.rename(expression).assign_attrs(units=unit)
