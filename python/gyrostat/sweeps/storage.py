"""Where a sweep's results go: every member's arrays in memory (at most :data:`MEMORY_LIMIT`
bytes) or each chunk appended to a NetCDF file as it arrives; each variable's units and
description; the Dataset a user sees (a grid on its parameters' axes), and :func:`open_sweep`
for a sweep written to a file."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np

from gyrostat.schema import locate
from gyrostat.sweeps.chunks import STATS, _blank
from gyrostat.sweeps.parameters import parse_path
from gyrostat.sweeps.plan import Plan

MEMORY_LIMIT = 4 * 2**30
"""Bytes a sweep may keep in memory (trajectories and summaries); beyond it a sweep asks for
``trajectories=False`` or ``path=`` (streaming to a file) before it starts."""


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
             "accuracy_warning": {"description": "the first doubt the run had about its own answer (the accuracy "
                                                 "asked not met, the splitting's estimated error above rtol, BDF over "
                                                 "oscillations); empty: none"},
             "error_estimate": {"units": "1", "description": "the member's measured global error, relative "
                                                             "(gyrostat.accuracy; NaN: not measured)"}}
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
