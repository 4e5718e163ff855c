"""Forward sensitivities of a run: the derivatives ∂y(t)/∂p of the solution with respect to the
initial state's components and to the model's parameters, integrated with the solution by the
engine's variational equations (``cpp/include/gyrostat/model/variational.hpp``) on the augmented
state: by DOP853 (the default, ``integrate/variational.hpp``), CVODE's BDF (``method="cvode_bdf"``,
``integrate/variational_bdf.hpp``) or, for the gyrostat under constant and linear torques, whose
variational equations are polynomial, the Taylor method (``method="taylor"``,
``integrate/variational_taylor.hpp``; the engine refuses it for the other models and torques).

A parameter is named as a user writes it (:func:`parameter_names` lists a model's):

* ``"moments[k]"``, ``"rotor[k]"``: the body's principal moment or rotor momentum component k (a
  body given by its principal moments); ``"inertia[i,j]"`` (i ≤ j, the symmetric pair moved
  together) and ``"rotor[k]"`` for a body given by its inertia tensor with products of inertia
  (the principal axes the model runs in turn with the entry: the moved models' right-hand sides
  are taken through the user's frame, ``model/variational.hpp``);
* ``"<Torque>.<parameter>"``, ``"<Torque>.<parameter>[i]"``, ``"<Torque>.<parameter>[i,j]"`` (and
  ``[k,i,j]`` for a list of matrices): a stored parameter of a torque the model holds once (e.g.
  ``"ViscousCavity.viscosity"``, ``"LinearDamping.matrix[0,0]"``), or ``"torques[n]."`` + the same
  for its n-th torque; one matrix entry moves alone (D[0,1] without D[1,0]);
* a family's own numbers by their attribute names (the moving mass's ``"mass"``, ``"arm"``,
  ``"frequency"``, ``"damping"``; the Lagrange top's ``"A"``, ``"C"``, ``"mu"``).

∂f/∂p is the central difference of the right-hand side between the model built with the parameter
moved by ±h, h = ε^(1/3) |p| (truncation ~1e-11 relative; exact up to rounding where the right-hand
side is affine in p, as in every torque's gain). A ``CustomTorque`` given ``parameters`` (its
function made by a factory) offers them by name (``"CustomTorque.c"``): the factory is called again
with c moved, and ∂M/∂c is the difference quotient of the two torques made (the run's notes say
so); one given without parameters offers none.
"""

from __future__ import annotations

import re
from collections.abc import Callable, Mapping

import numpy as np

from gyrostat import _core
from gyrostat.accuracy import span_estimates, tighter

STEP = float(np.finfo(float).eps) ** (1.0 / 3.0)  # a central difference's best relative step
PARAMETER_FLOOR = 1e-10
"""The least error a parameter's sensitivity reports: its ∂f/∂p is a central difference (~ε^(2/3)
≈ 4e-11 relative per evaluation) that a companion at tighter tolerances repeats, not measures."""


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


_STORED: dict[type, list[str]] = {}  # a torque type's stored parameters, read once from its declaration


def _torque_parameters(torque, only: str | None = None) -> dict[str, tuple[float, float, Callable, int]]:
    """A torque's stored parameters (or the entry named ``only``, e.g. ``matrix[2,2]``): suffix →
    (value, scale, rebuild(new value) → torque, the power k of M ∝ p^k it declares: 1 for its
    ``affine_in``, −1 for its ``inverse_in``, 0 for neither)."""
    stored = _STORED.get(type(torque))
    if stored is None:
        stored = _STORED[type(torque)] = [p["name"] for p in torque.parameters if p["stored"]]
    wanted, _, entry = (only or "").partition("[")
    made = {}
    for name in stored if only is None else [n for n in stored if n == wanted]:
        value = getattr(torque, name)
        if value is None:  # not given (an orbit torque's own orbit, where the model gives the orbit)
            continue
        scale = float(np.max(np.abs(value))) if np.size(value) else 0.0
        for suffix, index in _entries(value):
            if only is not None and suffix != ("[" + entry if entry else ""):
                continue
            def rebuild(new, name=name, value=value, index=index):
                arguments = {p: getattr(torque, p) for p in stored if getattr(torque, p) is not None}  # (None: not given)
                arguments[name] = _moved(value, index, new)
                return type(torque)(**arguments)
            made[f"{name}{suffix}"] = (float(np.asarray(value, dtype=float)[index]), scale, rebuild,
                                       1 if name in type(torque).affine_in else -1 if name in type(torque).inverse_in
                                       else 0)
    return made


