"""A run joined from pieces (the model ladder's switches) as one :class:`gyrostat.Solution`:
:meth:`SolutionJoin.join` adds up the pieces' statistics and puts their trajectories, already in
one model's variables, end to end; the Solution keeps the pieces, the switches and, per output
time, the model that made it (``pieces``, ``switches``, ``rung``)."""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np


def _no_dense_output(times):
    raise ValueError("a run joined from pieces keeps no dense output: evaluate its pieces (solution.pieces)")


class SolutionJoin:
    """How :class:`gyrostat.Solution` is made from the pieces of a run that switched models (a base
    of Solution: :meth:`join` is ``Solution.join``).

    Examples
    --------
    :meth:`join`'s example joins the first three outputs of a run of a free triaxial body:

    >>> import gyrostat
    >>> model = gyrostat.Model(gyrostat.Body([3.0, 2.0, 1.0]))
    >>> sol = gyrostat.solve(model, [0.1, 0.2, 1.0], (0.0, 5.0), n_out=6, error_estimate=False)
    >>> len(sol), sol.state_names
    (6, ('p', 'q', 'r'))
    """

    __slots__ = ()

    @classmethod
    def join(cls, model, pieces: list[tuple[str, "Solution"]], parts: list[tuple], switches: list[tuple],
             y_last, event_names: tuple = (), t_events: list | None = None, y_events: list | None = None,
             terminal_event: int = -1, notes: tuple = ()) -> "Solution":
        """One solution of ``model`` from the pieces of a run that switched models.

        The statistics add up; status, message and the step to continue with are the last
        piece's; no output is marked conserved (the pieces' models differ). The model ladder
        (``model = "auto"`` in a scene) makes these; a joined run keeps no dense output.

        Parameters
        ----------
        model : gyrostat.ModelBase
            The model whose state and outputs the joined solution has.
        pieces : list of (str, Solution)
            The pieces in order, each with the name of its model.
        parts : list of (t, y, outputs, index)
            Each non-empty piece already in ``model``'s state and outputs (index: 0 where
            ``model`` itself ran).
        switches : list of (t, from, to, reason)
            Where the run switched models and why.
        y_last : array_like
            The last state, in ``model``'s variables.
        event_names, t_events, y_events, terminal_event : optional
            The caller's events over the pieces (the crossings' states in ``model``'s variables;
            ``terminal_event`` the index of the one that ended the run, -1: none).
        notes : tuple of str, optional
            What the run notes besides (an event not located on a piece whose model lacks its quantity).

        Examples
        --------
        >>> t = sol.t[:3]
        >>> part = (t, sol.y[:3], sol._result.outputs[:3], 0)
        >>> joined = gyrostat.Solution.join(model, [("full", sol)], [part], [], sol.y[2])
        >>> len(joined), joined.rung.tolist()
        (3, [0.0, 0.0, 0.0])
        """
        core = model._core
        dim, n_out = len(core.state_names), len(core.output_names)
        quantities = core.quantities  # made by the core on each call: once
        last = pieces[-1][1]
        each = [sol.stats for _, sol in pieces]  # a dict made on each call: once per piece
        stats = {k: sum(piece[k] for piece in each) for k in each[-1] if k != "last_step"}
        result = SimpleNamespace(
            t=np.concatenate([p[0] for p in parts]) if parts else np.zeros(0),
            y=np.vstack([p[1] for p in parts]) if parts else np.zeros((0, dim)),
            outputs=np.vstack([p[2] for p in parts]) if parts else np.zeros((0, n_out)),
            state_names=tuple(core.state_names), output_names=tuple(core.output_names),
            state_units=tuple(q["unit"] for q in quantities if q["role"] == "state"),
            output_units=tuple(q["unit"] for q in quantities if q["role"] == "output"),
            output_conserved=(False,) * n_out, output_kept=(False,) * n_out, options=last._result.options,
            stats=SimpleNamespace(**stats, last_step=each[-1]["last_step"]),
            t_last=last.t_last, y_last=y_last, h_next=last.h_next, status=last.status,
            message=(f"terminal event {terminal_event} ('{event_names[terminal_event]}') at t = {last.t_last:.17g}"
                     if terminal_event >= 0 else last.message),
            success=last.success, method="+".join(dict.fromkeys(f"{name}:{sol.method}" for name, sol in pieces)),
            methods_used=(), switches=[], warnings=(), notes=tuple(notes), remarked=bool(notes), t_events=list(t_events or []),
            y_events=list(y_events or []), event_names=tuple(event_names), terminal_event=terminal_event,
            error_estimate=float("nan"), dense=_no_dense_output)
        joined = cls(result, model)
        joined.pieces, joined.switches = tuple(pieces), list(switches)
        joined.rung = np.concatenate([np.full(len(p[0]), float(p[3])) for p in parts]) if parts else np.zeros(0)
        return joined
