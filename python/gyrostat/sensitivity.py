"""Forward sensitivities of a run: the derivatives ∂y(t)/∂p of the solution with respect to the
initial state's components and to the model's parameters, integrated with the solution by the
engine's variational equations (``cpp/include/gyrostat/model/variational.hpp``; DOP853 on the
augmented state, ``integrate/variational.hpp``).

A parameter is named as a user writes it (:func:`parameter_names` lists a model's):

* ``"moments[k]"``, ``"rotor[k]"``: the body's principal moment or rotor momentum component k
  (a body given by its principal moments; the inertia tensor's entries are not offered: moving one
  turns the principal axes the model runs in);
* ``"<Torque>.<parameter>"``, ``"<Torque>.<parameter>[i]"``, ``"<Torque>.<parameter>[i,j]"`` (and
  ``[k,i,j]`` for a list of matrices): a stored parameter of a torque the model holds once (e.g.
  ``"ViscousCavity.viscosity"``, ``"LinearDamping.matrix[0,0]"``), or ``"torques[n]."`` + the same
  for its n-th torque; one matrix entry moves alone (D[0,1] without D[1,0]);
* a family's own numbers by their attribute names (the moving mass's ``"mass"``, ``"arm"``,
  ``"frequency"``, ``"damping"``; the Lagrange top's ``"A"``, ``"C"``, ``"mu"``).

∂f/∂p is the central difference of the right-hand side between the model built with the parameter
moved by ±h, h = ε^(1/3) |p| (truncation ~1e-11 relative; exact up to rounding where the right-hand
side is affine in p, as in every torque's gain). A ``CustomTorque``'s parameters are the user's
function's own and are not offered.
"""

from __future__ import annotations

import re
from collections.abc import Callable

import numpy as np

from gyrostat import _core

STEP = float(np.finfo(float).eps) ** (1.0 / 3.0)  # a central difference's best relative step


def _entries(value) -> list[tuple[str, tuple]]:
    """The suffix and index of every entry of a parameter's value (scalar, vector, matrix, matrices)."""
    array = np.asarray(value, dtype=float)
    if array.ndim == 0:
        return [("", ())]
    return [("[" + ",".join(map(str, index)) + "]", index) for index in np.ndindex(*array.shape)]


def _moved(value, index: tuple, new: float):
    array = np.array(value, dtype=float)
    if array.ndim == 0:
        return float(new)
    array[index] = new
    return [m for m in array] if array.ndim == 3 else array


def _torque_parameters(torque) -> dict[str, tuple[float, float, Callable]]:
    """A torque's stored parameters: suffix → (value, scale, rebuild(new value) → torque)."""
    stored = [p["name"] for p in torque.parameters if p["stored"]]
    made = {}
    for name in stored:
        value = getattr(torque, name)
        scale = float(np.max(np.abs(value))) if np.size(value) else 0.0
        for suffix, index in _entries(value):
            def rebuild(new, name=name, value=value, index=index):
                arguments = {p: getattr(torque, p) for p in stored}
                arguments[name] = _moved(value, index, new)
                return type(torque)(**arguments)
            made[f"{name}{suffix}"] = (float(np.asarray(value, dtype=float)[index]), scale, rebuild)
    return made


def parameters(model) -> dict[str, tuple[float, float, Callable]]:
    """Every parameter a model offers: name → (value, its scale, rebuild(new value) → the model
    with that parameter changed). Empty for a model that cannot be rebuilt (a closed form)."""
    arguments = getattr(model, "_arguments", None)
    if arguments is None:
        return {}
    given = arguments()
    made: dict[str, tuple[float, float, Callable]] = {}

    def rebuilt(**changes):
        return type(model)(**{**given, **changes})

    body = given.get("body")
    if body is not None and body.principal:
        for vector in ("moments", "rotor"):
            values = np.array(getattr(body, vector), dtype=float)
            for k in range(3):
                def rebuild(new, vector=vector, k=k, values=values):
                    changed = values.copy()
                    changed[k] = new
                    kept = {"moments": body.moments, "rotor": body.rotor}
                    kept[vector] = changed
                    return rebuilt(body=_core.Body(moments=kept["moments"], rotor=kept["rotor"]))
                made[f"{vector}[{k}]"] = (float(values[k]), float(np.max(np.abs(values))), rebuild)
    torques = tuple(given.get("torques", ()))
    kinds = [type(t).__name__ for t in torques]
    for n, torque in enumerate(torques):
        if kinds[n] == "CustomTorque":
            continue
        for suffix, (value, scale, rebuild_torque) in _torque_parameters(torque).items():
            def rebuild(new, n=n, rebuild_torque=rebuild_torque):
                changed = list(torques)
                changed[n] = rebuild_torque(new)
                return rebuilt(torques=changed)
            made[f"torques[{n}].{suffix}"] = (value, scale, rebuild)
            if kinds.count(kinds[n]) == 1:
                made[f"{kinds[n]}.{suffix}"] = (value, scale, rebuild)
    for name in getattr(model, "_numbers", ()):
        value = float(given[name])
        made[name] = (value, abs(value), lambda new, name=name: rebuilt(**{name: new}))
    return made