def _custom_parameters(torque, only: str | None = None) -> dict[str, tuple[float, float, Callable, int]]:
    """A ``CustomTorque``'s parameters (the keyword arguments its factory was called with that are
    numbers), as :func:`_torque_parameters` gives a declared torque's: moved by calling the factory
    again."""
    arguments = torque.arguments
    numbers = [n for n, v in arguments.items() if isinstance(v, (int, float, np.floating, np.integer))
               and not isinstance(v, bool)]
    made = {}
    for name in numbers if only is None else [n for n in numbers if n == only]:
        def rebuild(new, name=name):
            return type(torque)(torque.factory, torque.jacobian_factory, attitude=torque.attitude, name=torque.name,
                                parameters={**arguments, name: new})
        made[name] = (float(arguments[name]), abs(float(arguments[name])), rebuild, 0)
    return made


def _body_parameters(body, rebuilt: Callable) -> dict[str, tuple[float, float, Callable, int]]:
    """A body's parameters: by its principal moments, ``moments[k]`` and ``rotor[k]``; by its
    inertia tensor, ``inertia[i,j]`` (i ≤ j; the symmetric pair moves together, and the principal
    axes turn with it) and ``rotor[k]`` (the user's axes)."""
    made = {}
    tensor, rotor = np.array(body.inertia, dtype=float), np.array(body.rotor, dtype=float)
    if body.principal:
        moments = np.array(body.moments, dtype=float)
        for vector, values in (("moments", moments), ("rotor", rotor)):
            for k in range(3):
                def rebuild(new, vector=vector, k=k):
                    kept = {"moments": moments.copy(), "rotor": rotor.copy()}
                    kept[vector][k] = new
                    return rebuilt(body=_core.Body(moments=kept["moments"], rotor=kept["rotor"]))
                made[f"{vector}[{k}]"] = (float(values[k]), float(np.max(np.abs(values))), rebuild, 0)
        return made
    for i in range(3):
        for j in range(i, 3):
            def rebuild(new, i=i, j=j):
                changed = tensor.copy()
                changed[i, j] = changed[j, i] = new
                return rebuilt(body=_core.Body(inertia=changed, rotor=rotor))
            made[f"inertia[{i},{j}]"] = (float(tensor[i, j]), float(np.max(np.abs(tensor))), rebuild, 0)
    for k in range(3):
        def rebuild(new, k=k):
            changed = rotor.copy()
            changed[k] = new
            return rebuilt(body=body.with_rotor(changed))  # (the same axes: a tensor given again turns them by 1e-16)
        made[f"rotor[{k}]"] = (float(rotor[k]), float(np.max(np.abs(rotor))), rebuild, 0)
    return made


def parameters(model, only: str | None = None) -> dict[str, tuple[float, float, Callable, int]]:
    """Every parameter a model offers (or those of the one named ``only``, made alone): name →
    (value, its scale, rebuild(new value) → the model with that parameter changed, the power k of
    the right-hand side's torque term M ∝ p^k its torque or model declares: 1 affine, −1 inversely
    proportional, 0 neither). Empty for a model that cannot be rebuilt (a closed form)."""
    arguments = getattr(model, "_arguments", None)
    if arguments is None:
        return {}
    given = arguments()
    made: dict[str, tuple[float, float, Callable, int]] = {}

    def rebuilt(**changes):
        return type(model)(**{**given, **changes})

    selector, _, wanted_parameter = (only or "").partition(".")
    body = given.get("body")
    if body is not None and (only is None or only.startswith(("moments[", "rotor[", "inertia["))):
        made.update(_body_parameters(body, rebuilt))
    torques = tuple(given.get("torques", ()))
    kinds = [type(t).__name__ for t in torques]
    for n, torque in enumerate(torques):
        if only is not None and selector not in (f"torques[{n}]", kinds[n]):
            continue
        own = _custom_parameters if kinds[n] == "CustomTorque" else _torque_parameters
        for suffix, (value, scale, rebuild_torque, power) in own(torque, wanted_parameter or None).items():
            def rebuild(new, n=n, rebuild_torque=rebuild_torque):
                changed = list(torques)
                changed[n] = rebuild_torque(new)
                return rebuilt(torques=changed)
            made[f"torques[{n}].{suffix}"] = (value, scale, rebuild, power)
            if kinds.count(kinds[n]) == 1:
                made[f"{kinds[n]}.{suffix}"] = (value, scale, rebuild, power)
    for name in getattr(model, "_numbers", ()) if only is None else [n for n in getattr(model, "_numbers", ()) if n == only]:
        value = float(given[name])
        made[name] = (value, abs(value), lambda new, name=name: rebuilt(**{name: new}),
                      int(name in model._core.affine_in))
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
    cache = model.__dict__.setdefault("_sensitivity_columns", {})  # the moved models, built once per model
    key = (names, atol)
    try:
        return cache[key]
    except (KeyError, TypeError):  # (not made yet; or a name that is not hashable, refused below)
        pass
    if not all(isinstance(name, str) for name in names):
        return _columns(model, names, atol)  # (refused there, by name)
    made = _columns(model, names, atol)
    if len(cache) < 64:
        cache[key] = made
    return made


