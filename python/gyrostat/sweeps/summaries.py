"""What a sweep's plot shows: :func:`summary` (a variable or an arithmetic expression of the
Dataset's variables, its units following from theirs) and :func:`check_plot` (the summary,
reference lines and contour checked before any member runs)."""

from __future__ import annotations

import re
from collections.abc import Mapping, Sequence

import numpy as np

from gyrostat.sweeps.chunks import _blank
from gyrostat.sweeps.plan import Plan
from gyrostat.sweeps.storage import _attributes

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
