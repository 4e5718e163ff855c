"""The result of a run of any model: times, states and named outputs, statistics, status. One
type for every run: a run joined from pieces (the model ladder's switches) is a
:class:`Solution` too (:meth:`Solution.join`, ``pieces``, ``switches``, ``rung``).

Here: the Solution's arrays, names, events, dense output, run information and the accuracy it
measured; its labelled-data and attitude views (``units``, ``columns``, ``to_xarray``, ``omega``,
``quaternion``, ``euler_angles``, ``invariants``) come from :mod:`gyrostat.solution_views`, and
:meth:`Solution.join` from :mod:`gyrostat.solution_join` (its bases)."""

from __future__ import annotations

import numpy as np

from gyrostat import _core
from gyrostat.arguments import floats
from gyrostat.solution_join import SolutionJoin
from gyrostat.solution_views import SolutionViews


class AccuracyWarning(UserWarning):
    """A run doubts its own answer: the splitting's estimated error exceeds rtol, a fixed step was
    clamped to the span, or BDF stepped over oscillations it damps away. The sentence names the
    measured values and what to do; it is also kept in ``Solution.notes``.

    Examples
    --------
    >>> import warnings
    >>> import gyrostat
    >>> model = gyrostat.Model(gyrostat.Body([3.0, 2.0, 1.0]))
    >>> with warnings.catch_warnings(record=True) as caught:
    ...     warnings.simplefilter("always")
    ...     sol = gyrostat.solve(model, [0.1, 0.2, 1.0], (0.0, 10.0), method="splitting", step=20.0)
    >>> [issubclass(w.category, gyrostat.AccuracyWarning) for w in caught][:1]
    [True]
    """