def parameter_names(model) -> tuple[str, ...]:
    """The names :func:`gyrostat.solve`'s ``sensitivities`` takes for this model's parameters (its
    state components' names are taken as well: the initial state's).

    Examples
    --------
    >>> import gyrostat
    >>> cavity = gyrostat.ViscousCavity(density=1.0, viscosity=0.1, p0=0.5)
    >>> model = gyrostat.Model(gyrostat.Body([1.0, 1.4, 2.1]), [cavity])
    >>> gyrostat.sensitivity.parameter_names(model)[::2]
    ('moments[0]', 'moments[2]', 'rotor[1]', 'torques[0].density', 'torques[0].viscosity', 'torques[0].p0')
    >>> gyrostat.sensitivity.parameter_names(gyrostat.lagrange.LagrangeTop(2.0, 1.0, 0.5))
    ('A', 'C', 'mu')
    """
    return tuple(parameters(model))


_NAME = re.compile(r"^[A-Za-z_][\w.\[\],]*$")


def columns(model, names, atol: float) -> tuple[tuple[str, ...], list[tuple]]:
    """The names asked (one str or a list) and the engine's columns for them (``_core.solve_sensitivities``)."""
    names = (names,) if isinstance(names, str) else tuple(names)
    if not all(isinstance(name, str) for name in names):
        return _columns(model, names, atol)  # (refused there, by name)
    cache = model.__dict__.setdefault("_sensitivity_columns", {})  # the moved models, built once per model
    key = (names, atol)
    if key in cache:
        return cache[key]
    made = _columns(model, names, atol)
    if len(cache) < 64:
        cache[key] = made
    return made


def _columns(model, names: tuple, atol: float) -> tuple[tuple[str, ...], list[tuple]]:
    if not names:
        raise ValueError("sensitivities: give at least one name (a state component or a parameter)")
    states = list(model.state_names)
    offered = None
    made = []
    for name in names:
        if not isinstance(name, str) or not _NAME.match(name.replace(" ", "")):
            raise ValueError(f"sensitivities: {name!r} is not a name")
        name = name.replace(" ", "")
        if name in states:
            made.append((states.index(name), None, None, 0.0, atol))
            continue
        if offered is None:
            offered = parameters(model)
        if name not in offered:
            raise ValueError(f"sensitivities: no parameter or state component {name!r} in this "
                             f"{type(model).__name__}; state: {', '.join(states)}; parameters: "
                             + (", ".join(offered) if offered else "none"))
        value, scale, rebuild = offered[name]
        size = max(abs(value), scale) or 1.0
        step = STEP * size
        try:
            plus, minus = rebuild(value + step), rebuild(value - step)
        except (ValueError, TypeError) as error:
            raise ValueError(f"sensitivities: {name} = {value!r} cannot be moved by ±{step:.3g}: {error}") from None
        made.append((-1, plus._core, minus._core, step, atol / size))
    if len(set(names)) != len(names):
        raise ValueError(f"sensitivities: a name is asked twice in {list(names)}")
    return tuple(name.replace(" ", "") for name in names), made


def attach(solution, names: tuple[str, ...], state: np.ndarray, outputs: np.ndarray) -> None:
    """Gives a Solution its sensitivities (``Solution.sensitivity``)."""
    solution._sensitivities = {name: (state[:, :, j], outputs[:, :, j]) for j, name in enumerate(names)}