def _columns(model, names: tuple, atol: float) -> tuple[tuple[str, ...], list[tuple]]:
    if not names:
        raise ValueError("sensitivities: give at least one name (a state component or a parameter)")
    states = list(model.state_names)
    made = []
    for name in names:
        if not isinstance(name, str) or not _NAME.match(name.replace(" ", "")):
            raise ValueError(f"sensitivities: {name!r} is not a name")
        name = name.replace(" ", "")
        if name in states:
            made.append((states.index(name), None, None, 0.0, atol))
            continue
        offered = parameters(model, name)
        if name not in offered:
            offered = parameters(model)
            raise ValueError(f"sensitivities: no parameter or state component {name!r} in this "
                             f"{type(model).__name__}; state: {', '.join(states)}; parameters: "
                             + (", ".join(offered) if offered else "none"))
        value, scale, rebuild, power = offered[name]
        size = max(abs(value), scale) or 1.0
        step = STEP * size
        try:
            plus, minus = rebuild(value + step), rebuild(value - step)
        except (ValueError, TypeError) as error:
            raise ValueError(f"sensitivities: {name} = {value!r} cannot be moved by ±{step:.3g}: {error}") from None
        # the rate's one-sided difference, exact to rounding, to the model moved by the parameter's own
        # size: f(p + |p|) − f(p) = far_step · ∂f/∂p, far_step = |p| where f is affine in p, and p/2
        # where M ∝ 1/p (the move doubles p: (2^k − 1) p / k with k = −1)
        far, far_step = None, size
        inverse = power == -1 and value > 0 and size == value
        if power == 1 or inverse:
            far_step = size if power == 1 else (2.0 ** power - 1.0) * value / power
            try:
                far = rebuild(value + size)._core
            except (ValueError, TypeError):
                far = None  # (a move that large breaks a rule of the model's: the central difference)
        analytic = model._core.analytic_in
        if name in analytic:  # the model's own closed form of the rate's derivative (the moved models give the start's)
            made.append((-1, plus._core, minus._core, step, atol / size, far, far_step, analytic.index(name)))
        else:
            made.append((-1, plus._core, minus._core, step, atol / size, far, far_step))
    if len(set(names)) != len(names):
        raise ValueError(f"sensitivities: a name is asked twice in {list(names)}")
    return tuple(name.replace(" ", "") for name in names), made


def attach(solution, names: tuple[str, ...], state: np.ndarray, outputs: np.ndarray, events=None, dense=None,
           errors=None) -> None:
    """Gives a Solution its sensitivities (``Solution.sensitivity``); ``events[k]``: (occurrences,
    columns) ∂t/∂p of event k's occurrences; ``dense``: the variational run's Result whose dense
    output keeps them between the output times (``Result.dense_whole``: the state, then each
    column's block)."""
    solution._sensitivities = Columns(names, state, outputs, events, dense)
    if errors is not None:
        solution._sensitivity_errors, basis = errors
        solution.notes.append(f"sensitivities' error estimate: {basis}")
    for name in names:  # (a user's torque's parameter is named by its torque)
        if name.startswith(("torques[", "CustomTorque")):
            break
    else:
        return
    for name in _of_custom_torques(solution.model, names):
        solution.notes.append(f"sensitivity to {name}: dM/d{name.partition('.')[2]} of the user's torque is the central "
                              f"difference quotient of the torques its factory made with the parameter moved by "
                              f"±{STEP:.1e} of its size (truncation ~1e-11 relative where M is smooth in it)")


