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

The package, one concern a module: ``draws`` (the distributions and the members' random
streams), ``parameters`` (paths in a scene document, :class:`Parameter`), ``plan``
(:class:`Plan`: what a sweep solves), ``chunks`` (a chunk's members solved and recorded),
``storage`` (where results go: memory or a NetCDF file; the Dataset, :func:`open_sweep`),
``runners`` (:func:`sweep`: this process, worker processes, Dask) and ``summaries``
(:func:`summary`, :func:`check_plot`).
"""

from gyrostat.sweeps.chunks import solve_chunk
from gyrostat.sweeps.draws import LogUniform, Normal, Uniform
from gyrostat.sweeps.parameters import Parameter, parameter_from_table, parameter_from_text
from gyrostat.sweeps.plan import Plan
from gyrostat.sweeps.runners import WORKERS_FROM, sweep
from gyrostat.sweeps.storage import MEMORY_LIMIT, open_sweep
from gyrostat.sweeps.summaries import check_plot, summary

__all__ = ["Uniform", "Normal", "LogUniform", "Parameter", "Plan", "sweep", "open_sweep", "summary",
           "solve_chunk", "parameter_from_table", "parameter_from_text", "check_plot", "MEMORY_LIMIT",
           "WORKERS_FROM"]
