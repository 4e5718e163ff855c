"""The labelled-data, attitude and error views of a :class:`gyrostat.Solution`: every column by name
with its unit (:meth:`~SolutionViews.columns`, :attr:`~SolutionViews.units`), the whole run as an
``xarray.Dataset`` (:meth:`~SolutionViews.to_xarray`), the angular velocity, the attitude
quaternion and its Euler angles, the measured error (:attr:`~SolutionViews.error_estimate`). Made
from what the Solution holds, without physics recomputed
(the Euler angles of a convention the engine did not record come from :mod:`gyrostat.attitude`)."""

from __future__ import annotations

import re

import numpy as np

_RATES = ("p", "q", "r")


def sensitivity_column(quantity: str, name: str) -> str:
    """The column of ∂quantity/∂name in files and Datasets: ``d_<quantity>__d_<name>``, the name's
    brackets and commas as underscores (``LinearDamping.matrix[0,1]`` → ``LinearDamping.matrix_0_1``)."""
    return f"d_{quantity}__d_" + re.sub(r"[^0-9A-Za-z_.]+", "_", name).strip("_")


class SolutionViews:
    """What :class:`gyrostat.Solution` shows of its run as labelled data and as attitude (a base of
    Solution: these are its methods and properties).

    Examples
    --------
    The examples of the attributes below use this solution (a triaxial body with attitude, 11
    output times):

    >>> import gyrostat
    >>> model = gyrostat.Model(gyrostat.Body([2.0, 1.5, 1.0]), attitude=True)
    >>> sol = gyrostat.solve(model, [0.1, 0.2, 1.0], (0.0, 10.0), n_out=11)
    >>> isinstance(sol, gyrostat.solution_views.SolutionViews)
    True
    """

    __slots__ = ()

    @property
    def sensitivities(self) -> tuple[str, ...]:
        """The names of the sensitivities the run carries (``gyrostat.solve(..., sensitivities=...)``);
        empty without.

        Examples
        --------
        >>> gyrostat.solve(model, [0.1, 0.2, 1.0], (0.0, 1.0), sensitivities=["p", "moments[0]"]).sensitivities
        ('p', 'moments[0]')
        """
        found = getattr(self, "_sensitivities", None)
        return tuple(found) if found else ()

    @property
    def sensitivity_errors(self) -> dict[str, float]:
        """Each sensitivity's measured global error, relative to its largest size over the run (a
        companion run at tighter tolerances: the basis is in :attr:`notes`); empty when not
        measured (``error_estimate=False``).

        Examples
        --------
        >>> run = gyrostat.solve(model, [0.1, 0.2, 1.0], (0.0, 1.0), rtol=1e-8, sensitivities="r")
        >>> bool(run.sensitivity_errors["r"] < 1e-6)
        True
        """
        return dict(getattr(self, "_sensitivity_errors", None) or {})

    def sensitivity(self, name: str, of: str | None = None, event: int | None = None, t=None) -> np.ndarray:
        """∂y(t)/∂``name`` at every output time.

        Parameters
        ----------
        name : str
            One of :attr:`sensitivities`: a state component (the initial one's) or a parameter
            (:mod:`gyrostat.sensitivity`).
        of : str, optional
            A state component or a named output: that quantity's derivative alone.
        event : int, optional
            The derivative of event ``event``'s times instead (one per occurrence, as
            :attr:`t_events` holds them): ∂t_event/∂``name``.
        t : float or array_like, optional
            Times anywhere in the span instead of the output times (a run with
            ``dense_output=True``: each step's continuous extension; state components only).

        Returns
        -------
        numpy.ndarray
            (n, dim) in the state's order; (n,) with ``of``; (occurrences,) with ``event``; (len(t),
            dim) or (len(t),) with ``t`` ((dim,) or a scalar with one ``t``, as ``sol(t)``). KeyError
            for a name the run does not carry.

        Examples
        --------
        A torque-free body: the rotation's sensitivity to its own initial rate is 1 at t = 0.

        >>> run = gyrostat.solve(model, [0.1, 0.2, 1.0], (0.0, 1.0), n_out=3, sensitivities="r")
        >>> run.sensitivity("r")[0, :3]
        array([0., 0., 1.])
        >>> run.sensitivity("r", of="r").shape
        (3,)
        """
        found = getattr(self, "_sensitivities", None) or {}
        if name not in found:
            raise KeyError(f"no sensitivity {name!r} in this run (it carries: {', '.join(found) or 'none'}; "
                           "ask for it with solve(..., sensitivities=[...]))")
        state, outputs, events, dense = found[name]
        if t is not None:
            if dense is None:
                raise ValueError("this run keeps no dense output of its sensitivities: solve with dense_output=True")
            if of is not None and of not in self.state_names:
                raise ValueError(f"between the output times only the state's sensitivities are kept: {of!r} is not a "
                                 f"state component ({', '.join(self.state_names)})")
            result, j = dense
            dim = len(self.state_names)
            block = result.dense_whole(np.atleast_1d(np.asarray(t, dtype=float)))[:, dim * (1 + j):dim * (2 + j)]
            block = block if of is None else block[:, self.state_names.index(of)]
            return block[0] if np.ndim(t) == 0 else block  # one time: one row, as sol(t) gives
        if event is not None:
            if events is None or not 0 <= event < len(events):
                raise KeyError(f"no event {event!r} in this run's sensitivities ({len(events or ())} events)")
            return events[event]
        if of is None:
            return state
        if of in self.state_names:
            return state[:, self.state_names.index(of)]
        if of in self.output_names:
            return outputs[:, self.output_names.index(of)]
        raise KeyError(f"no state component or output {of!r}: state {', '.join(self.state_names)}; "
                       f"outputs {', '.join(self.output_names)}")

    @property
    def units(self) -> dict[str, str]:
        """The SI unit of every column (t, each state component, each output; "1":
        dimensionless), as the C++ model declares them.

        Examples
        --------
        >>> sol.units["t"], sol.units["r"], sol.units["kinetic_energy"]
        ('s', 'rad/s', 'J')
        """
        r = self._result
        units = {"t": "s", **dict(zip(r.state_names, r.state_units)), **dict(zip(r.output_names, r.output_units))}
        if self.rung is not None:
            units["rung"] = "1"
        for name in self.sensitivities:
            units.update({sensitivity_column(c, name): f"{units[c]} per unit of {name}"
                          for c in (*r.state_names, *r.output_names)})
        return units

    @property
    def invariants(self) -> dict[str, np.ndarray]:
        """The conserved outputs by name (a subset of :attr:`outputs`).

        Examples
        --------
        >>> sorted(sol.invariants)
        ['angular_momentum_norm', 'kinetic_energy']
        """
        outputs = self.outputs
        return {name: outputs[name] for name in self.conserved}

    def columns(self) -> dict[str, np.ndarray]:
        """t, every state component and every output, by name (what the CSV/NPZ writers save).

        Examples
        --------
        >>> list(sol.columns())[:4]
        ['t', 'p', 'q', 'r']
        """
        columns = {"t": self.t}
        y = self.y
        columns.update({name: y[:, i] for i, name in enumerate(self._result.state_names)})
        columns.update(self.outputs)
        if self.rung is not None:
            columns["rung"] = self.rung
        for name, (state, outputs, *_) in (getattr(self, "_sensitivities", None) or {}).items():
            columns.update({sensitivity_column(c, name): state[:, i] for i, c in enumerate(self._result.state_names)})
            columns.update({sensitivity_column(o, name): outputs[:, i] for i, o in enumerate(self._result.output_names)})
        return columns

    @property
    def omega(self) -> np.ndarray:
        """(n, 3) angular velocity in body axes, in rad/s (a ValueError for a model without it).

        Examples
        --------
        >>> sol.omega.shape
        (11, 3)
        """
        if tuple(self._result.state_names[:3]) != _RATES:
            raise ValueError(f"this solution has no angular velocity in its state ({', '.join(self.state_names)})")
        return self.y[:, :3]

    @property
    def quaternion(self) -> np.ndarray:
        """(n, 4) attitude quaternion (w, x, y, z), body → inertial (a ValueError for a model without
        attitude).

        Examples
        --------
        >>> sol.quaternion.shape
        (11, 4)
        """
        names = self._result.state_names
        if "q_w" not in names:
            raise ValueError(f"this solution has no attitude: its state is ({', '.join(names)}); "
                             "solve a model with attitude (e.g. Model(..., attitude=True))")
        first = names.index("q_w")
        return self.y[:, first:first + 4]

    def euler_angles(self, convention: str = "zxz") -> np.ndarray:
        """(n, 3) Euler angles of the attitude, in rad.

        At the singular angles the free rotation is put in ψ and φ = 0 (see :mod:`gyrostat.attitude`).

        Parameters
        ----------
        convention : {"zxz", "zyx"}
            ``"zxz"``: ψ precession, θ nutation, φ proper rotation (recorded by the engine);
            ``"zyx"``: yaw, pitch, roll.

        Examples
        --------
        >>> sol.euler_angles("zyx").shape
        (11, 3)
        """
        if convention == "zxz" and "psi" in self._result.output_names:
            return np.column_stack([self["psi"], self["theta"], self["phi"]])
        from gyrostat import attitude

        return attitude.euler_angles(self.quaternion, convention)

    def to_xarray(self):
        """The solution as an ``xarray.Dataset``: dimension ``time`` (its coordinate, in s), the
        state components and outputs as variables with their units, each event's crossing
        times (``t_event_<name>``), and the method (the methods used and the switches of
        ``"auto"``), status, message and statistics as attributes; ``to_netcdf`` writes it.

        Examples
        --------
        >>> sol.to_xarray()["r"].attrs["units"]
        'rad/s'
        """
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

    @property
    def error_estimate(self) -> float:
        """The measured global error of the answer: the largest relative error over the compared
        quantities (:attr:`error_estimates`; how it was measured: :attr:`error_basis`). NaN: not
        measured (``error_estimate=False``, a failed run), or the splitting's own estimate when
        only that was made.

        Examples
        --------
        >>> bool(0 < sol.error_estimate < 1e-6)
        True
        """
        return self.estimate.value if self.estimate is not None else self._result.error_estimate

    @property
    def error_estimates(self) -> dict[str, float]:
        """The measured global error of each compared quantity (:func:`gyrostat.accuracy.quantities`),
        relative to its largest size.

        Examples
        --------
        >>> sorted(sol.error_estimates)
        ['angular_momentum_norm', 'kinetic_energy', 'omega', 'quaternion']
        """
        return dict(self.estimate.per_quantity) if self.estimate is not None else {}

    @property
    def error_basis(self) -> str:
        """How :attr:`error_estimate` was measured, in words ("" when it was not).

        Examples
        --------
        >>> "tighter" in sol.error_basis or "rtol and atol" in sol.error_basis
        True
        """
        return self.estimate.basis if self.estimate is not None else ""
