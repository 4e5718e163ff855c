"""The result of a run of any model: times, states and named outputs, statistics, status. One
type for every run: a run joined from pieces (the model ladder's switches) is a
:class:`Solution` too (:meth:`Solution.join`, ``pieces``, ``switches``, ``rung``)."""

from __future__ import annotations

import numpy as np

from gyrostat import _core

from types import SimpleNamespace

_RATES = ("p", "q", "r")
_QUATERNION = ("q_w", "q_x", "q_y", "q_z")


def _no_dense_output(times):
    raise ValueError("a run joined from pieces keeps no dense output: evaluate its pieces (solution.pieces)")


class AccuracyWarning(UserWarning):
    """A run doubts its own answer: the splitting's estimated error exceeds rtol, a fixed step was
    clamped to the span, or BDF stepped over oscillations it damps away. The sentence names the
    measured values and what to do; it is also kept in ``Solution.notes``."""


class Solution:
    """A trajectory of any model, as recorded by the engine.

    Attributes
    ----------
    t: (n,) output times.
    y: (n, dim) states; ``state_names`` names the columns.
    outputs: name → (n,) array of the quantities the engine recorded at each output time
       (invariants such as |G| and T, derived quantities such as Euler angles, τ, g, k²);
       ``output_names`` lists them, ``conserved`` names the first integrals among them.
    solution[name]: a state component or an output by name.
    omega, quaternion: the angular velocity (n, 3) and attitude quaternion (n, 4) where the
       model has them (a clear error otherwise).
    stats: steps, rhs_evals, rejected_steps, jacobian_evals, nonlinear_conv_failures, last_step.
    status: ``"success"`` or why the run stopped (``max_steps_reached``, ``step_size_underflow``,
       ``non_finite_state``, ``solver_failure``, ``invalid_input``, ``interrupted``); a failed
       or interrupted run keeps its partial trajectory.
    message: the reason in words (empty on success).
    t_last, y_last, h_next: where the run stopped and the step it would have tried next; pass
       the solution as ``y0`` to :func:`gyrostat.solve` to continue the run from there.
    method: the integrator asked for (``"auto"`` included), or ``"closed_form"``.
    methods_used, method_switches: the integrators that carried the run, in order of first use;
       for ``method="auto"``, each switch as (t, method, reason): where the run went from DOP853
       to CVODE BDF or back, and the measured h·|λ| that decided it.
    notes: what the run says about its own answer (the splitting's chosen step and estimated
       error; every :class:`AccuracyWarning`), then remarks added after the run (assumptions
       checked, paper-specific analysis).
    pieces, switches, rung: a run joined from pieces (:meth:`join`: a run that switched models
       along the way): the pieces as (name, Solution) in order, each switch as (t, from, to,
       reason), and per output time the index of the model that made it (0: the solution's own
       model; also the column ``rung``). Empty, empty and None for a run of one model.

    The arrays are views of the engine's memory, made on first access: no copy, no physics
    recomputed in Python.
    """

    __slots__ = ("_result", "_columns", "notes", "model", "pieces", "switches", "rung")

    def __init__(self, result: _core.Result, model=None):
        self._result = result
        self._columns = None
        self.notes: list[str] = list(result.notes) + list(result.warnings) if result.notes or result.warnings else []
        self.model = model
        self.pieces: tuple[tuple[str, Solution], ...] = ()
        self.switches: list[tuple] = []
        self.rung: np.ndarray | None = None

    @classmethod
    def join(cls, model, pieces: list[tuple[str, "Solution"]], parts: list[tuple], switches: list[tuple],
             y_last) -> "Solution":
        """One solution of ``model`` from the pieces of a run that switched models: ``pieces``
        (name, Solution) in order, ``parts`` (t, y, outputs, index) of each non-empty piece
        already in ``model``'s state and outputs (index: 0 where ``model`` itself ran), the
        ``switches`` (t, from, to, reason), and the last state in ``model``'s variables. The
        statistics add up; status, message and the step to continue with are the last piece's;
        no output is marked conserved (the pieces' models differ)."""
        core = model._core
        dim, n_out = len(core.state_names), len(core.output_names)
        last = pieces[-1][1]
        stats = {k: sum(sol.stats[k] for _, sol in pieces) for k in last.stats if k != "last_step"}
        result = SimpleNamespace(
            t=np.concatenate([p[0] for p in parts]) if parts else np.zeros(0),
            y=np.vstack([p[1] for p in parts]) if parts else np.zeros((0, dim)),
            outputs=np.vstack([p[2] for p in parts]) if parts else np.zeros((0, n_out)),
            state_names=tuple(core.state_names), output_names=tuple(core.output_names),
            state_units=tuple(q["unit"] for q in core.quantities if q["role"] == "state"),
            output_units=tuple(q["unit"] for q in core.quantities if q["role"] == "output"),
            output_conserved=(False,) * n_out, output_kept=(False,) * n_out, options=last._result.options,
            stats=SimpleNamespace(**stats, last_step=last.stats["last_step"]),
            t_last=last.t_last, y_last=y_last, h_next=last.h_next, status=last.status, message=last.message,
            success=last.success, method="+".join(dict.fromkeys(f"{name}:{sol.method}" for name, sol in pieces)),
            methods_used=(), switches=[], warnings=(), notes=(), t_events=[], y_events=[], event_names=(),
            terminal_event=-1, error_estimate=float("nan"), dense=_no_dense_output)
        joined = cls(result, model)
        joined.pieces, joined.switches = tuple(pieces), list(switches)
        joined.rung = np.concatenate([np.full(len(p[0]), float(p[3])) for p in parts]) if parts else np.zeros(0)
        return joined

    # ---- arrays
    @property
    def t(self) -> np.ndarray:
        return self._result.t

    @property
    def y(self) -> np.ndarray:
        return self._result.y

    @property
    def state_names(self) -> tuple[str, ...]:
        return tuple(self._result.state_names)

    @property
    def output_names(self) -> tuple[str, ...]:
        return tuple(self._result.output_names)

    @property
    def outputs(self) -> dict[str, np.ndarray]:
        values = self._result.outputs
        return {name: values[:, i] for i, name in enumerate(self._result.output_names)}

    @property
    def conserved(self) -> tuple[str, ...]:
        """The outputs that are first integrals of the unperturbed model (|G|, T, G_z, H, …)."""
        return tuple(n for n, c in zip(self._result.output_names, self._result.output_conserved) if c)

    @property
    def kept(self) -> tuple[str, ...]:
        """The first integrals (:attr:`conserved`) this model keeps with its torques, as its C++
        model says (a forced or damped energy is not kept; the cavity keeps |G|)."""
        flags = getattr(self._result, "output_kept", self._result.output_conserved)
        return tuple(n for n, c in zip(self._result.output_names, flags) if c)

    @property
    def invariants(self) -> dict[str, np.ndarray]:
        """The conserved outputs by name (a subset of :attr:`outputs`)."""
        outputs = self.outputs
        return {name: outputs[name] for name in self.conserved}

    def __getitem__(self, name: str) -> np.ndarray:
        if name == "t":
            return self.t
        if self._columns is None:
            self._columns = {name: ("y", i) for i, name in enumerate(self._result.state_names)}
            self._columns.update({name: ("outputs", i) for i, name in enumerate(self._result.output_names)})
        try:
            where, i = self._columns[name]
        except KeyError:
            raise KeyError(f"{name!r} is neither a state component ({', '.join(self.state_names)}) nor an output "
                           f"({', '.join(self.output_names)}) of this solution") from None
        return getattr(self._result, where)[:, i]

    def __contains__(self, name: str) -> bool:
        return name in self._result.state_names or name in self._result.output_names

    @property
    def units(self) -> dict[str, str]:
        """The SI unit of every column (t, each state component, each output; "1":
        dimensionless), as the C++ model declares them."""
        r = self._result
        units = {"t": "s", **dict(zip(r.state_names, r.state_units)), **dict(zip(r.output_names, r.output_units))}
        if self.rung is not None:
            units["rung"] = "1"
        return units

    @property
    def options(self):
        """The options the run was made with (:class:`gyrostat.Options`, without t_eval and events)."""
        return self._result.options

    def columns(self) -> dict[str, np.ndarray]:
        """t, every state component and every output, by name (what the CSV/NPZ writers save)."""
        columns = {"t": self.t}
        y = self.y
        columns.update({name: y[:, i] for i, name in enumerate(self._result.state_names)})
        columns.update(self.outputs)
        if self.rung is not None:
            columns["rung"] = self.rung
        return columns

    @property
    def omega(self) -> np.ndarray:
        """(n, 3) angular velocity in body axes."""
        if tuple(self._result.state_names[:3]) != _RATES:
            raise ValueError(f"this solution has no angular velocity in its state ({', '.join(self.state_names)})")
        return self.y[:, :3]

    @property
    def quaternion(self) -> np.ndarray:
        """(n, 4) attitude quaternion (w, x, y, z), body → inertial."""
        names = self._result.state_names
        if "q_w" not in names:
            raise ValueError(f"this solution has no attitude: its state is ({', '.join(names)}); "
                             "solve a model with attitude (e.g. Model(..., attitude=True))")
        first = names.index("q_w")
        return self.y[:, first:first + 4]

    def euler_angles(self, convention: str = "zxz") -> np.ndarray:
        """(n, 3) Euler angles of the attitude: ``"zxz"`` (ψ precession, θ nutation, φ proper
        rotation; recorded by the engine) or ``"zyx"`` (yaw, pitch, roll). At the singular
        angles the free rotation is put in ψ and φ = 0 (see :mod:`gyrostat.attitude`)."""
        if convention == "zxz" and "psi" in self._result.output_names:
            return np.column_stack([self["psi"], self["theta"], self["phi"]])
        from gyrostat import attitude

        return attitude.euler_angles(self.quaternion, convention)

    # ---- events and dense output
    @property
    def t_events(self) -> list[np.ndarray]:
        """One array per event: the times of its crossings (SciPy's name)."""
        return self._result.t_events

    @property
    def y_events(self) -> list[np.ndarray]:
        """One (k, dim) array per event: the states at its crossings (SciPy's name)."""
        return self._result.y_events

    @property
    def event_names(self) -> tuple[str, ...]:
        return tuple(self._result.event_names)

    @property
    def terminal_event(self) -> int | None:
        """The index of the event that ended the run, or None."""
        index = self._result.terminal_event
        return None if index < 0 else index

    def __call__(self, t) -> np.ndarray:
        """The solution at t (a number or an array of times anywhere in the span), from the
        stored continuous extension of each step (solve with ``dense_output=True``; memory grows
        with the steps taken). The attitude part stays a unit quaternion."""
        from gyrostat.modelbase import floats

        times = floats(t, "t", "a time or times (numbers)")
        values = self._result.dense(times.ravel())
        return values[0] if times.ndim == 0 else values.reshape(times.shape + (values.shape[1],))

    # ---- labelled data
    def to_xarray(self):
        """The solution as an ``xarray.Dataset``: dimension ``time`` (its coordinate, in s), the
        state components and outputs as variables with their units, each event's crossing
        times (``t_event_<name>``), and the method (the methods used and the switches of
        ``"auto"``), status, message and statistics as attributes; ``to_netcdf`` writes it."""
        import xarray as xr

        from gyrostat.events import variable_name

        units = self.units
        variables = {name: ("time", values, {"units": units[name]}) for name, values in self.columns().items()
                     if name != "t"}
        for label, times in zip(self.event_names, self.t_events):
            key = variable_name(label)
            variables[f"t_event_{key}"] = (f"crossing_{key}", np.asarray(times),
                                           {"units": "s", "long_name": f"crossings of {label}"})
        attrs = {"method": self.method, "methods_used": ", ".join(self.methods_used),
                 "method_switches": "\n".join(f"t = {t!r}: {to} ({why})" for t, to, why in self.method_switches),
                 "status": self.status, "message": self.message,
                 **{name: value for name, value in self.stats.items()},
                 "terminal_event": "" if self.terminal_event is None else self.event_names[self.terminal_event]}
        if self.notes:
            attrs["notes"] = "\n".join(self.notes)
        return xr.Dataset(variables, {"time": ("time", np.asarray(self.t), {"units": "s"})}, attrs)

    # ---- run information
    @property
    def stats(self) -> dict[str, float]:
        s = self._result.stats
        return {"steps": s.steps, "rhs_evals": s.rhs_evals, "rejected_steps": s.rejected_steps,
                "jacobian_evals": s.jacobian_evals, "nonlinear_conv_failures": s.nonlinear_conv_failures,
                "last_step": s.last_step}

    @property
    def t_last(self) -> float:
        """Where the run stopped, however it ended (t1, a terminal event, max_steps, a failure,
        Ctrl-C): the last accepted time. ``solve(model, solution, (solution.t_last, t1))``
        continues from there."""
        return self._result.t_last

    @property
    def y_last(self) -> np.ndarray:
        """The state at :attr:`t_last` (the last accepted step, not an interpolated output)."""
        return self._result.y_last

    @property
    def h_next(self) -> float:
        """The step size the integrator would have tried next (0: the method picks its own)."""
        return self._result.h_next

    @property
    def status(self) -> str:
        return self._result.status

    @property
    def message(self) -> str:
        return self._result.message

    @property
    def accuracy_warnings(self) -> tuple[str, ...]:
        """What the run doubts about its own answer (each one an :class:`AccuracyWarning` when
        :func:`gyrostat.solve` returned, and in ``notes``)."""
        return tuple(self._result.warnings)

    @property
    def error_estimate(self) -> float:
        """The run's own global error estimate relative to max|y_i| (``splitting``); NaN: none."""
        return self._result.error_estimate

    @property
    def method(self) -> str:
        return self._result.method

    @property
    def methods_used(self) -> tuple[str, ...]:
        """The integrators that carried the run, in order of first use (one unless ``"auto"``)."""
        return tuple(self._result.methods_used)

    @property
    def method_switches(self) -> list[tuple[float, str, str]]:
        """Method ``"auto"``: each switch as (t, the method switched to, the reason with the
        measured h·|λ|); empty for the other methods."""
        return self._result.switches

    @property
    def success(self) -> bool:
        return self._result.success

    def raise_for_status(self) -> "Solution":
        """Raises RuntimeError with the message when the run failed; returns self otherwise."""
        if not self.success:
            raise RuntimeError(f"{self.method}: {self.status}: {self.message}")
        return self

    def __len__(self) -> int:
        return len(self._result.t)

    def __repr__(self) -> str:
        t = self.t
        span = f"t in [{t[0]:.6g}, {t[-1]:.6g}]" if len(t) else "no outputs"
        return (f"<Solution {self.method}: {self.status}, {len(t)} outputs, {span}; state ({', '.join(self.state_names)});"
                f" outputs ({', '.join(self.output_names)})>")