class Columns(Mapping):
    """A run's sensitivities by name: name → (∂y/∂p [time, component], ∂outputs/∂p [time, output],
    per event ∂t/∂p of its occurrences or None, (the variational Result, column) for its dense
    output or None); each entry's views made when it is read, so that attaching them to a run costs
    nothing per name."""

    __slots__ = ("_names", "_state", "_outputs", "_events", "_dense")

    def __init__(self, names: tuple[str, ...], state: np.ndarray, outputs: np.ndarray, events=None, dense=None):
        self._names, self._state, self._outputs, self._events, self._dense = names, state, outputs, events, dense

    def __getitem__(self, name: str) -> tuple:
        try:
            j = self._names.index(name)
        except ValueError:
            raise KeyError(name) from None
        dense = self._dense
        return (self._state[:, :, j], self._outputs[:, :, j],
                None if self._events is None else [times[:, j] for times in self._events],
                None if dense is None or not dense.has_dense else (dense, j))

    def __iter__(self):
        return iter(self._names)

    def __len__(self) -> int:
        return len(self._names)

    def __contains__(self, name) -> bool:
        return name in self._names


def _of_custom_torques(model, names) -> list[str]:
    """The names among ``names`` that are a ``CustomTorque``'s parameters (found once per model
    and names, as :func:`columns` builds its moved models once)."""
    cache = model.__dict__.setdefault("_sensitivity_custom", {}) if hasattr(model, "__dict__") else {}
    key = tuple(names)
    found = cache.get(key)
    if found is None:
        found = cache[key] = _custom_torque_names(model, key)
    return found


def _custom_torque_names(model, names: tuple) -> list[str]:
    arguments = getattr(model, "_arguments", None)
    torques = list(arguments().get("torques", ())) if arguments is not None else []
    kinds = [type(t).__name__ for t in torques]
    found = []
    for name in names:
        selector = name.partition(".")[0]
        n = int(selector[8:-1]) if selector.startswith("torques[") and selector[8:-1].isdigit() else None
        if (selector == "CustomTorque" and "CustomTorque" in kinds) or (n is not None and n < len(kinds)
                                                                        and kinds[n] == "CustomTorque"):
            found.append(name)
    return found


def along(core, columns_made: list, y0, t0: float, plain, opts, events, report) -> tuple:
    """The sensitivities of a run made already (``plain``: its events and dense output the
    engine's), at its output times and its events' times: (∂y/∂p, ∂outputs/∂p, per event the
    (occurrences, columns) ∂t_event/∂p, the variational run's Result: its dense output with
    ``dense_output``). The variational run goes to where ``plain`` stopped (a
    terminal event), its output times those of ``plain`` and every event's.

    An event g(t, y) = 0 at t_e moves with p as ∂t_e/∂p = −(∂g/∂y · S + ∂g/∂p) / (dg/dt) (the
    implicit function theorem; dg/dt = ∂g/∂t + ∂g/∂y · f): for an event on a state component, g's
    gradient is that component's row of S and dg/dt its rate; on a named output, its sensitivity
    (explicit dependence on p included) and the central difference of the output along (1, f); on
    a function of the user's, central differences of it along S_j and along (1, f)."""
    from gyrostat.options import make_options  # (options are a floor below: imported where used)

    occurrences = [np.asarray(t, dtype=float) for t in plain.t_events]
    times = np.concatenate([np.asarray(plain.t, dtype=float)] + occurrences) if len(plain.t) or occurrences else np.zeros(0)
    direction = 1.0 if plain.t_last >= t0 else -1.0
    times = np.unique(times) if direction > 0 else -np.unique(-times)
    made = make_options(opts)
    made.events, made.t_eval = [], times  # (dense_output as asked: the sensitivities' own, between the outputs)
    end = float(plain.t_last) if np.isfinite(plain.t_last) else float(times[-1] if len(times) else t0)
    result, state, outputs = _core.solve_sensitivities(core, columns_made, y0, t0, end, made, report)
    if not result.success:
        raise RuntimeError(f"the sensitivities' run did not reach t = {end!r} where the run with events stopped: "
                           f"{result.message}")
    reached = np.asarray(result.t)
    rows = np.searchsorted(reached, plain.t) if direction > 0 else np.searchsorted(-reached, -np.asarray(plain.t))
    listed = list(events) if isinstance(events, (list, tuple)) else [events]
    derivatives = []
    for k, when in enumerate(occurrences):
        at = np.searchsorted(reached, when) if direction > 0 else np.searchsorted(-reached, -when)
        derivatives.append(np.array([_event_time_derivative(core, listed[k] if k < len(listed) else None,
                                                            reached[j], result.y[j], state[j], outputs[j])
                                     for j in at]).reshape(len(when), len(columns_made)))
    return state[rows], outputs[rows], derivatives, result