class Solution(SolutionViews, SolutionJoin):
    """A trajectory of any model, as recorded by the engine: what :func:`gyrostat.solve` returns.

    Times ``t``, states ``y`` (columns named by ``state_names``), the named outputs the engine
    recorded at each output time (``outputs``, ``output_names``; units in ``units``), events
    (``t_events``, ``y_events``, ``event_names``, ``terminal_event``), the continuous solution
    ``sol(t)`` and ``sol(t, name)`` (with ``dense_output=True``), statistics and status. A run
    joined from pieces (the model ladder's switches) is a Solution too (:meth:`join`,
    ``pieces``, ``switches``, ``rung``). A failed or interrupted run keeps its partial
    trajectory; pass the solution as ``y0`` to :func:`gyrostat.solve` to continue it.

    The arrays are views of the engine's memory, made on first access: no copy, no physics
    recomputed in Python.

    Parameters
    ----------
    result : gyrostat._core.Result
        The engine's result (made by :func:`gyrostat.solve`; users do not build one).
    model : gyrostat.ModelBase, optional
        The model that was solved: it evaluates named outputs at interpolated states.

    Examples
    --------
    The examples of the attributes below use this solution: a triaxial body with slight linear
    damping, with attitude, 11 output times, dense output and one event (q = 0).

    >>> import gyrostat
    >>> from gyrostat.events import Event
    >>> body = gyrostat.Body([2.0, 1.5, 1.0])
    >>> model = gyrostat.Model(body, [gyrostat.LinearDamping(diagonal=[0.01, 0.01, 0.01])], attitude=True)
    >>> sol = gyrostat.solve(model, [0.1, 0.2, 1.0], (0.0, 10.0), n_out=11, dense_output=True,
    ...                      events=[Event("q", 0.0)])
    >>> sol
    <Solution dop853: success, 11 outputs, t in [0, 10]; state (p, q, r, q_w, q_x, q_y, q_z); outputs (angular_momentum_norm, kinetic_energy, nutation_angle, psi, theta, phi)>
    >>> round(float(sol(2.5, "theta")), 6)
    0.422737
    """

    __slots__ = {
        "_result": "the engine's result",
        "_sensitivities": "name → (∂y/∂p, ∂outputs/∂p) at the output times (gyrostat.sensitivity.attach)",
        "_sensitivity_errors": "name → the sensitivity's measured relative error (gyrostat.sensitivity.measure)",
        "_columns": "name → (array, column), made on first look-up",
        "_notes": "the notes made so far (:attr:`notes` adds the estimate's line to them when first read)",
        "_noted": "the estimate whose line :attr:`notes` has yet to add (its basis written only when read)",
        "model": """The model that was solved (None when unknown): it evaluates ``sol(t, name)``.

        Examples
        --------
        >>> sol.model.kind
        'full'
        """,
        "pieces": """A run joined from pieces (:meth:`join`): the pieces as (name, Solution) in order;
        empty for a run of one model.

        Examples
        --------
        >>> sol.pieces
        ()
        """,
        "switches": """A run joined from pieces: each switch of model as (t, from, to, reason); empty
        for a run of one model.

        Examples
        --------
        >>> sol.switches
        []
        """,
        "rung": """A run joined from pieces: per output time, the index of the model that made it
        (0: the solution's own model; also the column ``rung``); None for a run of one model.

        Examples
        --------
        >>> sol.rung is None
        True
        """,
        "estimate": """The measured global error (:class:`gyrostat.accuracy.Estimate`: value, per
        quantity, basis, the accuracy asked and whether it is met); None when not measured.

        Examples
        --------
        >>> sol.estimate.met is None  # no accuracy was asked
        True
        """,
        "_doubts": "doubts recorded after the run (:meth:`doubt`)",
    }

    def __init__(self, result: _core.Result, model=None):
        self._result = result
        self._columns = None
        # (each read of notes or warnings converts the engine's strings: read once, and only where there are some)
        self._notes: list[str] = list(result.notes) + list(result.warnings) if result.remarked else []
        self._noted = None
        self.model = model
        self.pieces: tuple[tuple[str, Solution], ...] = ()
        self.switches: list[tuple] = []
        self.rung: np.ndarray | None = None
        self.estimate = None
        self._doubts: list[str] = []

    @property
    def notes(self) -> list[str]:
        """What the run says about its own answer (the splitting's chosen step and estimated
        error; every :class:`AccuracyWarning`), then remarks added after the run (assumptions
        checked, paper-specific analysis): a list of sentences.

        Examples
        --------
        >>> sol.notes[0].startswith("error estimate")
        True
        """
        if self._noted is not None:
            self._write_noted()
        return self._notes

    @notes.setter
    def notes(self, notes: list[str]) -> None:
        self._noted, self._notes = None, notes

    def note_estimate(self, estimate) -> None:
        """Puts the estimate's line among the notes ("error estimate VALUE: BASIS"), written when
        the notes are next read (the basis is words a run need not format when nobody reads them).

        Parameters
        ----------
        estimate : gyrostat.accuracy.Estimate
            The measured error of this solution's answer (its ``value`` and ``basis``).

        Examples
        --------
        >>> copy = gyrostat.Solution(sol._result, model)
        >>> copy.note_estimate(sol.estimate)
        >>> copy.notes[-1] == sol.notes[0]
        True
        """
        if self._noted is not None:  # (an earlier estimate's line first: each keeps its place)
            self._write_noted()
        self._noted = estimate

    def _write_noted(self) -> None:
        estimate, self._noted = self._noted, None
        self._notes.append(f"error estimate {estimate.value:.3g}: {estimate.basis}")

    # ---- arrays
    @property
    def t(self) -> np.ndarray:
        """(n,) output times, in s.

        Examples
        --------
        >>> sol.t
        array([ 0.,  1.,  2.,  3.,  4.,  5.,  6.,  7.,  8.,  9., 10.])
        """
        return self._result.t

    @property
    def y(self) -> np.ndarray:
        """(n, dim) states at the output times; :attr:`state_names` names the columns (units in :attr:`units`).

        Examples
        --------
        >>> sol.y.shape
        (11, 7)
        """
        return self._result.y

    @property
    def state_names(self) -> tuple[str, ...]:
        """The names of the state components, in the order of the columns of :attr:`y`.

        Examples
        --------
        >>> sol.state_names
        ('p', 'q', 'r', 'q_w', 'q_x', 'q_y', 'q_z')
        """
        return tuple(self._result.state_names)

    @property
    def output_names(self) -> tuple[str, ...]:
        """The quantities the engine recorded at every output time (invariants such as |G| and T,
        derived quantities such as Euler angles, τ, g, k²), as the C++ model declares them.

        Examples
        --------
        >>> sol.output_names
        ('angular_momentum_norm', 'kinetic_energy', 'nutation_angle', 'psi', 'theta', 'phi')
        """
        return tuple(self._result.output_names)

    @property
    def outputs(self) -> dict[str, np.ndarray]:
        """Name → (n,) array of each recorded output (see :attr:`output_names`, :attr:`units`).

        Examples
        --------
        >>> round(float(sol.outputs["kinetic_energy"][0]), 6)
        0.54
        """
        values = self._result.outputs
        return {name: values[:, i] for i, name in enumerate(self._result.output_names)}

    @property
    def conserved(self) -> tuple[str, ...]:
        """The outputs that are first integrals of the unperturbed model (|G|, T, G_z, H, …).

        Examples
        --------
        >>> sol.conserved
        ('angular_momentum_norm', 'kinetic_energy')
        """
        return tuple(n for n, c in zip(self._result.output_names, self._result.output_conserved) if c)

    @property
    def kept(self) -> tuple[str, ...]:
        """The first integrals (:attr:`conserved`) this model keeps with its torques, as its C++
        model says (a forced or damped energy is not kept; the cavity keeps |G|).

        Examples
        --------
        >>> sol.kept  # its torques change |G| and T
        ()
        """
        flags = getattr(self._result, "output_kept", self._result.output_conserved)
        return tuple(n for n, c in zip(self._result.output_names, flags) if c)

    def __getitem__(self, name: str) -> np.ndarray:
        """A state component, an output or ``"t"`` by name: its (n,) values at the output times.

        Parameters
        ----------
        name : str
            ``"t"``, one of :attr:`state_names` or one of :attr:`output_names`; anything else is a
            KeyError listing them.

        Examples
        --------
        >>> round(float(sol["r"][-1]), 6)
        0.918628
        """
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
        """Whether ``name`` is a state component or an output of this solution.

        Parameters
        ----------
        name : str
            The name asked about.

        Examples
        --------
        >>> "theta" in sol, "x" in sol
        (True, False)
        """
        return name in self._result.state_names or name in self._result.output_names

    @property
    def options(self):
        """The options the run was made with (:class:`gyrostat.Options`, without t_eval and events).

        Examples
        --------
        >>> sol.options.method, sol.options.rtol
        ('dop853', 1e-08)
        """
        return self._result.options

    # ---- events and dense output
    @property
    def t_events(self) -> list[np.ndarray]:
        """One array per event: the times of its crossings, in s (SciPy's name).

        Examples
        --------
        >>> sol.t_events
        [array([2.17071107])]
        """
        return self._result.t_events

    @property
    def y_events(self) -> list[np.ndarray]:
        """One (k, dim) array per event: the states at its crossings (SciPy's name).

        Examples
        --------
        >>> [y.shape for y in sol.y_events]
        [(1, 7)]
        """
        return self._result.y_events

    @property
    def event_names(self) -> tuple[str, ...]:
        """The label of each event, in the order of :attr:`t_events` (an :class:`~gyrostat.events.Event`'s
        ``name``, or ``quantity = value``; a callable's ``__name__``).

        Examples
        --------
        >>> sol.event_names
        ('q = 0',)
        """
        return tuple(self._result.event_names)

    @property
    def terminal_event(self) -> int | None:
        """The index of the event that ended the run, or None.

        Examples
        --------
        >>> sol.terminal_event is None
        True
        """
        index = self._result.terminal_event
        return None if index < 0 else index

    def __call__(self, t, name: str | None = None) -> np.ndarray:
        """The solution at any time of the span, from the stored continuous extension of each
        step (solve with ``dense_output=True``; memory grows with the steps taken).

        Parameters
        ----------
        t : float or array_like
            A time or an array of times in the span, in s.
        name : str, optional
            A state component or a named output (``"theta"``, ``"kinetic_energy"``, …; units in
            :attr:`units`). None (default): the whole state. An output is evaluated by the C++
            model at the interpolated state, as the engine records it at the output times.

        Returns
        -------
        numpy.ndarray
            Without ``name``: the state, shape ``(dim,)`` for one time or ``t.shape + (dim,)``;
            the attitude part stays a unit quaternion. With ``name``: its value, a float array of
            the shape of ``t``.

        Examples
        --------
        >>> sol(2.5).shape
        (7,)
        >>> round(float(sol(2.5, "r")), 6)
        0.989476
        >>> sol([1.0, 2.0, 3.0], "theta").shape
        (3,)
        >>> bool(abs(sol(4.0, "kinetic_energy") - sol["kinetic_energy"][4]) < 1e-12)
        True
        """
        times = floats(t, "t", "a time or times (numbers)")
        if name is not None:
            if name in self._result.state_names:
                column = list(self._result.state_names).index(name)
                return self(times)[..., column]
            if name not in self._result.output_names:
                raise KeyError(f"{name!r} is neither a state component ({', '.join(self.state_names)}) nor an "
                               f"output ({', '.join(self.output_names)}) of this solution")
            if self.model is None:
                raise ValueError(f"this solution does not know its model: {name!r} cannot be evaluated between "
                                 "outputs (solve it with gyrostat.solve)")
            column = list(self._result.output_names).index(name)
            core, flat = self.model._core, times.ravel()
            states = self._result.dense(flat)
            values = np.array([core.outputs_at(float(ti), yi)[column] for ti, yi in zip(flat, states)])
            return values[0] if times.ndim == 0 else values.reshape(times.shape)
        values = self._result.dense(times.ravel())
        return values[0] if times.ndim == 0 else values.reshape(times.shape + (values.shape[1],))

    # ---- run information
    @property
    def stats(self) -> dict[str, float]:
        """The integrator's work: steps, rhs_evals, rejected_steps, jacobian_evals,
        nonlinear_conv_failures, and last_step (the last step size, in s).

        Examples
        --------
        >>> sorted(sol.stats)[:3]
        ['jacobian_evals', 'last_step', 'nonlinear_conv_failures']
        """
        s = self._result.stats
        return {"steps": s.steps, "rhs_evals": s.rhs_evals, "rejected_steps": s.rejected_steps,
                "jacobian_evals": s.jacobian_evals, "nonlinear_conv_failures": s.nonlinear_conv_failures,
                "last_step": s.last_step}

    @property
    def t_last(self) -> float:
        """Where the run stopped, however it ended (t1, a terminal event, max_steps, a failure,
        Ctrl-C): the last accepted time, in s. ``solve(model, solution, (solution.t_last, t1))``
        continues from there.

        Examples
        --------
        >>> sol.t_last
        10.0
        """
        return self._result.t_last

    @property
    def y_last(self) -> np.ndarray:
        """The state at :attr:`t_last` (the last accepted step, not an interpolated output).

        Examples
        --------
        >>> sol.y_last.shape
        (7,)
        """
        return self._result.y_last

    @property
    def h_next(self) -> float:
        """The step size the integrator would have tried next, in s (0: the method picks its own).

        Examples
        --------
        >>> sol.h_next > 0
        True
        """
        return self._result.h_next

    @property
    def status(self) -> str:
        """``"success"`` or why the run stopped: ``max_steps_reached``, ``step_size_underflow``,
        ``non_finite_state``, ``solver_failure``, ``invalid_input``, ``interrupted``.

        Examples
        --------
        >>> sol.status
        'success'
        """
        return self._result.status

    @property
    def message(self) -> str:
        """Why the run stopped, in words (empty on success).

        Examples
        --------
        >>> sol.message
        ''
        """
        return self._result.message

    @property
    def accuracy_warnings(self) -> tuple[str, ...]:
        """What the run doubts about its own answer (each one an :class:`AccuracyWarning` when
        :func:`gyrostat.solve` returned, and in ``notes``): the accuracy asked not met, with the
        measured error and what would meet it, and the integrators' own doubts.

        Examples
        --------
        >>> sol.accuracy_warnings
        ()
        """
        return tuple(self._result.warnings) + tuple(self._doubts)

    def doubt(self, text: str) -> None:
        """Records a doubt about the answer (in :attr:`accuracy_warnings` and ``notes``).

        Parameters
        ----------
        text : str
            The doubt, naming the measured values and what would remove it.

        Examples
        --------
        >>> copy = gyrostat.Solution(sol._result, model)
        >>> copy.doubt("an example")
        >>> copy.accuracy_warnings
        ('an example',)
        """
        self._doubts.append(text)
        self.notes.append(text)

    @property
    def method(self) -> str:
        """The integrator asked for (``"auto"`` included), or ``"closed_form"``.

        Examples
        --------
        >>> sol.method
        'dop853'
        """
        return self._result.method

    @property
    def methods_used(self) -> tuple[str, ...]:
        """The integrators that carried the run, in order of first use (one unless ``"auto"``).

        Examples
        --------
        >>> sol.methods_used
        ('dop853',)
        """
        return tuple(self._result.methods_used)

    @property
    def method_switches(self) -> list[tuple[float, str, str]]:
        """Method ``"auto"``: each switch as (t, the method switched to, the reason with the
        measured h·|λ|); empty for the other methods.

        Examples
        --------
        >>> sol.method_switches
        []
        """
        return self._result.switches

    @property
    def success(self) -> bool:
        """Whether the run reached t1 or a terminal event (``status == "success"``).

        Examples
        --------
        >>> sol.success
        True
        """
        return self._result.success

    def raise_for_status(self) -> "Solution":
        """Raises RuntimeError with the message when the run failed; returns self otherwise.

        Examples
        --------
        >>> sol.raise_for_status() is sol
        True
        """
        if not self.success:
            raise RuntimeError(f"{self.method}: {self.status}: {self.message}")
        return self

    def __len__(self) -> int:
        """The number of output times.

        Examples
        --------
        >>> len(sol)
        11
        """
        return len(self._result.t)

    def __repr__(self) -> str:
        t = self.t
        span = f"t in [{t[0]:.6g}, {t[-1]:.6g}]" if len(t) else "no outputs"
        return (f"<Solution {self.method}: {self.status}, {len(t)} outputs, {span}; state ({', '.join(self.state_names)});"
                f" outputs ({', '.join(self.output_names)})>")