def _event_time_derivative(core, event, t: float, y: np.ndarray, state: np.ndarray, outputs: np.ndarray) -> np.ndarray:
    """∂t_e/∂p for every column at one occurrence (NaN for an engine event given as it is)."""
    from gyrostat.events import Event

    rate = np.asarray(core.rhs(t, y), dtype=float)
    delta = STEP * max(float(np.linalg.norm(y)), 1e-300) / max(float(np.linalg.norm(rate)), 1e-300)
    if isinstance(event, Event) and event.quantity in core.state_names:
        index = list(core.state_names).index(event.quantity)
        gradient, change = state[index], rate[index]
    elif isinstance(event, Event):
        index = list(core.output_names).index(event.quantity)
        gradient = outputs[index]
        change = (core.outputs_at(t + delta, y + delta * rate)[index]
                  - core.outputs_at(t - delta, y - delta * rate)[index]) / (2 * delta)
    elif callable(event):
        gradient = np.empty(state.shape[1])
        for j in range(state.shape[1]):
            s = state[:, j]
            step = STEP * max(float(np.linalg.norm(y)), 1e-300) / max(float(np.linalg.norm(s)), 1e-300)
            gradient[j] = (event(t, y + step * s) - event(t, y - step * s)) / (2 * step) if np.any(s) else 0.0
        change = (event(t + delta, y + delta * rate) - event(t - delta, y - delta * rate)) / (2 * delta)
    else:
        return np.full(state.shape[1], np.nan)
    return -np.asarray(gradient, dtype=float) / change


def check(asked, opts) -> None:
    """What a run with sensitivities cannot take, refused by name (the accuracy contract, another method)."""
    if asked is not None:
        raise ValueError("sensitivities are integrated at the rtol and atol given (the variational equations by "
                         "dop853): the accuracy contract does not choose them yet; give rtol instead of accuracy")
    if opts.method not in ("dop853", "cvode_bdf", "taylor"):
        raise ValueError(f"sensitivities are integrated by dop853, cvode_bdf or taylor (the variational equations), "
                         f"not by method {opts.method!r}: leave method out (dop853), or give 'cvode_bdf' for a stiff "
                         f"model, 'taylor' for a gyrostat under constant and linear torques")


class MemberResults(list):
    """The members' engine Results (a list, as :func:`gyrostat.solve.ensemble_results` gives them),
    with each member's sensitivities beside: ``sensitivities[i]`` = (names, ∂y/∂p, ∂outputs/∂p),
    the arrays [time, component, column]."""

    sensitivities: list


def ensemble(models, cores, y0s, t0, t1, opts, names, threads: int, report) -> MemberResults:
    """Every member's run with its sensitivities (``_core.solve_sensitivities_ensemble``), each
    member's parameters moved on its own model."""
    made = [columns(model, names, opts.atol) for model in models]
    runs = _core.solve_sensitivities_ensemble(cores, [c for _, c in made], y0s, t0, t1, opts, threads, report)
    results = MemberResults(result for result, _, _ in runs)
    results.sensitivities = [(made[0][0], state, outputs, None, result) for result, state, outputs in runs]
    return results


def ensemble_along(models, cores, y0s, t0, opts, names, plain: list, events) -> MemberResults:
    """Every member's sensitivities along its run made already (with events or dense output:
    :func:`along`, one member after another); a member whose run failed has none (empty arrays)."""
    results = MemberResults(plain)
    results.sensitivities = []
    for i, result in enumerate(plain):
        model, core = (models[0], cores[0]) if len(models) == 1 else (models[i], cores[i])
        names_made, made = columns(model, names, opts.atol)
        dense = None
        if result.success:
            state, outputs, times, dense = along(core, made, y0s[i], t0, result, opts, events, None)
        else:
            state, outputs = np.zeros((0, core.dim, len(made))), np.zeros((0, len(core.output_names), len(made)))
            times = [np.zeros((0, len(made))) for _ in result.t_events]
        results.sensitivities.append((names_made, state, outputs, times, dense))
    return results


def measure(cores, column_sets, y0s, t0: float, t1: float, opts, states, names, threads: int = 1) -> list:
    """Each run's sensitivities' global errors, measured: the same variational runs at tighter
    tolerances (:func:`gyrostat.accuracy.tighter`: rtol and atol ρ times smaller) at the same
    output times (:func:`compared`). Per run: ({name: relative error (NaN: not measured)}, the
    basis in words)."""
    made, gain, words = tighter(opts)
    if not np.isfinite(gain):
        return [({name: np.nan for name in names}, f"not measured: {words}")] * len(states)
    runs = _core.solve_sensitivities_ensemble(cores, column_sets, y0s, t0, t1, made, threads, None)
    sets = column_sets * len(states) if len(column_sets) == 1 else column_sets
    return [compared(names, columns_made, state, tight, gain, words)
            for (_, tight, _), state, columns_made in zip(runs, states, sets)]


def compared(names, columns_made, state, tight, gain: float, words: str) -> tuple[dict, str]:
    """A run's sensitivities against its companion's (``tight``, rows from the same output times):
    each one's largest difference relative to its largest size, times the companion's gain ρ/(ρ−1)
    (the run's own error, the companion's being ρ^(order) times smaller). A parameter's column is
    given at least PARAMETER_FLOOR: the central difference of the right-hand side between the moved
    models is the same in both runs, and no companion sees its error (measured against heyoka: up to
    8.5e-11 for a moment of inertia at rtol 1e-10)."""
    basis = (f"each against the same run with {words}, the largest difference over the output times relative to "
             f"the sensitivity's largest size, times {gain:.3g}; a parameter's at least {PARAMETER_FLOOR:g} (its "
             f"central difference of the right-hand side)")
    rows = len(state)
    errors = {}
    for j, name in enumerate(names):
        if tight is None or len(tight) < rows or rows == 0 or not np.isfinite(gain):
            errors[name] = np.nan
            continue
        size = max(float(np.max(np.abs(tight[:rows, :, j]))), 1e-300)
        errors[name] = gain * float(np.max(np.abs(state[:, :, j] - tight[:rows, :, j]))) / size
        if columns_made[j][0] < 0:
            errors[name] = max(errors[name], PARAMETER_FLOOR)
    return errors, basis


def estimates(cores, column_sets, y0s, t0: float, opts, results, states, names, threads: int = 1) -> tuple[list, list]:
    """The errors of runs made with their sensitivities (the variational runs are the answers: their
    states are more accurate than a plain run's at the same rtol, since each sensitivity's error is
    controlled with the state's), from one companion each: the same variational run at tighter
    tolerances over the whole span (:func:`gyrostat.accuracy.span_estimates`), which measures the
    state (each run's Estimate) and the sensitivities (:func:`compared`). Returns (Estimates,
    sensitivities' errors), per run."""
    kept: dict = {}
    one = len(cores) == 1

    def runner(o, t_end, members):
        runs = _core.solve_sensitivities_ensemble([cores[0 if one else m] for m in members],
                                                  [column_sets[0 if one else m] for m in members],
                                                  [y0s[m] for m in members], t0, t_end, o, threads, None)
        kept.update(zip(members, runs))
        return [run[0] for run in runs]

    members = [i for i, r in enumerate(results) if r.success and len(r.t) and r.t_last != t0]
    made_estimates: list = [None] * len(results)
    spans = span_estimates(runner, [cores[0 if one else i] for i in range(len(results))], opts, t0, list(results),
                           members)
    for m, e in zip(members, spans):
        made_estimates[m] = e
    _, gain, words = tighter(opts)
    errors = [compared(names, column_sets[0 if one else i], states[i], kept[i][1] if i in kept else None, gain, words)
              for i in range(len(results))]
    return made_estimates, errors
