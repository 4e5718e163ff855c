"""Sweeps and Monte Carlo runs: grids and seeded dispersions of scene entries, xarray results,
the local pool and a real Dask cluster, NetCDF, failing members, Ctrl-C, progress, the CLI."""

import json
import math
import os
import threading
import tomllib
import warnings
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

import gyrostat as g
from gyrostat import sweeps
from gyrostat.sweeps import chunks, runners, storage
from gyrostat.cli import main
from gyrostat.schema import SceneError

SCENES = Path(g.__file__).parent / "scenes"


def scene(name: str, **integration) -> dict:
    """A shipped scene as a document, with its [integration] changed (short runs for tests)."""
    with open(SCENES / f"{name}.toml", "rb") as handle:
        doc = tomllib.load(handle)
    doc.setdefault("integration", {}).update(integration)
    doc.pop("sweep", None)
    return doc


def single(plan: sweeps.Plan, i: int) -> g.Solution:
    """Member i solved alone, from its own validated scene, as an ensemble of one (where SIMD
    batches apply, a batch of one: a lane's numbers do not depend on its neighbours, so the
    sweep's chunking must not change them)."""
    member = plan.scene(i)
    run = next(r for r in member.runs if r.name == plan.run)
    return g.solve_ensemble(run.model, [run.y0], run.t_span, **run.options, check_validity=False, progress=False)[0]


def assert_member_is_single_run(ds: xr.Dataset, plan: sweeps.Plan, i: int, index: dict) -> None:
    member = ds.isel(index) if index else ds.isel(member=i)
    solution = single(plan, i)
    assert str(member["status"].values) == solution.status
    for name in plan.names:  # bit for bit: the same engine, the same options, the same inputs
        assert np.array_equal(member[name].values[:len(solution)], solution[name], equal_nan=True), name
        assert member[f"final_{name}"].values == solution[name][-1], name
    assert int(member["steps"]) == solution.stats["steps"]


# ------------------------------------------------------------------------------------ equal to single runs
@pytest.mark.parametrize("name, vary, run, integration", [
    ("forced_damped", {"body.moments[0]": [1.0, 1.3], "torques[0].moment[2]": [0.0, 0.05, 0.1]}, None,
     {"t_span": [0.0, 20.0], "n_out": 51}),
    ("p001_A1p5_C1_I1-1p25", {"torques[1].damping": [50.0, 98.0], "initial.omega[2]": [0.5, 1.0]}, "averaged",
     {"t_span": [0.0, 10.0], "n_out": 41}),
    ("p001_explicit_moving_mass", {"damper.damping": [20.0, 40.0]}, None, {"t_span": [0.0, 2.0], "n_out": 21}),
    ("explorer1_flat_spin", {"torques[0].p0": [1e-4, 2e-4], "initial.omega[0]": [0.05, 0.1]}, "averaged",
     {"t_span": [0.0, 2e4], "n_out": 21, "model": "averaged_triaxial"}),
    ("p003_case1_theta0_5deg", {"initial.theta_deg": [5.0, 20.0], "torque.b[0]": [0.5, 1.0]}, "averaged",
     {"tau_end": 0.5, "n_out": 31}),
    ("p004_triaxial", {"runs[0].law.value": [0.05, 0.1], "initial.omega[0]": [0.5, 1.0]}, "constant",
     {"t_span": [0.0, 5.0], "n_out": 41}),
])
def test_a_grid_equals_its_members_solved_one_by_one(name, vary, run, integration):
    doc = scene(name, **integration)
    ds = g.sweep(doc, vary, run=run, progress=False, chunk_size=3)
    plan = sweeps.Plan(doc, vary, run=run)
    assert ds.sizes == {**{path: len(v) for path, v in vary.items()}, "time": integration["n_out"]}
    assert set(ds["status"].values.ravel()) == {"success"}
    for i in range(plan.size):
        index = dict(zip(vary, np.unravel_index(i, plan.shape)))
        assert_member_is_single_run(ds, plan, i, index)
        for path, k in index.items():  # the coordinates are the values the member got
            assert ds[path].values[k] == plan.values(i)[list(vary).index(path)]


def test_a_varied_entry_reaches_the_model():
    # paper 001 with the damper removed: a' = -eps I1/A a, r' = -eps I3/C r exactly, so
    # x/y = exp(-2 t (d1/A - d3/C)) with d1 = eps I1, d3 = eps I3: an analytic map of the sweep
    doc = scene("p001_A1p5_C1_I1-1p25", t_span=[0.0, 10.0], n_out=11, model="averaged")
    doc["torques"] = doc["torques"][:1]
    parameters = [g.Parameter("A", ["body.moments[0:2]"], [1.2, 1.5, 2.0]),
                  g.Parameter("I1", ["torques[0].diagonal[0:2]"], [0.8, 1.5, 2.5], scale=0.1)]
    ds = g.sweep(doc, parameters, progress=False)
    A, I1 = np.meshgrid(ds["A"].values, ds["I1"].values, indexing="ij")
    expected = np.exp(-2 * 10.0 * (0.1 * I1 / A - 0.1 / 1.0))
    ratio = sweeps.summary(ds, "final_x / final_y").values
    # rtol 1e-10 per step over t = 10 of exponential decay: 1e-8 relative is generous and still sharp
    np.testing.assert_allclose(ratio, expected, rtol=1e-8)
    assert ds["A"].attrs["units"] == "kg m^2" and "units" not in ds["I1"].attrs  # a scaled entry has no unit


# ------------------------------------------------------------------------------------ dispersions
DISPERSED = {"body.moments[0]": g.Normal(1.0, 0.6), "initial.omega[2]": g.Uniform(-0.5, 0.5),
             "torques[1].matrix[0][0]": g.LogUniform(1e-3, 1e-1)}


def test_a_dispersion_is_reproducible_member_by_member_and_keeps_failed_members():
    doc = scene("forced_damped", t_span=[0.0, 5.0], n_out=11)
    ds = g.sweep(doc, DISPERSED, samples=60, seed=11, progress=False, chunk_size=7)
    again = g.sweep(doc, DISPERSED, samples=60, seed=11, progress=False, chunk_size=60, trajectories=True)
    xr.testing.assert_identical(ds.drop_attrs(), again.drop_attrs())  # the chunking changes nothing
    assert ds.attrs["seed"] == 11 and ds.sizes["member"] == 60
    plan = sweeps.Plan(doc, DISPERSED, samples=60, seed=11)
    status = ds["status"].values
    # N(1, 0.6) gives A1 <= 0 or a broken triangle inequality for some members: refused, recorded
    failed = np.flatnonzero(status != "success")
    assert 3 <= len(failed) <= 40 and set(status[failed]) == {"invalid_input"}
    for i in failed:
        assert "[body]" in ds["message"].values[i] and str(ds["body.moments[0]"].values[i])[:6] in \
            ds["message"].values[i] or "triangle" in ds["message"].values[i]
        assert np.isnan(ds["final_p"].values[i])
    for i in [j for j in range(60) if j not in failed][:6]:
        assert_member_is_single_run(ds, plan, i, {})
    values = np.array([plan.values(i) for i in range(60)])  # member i alone: its own stream
    for k, path in enumerate(DISPERSED):
        assert np.array_equal(ds[path].values, values[:, k])
    assert np.all((values[:, 1] >= -0.5) & (values[:, 1] < 0.5)) and np.all((values[:, 2] >= 1e-3) & (values[:, 2] < 0.1))
    other = g.sweep(doc, DISPERSED, samples=60, seed=12, progress=False, trajectories=False)
    assert not np.array_equal(other["body.moments[0]"].values, ds["body.moments[0]"].values)


@pytest.mark.parametrize("seed", [0, 1, 11, 2**32 + 5, 2**63 - 1])
def test_a_chunks_streams_are_numpys_own(seed):
    """A chunk's members draw from streams computed together: the same numbers as
    NumPy's default_rng(SeedSequence(seed, spawn_key=(i,))), member by member."""
    plan = sweeps.Plan(scene("forced_damped"), DISPERSED, samples=3000, seed=seed)
    together = plan.values_range(2980, 3000) + plan.values_range(0, 20)
    alone = []
    for i in list(range(2980, 3000)) + list(range(20)):
        rng = np.random.default_rng(np.random.SeedSequence(seed, spawn_key=(i,)))
        alone.append(tuple(p.distribution.draw(rng) for p in plan.parameters))
    assert together == alone
    assert plan.values_range(5, 5) == [] and plan.values(7) == alone[27]
    with pytest.raises(IndexError, match="members 2999 … 3000 of a sweep of 3000"):
        plan.values_range(2999, 3001)


@pytest.mark.parametrize("distribution, numpys_own", [
    (g.Uniform(-0.5, 2), lambda rng: rng.uniform(-0.5, 2)),
    (g.Normal(1, 0.1), lambda rng: rng.normal(1, 0.1)),
    (g.LogUniform(1e-3, 1e-1), lambda rng: math.exp(rng.uniform(math.log(1e-3), math.log(1e-1))))])
def test_a_draw_is_numpys_own_distribution_bit_for_bit(distribution, numpys_own):
    """The draws are written out (a + w·u, m + s·z) for speed; they must stay NumPy's numbers."""
    ours, theirs = np.random.default_rng(3), np.random.default_rng(3)
    drawn = [distribution.draw(ours) for _ in range(20000)]
    assert drawn == [float(numpys_own(theirs)) for _ in range(20000)]
    assert all(type(x) is float for x in drawn[:10])


def test_summaries_alone_equal_the_summaries_kept_with_trajectories():
    """A summaries-only sweep records its members' columns together: the same values,
    statuses and statistics as the member-by-member record of a sweep that keeps trajectories,
    refused members included."""
    doc = scene("forced_damped", t_span=[0.0, 5.0], n_out=11)
    summaries = g.sweep(doc, DISPERSED, samples=40, seed=3, progress=False, trajectories=False)
    full = g.sweep(doc, DISPERSED, samples=40, seed=3, progress=False, trajectories=True)
    assert (summaries["status"] != "success").any() and (summaries["status"] == "success").any()
    for name in summaries.data_vars:
        xr.testing.assert_identical(summaries[name].drop_attrs(), full[name].drop_attrs())


def test_summaries_in_bulk_equal_each_members_own_run():
    """The bulk summaries (final values, extrema, t_final: one stack per number of output times)
    of members whose output counts differ equal each member solved alone, number for number."""
    doc = scene("forced_damped", t_span=[0.0, 5.0], n_out=11)
    vary = {"integration.n_out": [5, 11], "torques[0].moment[2]": [0.0, 0.05]}
    ds = g.sweep(doc, vary, progress=False, trajectories=False)
    plan = sweeps.Plan(doc, vary)
    for i in range(plan.size):
        index = dict(zip(vary, np.unravel_index(i, plan.shape)))
        member, solution = ds.isel(index), single(plan, i)
        assert len(solution) == vary["integration.n_out"][index["integration.n_out"]]
        assert float(member["t_final"]) == solution.t[-1] == 5.0
        assert int(member["steps"]) == solution.stats["steps"] and str(member["status"].values) == "success"
        for name in plan.names:
            assert member[f"final_{name}"].values == solution[name][-1], name
        for name in plan.output_names:
            assert member[f"min_{name}"].values == solution[name].min(), name
            assert member[f"max_{name}"].values == solution[name].max(), name


def test_bulk_records_equal_member_by_member_records():
    """chunks._record_results (the engine's summaries in bulk: _core.summaries) over members of
    different lengths (a member stopped by max_steps keeps a shorter trajectory, a refused one
    none) and one member with other names (no attitude) writes what _record writes member by
    member, bit for bit."""
    from gyrostat.solve import ensemble_results

    doc = scene("forced_damped", t_span=[0.0, 5.0], n_out=4)
    plan = sweeps.Plan(doc, {"torques[0].moment[2]": [0.0, 0.05, 0.1]})
    run = plan.member(plan.values(1))
    options = dict(n_out=4, method="dop853", rtol=1e-10, atol=1e-12)
    y0 = np.asarray(run.y0)
    refused = y0.copy()
    refused[0] = np.nan
    _, full, _ = ensemble_results([run.model], np.stack([y0, 1.1 * y0, refused]), run.t_span, **options)
    _, stopped, _ = ensemble_results([run.model], np.stack([y0]), run.t_span, max_steps=3, **options)
    other = g.Model(run.model.body, run.model.torques)  # the same body without attitude: other names
    _, unnamed, _ = ensemble_results([other], np.stack([y0[:3]]), run.t_span, **options)
    results = [full[0], stopped[0], full[1], full[2], unnamed[0]]
    models = [run.model, run.model, run.model, run.model, other]
    assert [(r.status, len(r.t)) for r in results] == [("success", 4), ("max_steps_reached", 1), ("success", 4),
                                                       ("invalid_input", 0), ("success", 4)]
    extrema = plan.output_names[:2] + ("q",)
    bulk, one = chunks._blank(plan, 5, False, extrema), chunks._blank(plan, 5, False, extrema)
    warnings_ = chunks._record_results(bulk, list(range(5)), results, models, plan, False, extrema)
    for j, r in enumerate(results):
        chunks._record(one, j, g.Solution(r, models[j]), plan, False, extrema)
    assert list(warnings_) == [r.warnings[0] if len(r.warnings) else "" for r in results]
    assert set(bulk) == set(one)
    for name in one:
        assert np.array_equal(bulk[name], one[name], equal_nan=bulk[name].dtype != object), name
    assert bulk["final_p"][0] == results[0].y[-1, 0] and bulk["final_p"][1] == results[1].y[-1, 0]
    assert bulk["max_q"][2] == results[2].y[:, 1].max() and bulk["min_q"][2] == results[2].y[:, 1].min()
    assert np.isnan(bulk["final_p"][3]) and bulk["final_r"][4] == results[4].y[-1, 2]
    assert np.isnan(bulk[f"final_{plan.state_names[3]}"][4])  # a quaternion component the member has not


def test_dispersion_statistics():
    doc = scene("torque_free_integrated", t_span=[0.0, 0.1], n_out=2)
    vary = {"initial.omega[0]": g.Normal(2.0, 0.5), "initial.omega[1]": g.LogUniform(1e-2, 1e2)}
    plan = sweeps.Plan(doc, vary, samples=4000, seed=5)
    values = np.array([plan.values(i) for i in range(plan.size)])
    # the mean of 4000 normal draws lies within 4 standard errors (0.5/sqrt(4000)) of 2 unless broken
    assert abs(values[:, 0].mean() - 2.0) < 4 * 0.5 / math.sqrt(4000)
    assert abs(values[:, 0].std() - 0.5) < 0.05
    # log-uniform over four decades: each decade gets a quarter of the members (± 4 sigma)
    counts = np.histogram(np.log10(values[:, 1]), bins=[-2, -1, 0, 1, 2])[0]
    assert np.all(np.abs(counts - 1000) < 4 * math.sqrt(4000 * 0.25 * 0.75))


# ------------------------------------------------------------------------------------ files and Dask
def test_netcdf_round_trip_keeps_values_units_and_coordinates(tmp_path):
    doc = scene("forced_damped", t_span=[0.0, 5.0], n_out=21)
    ds = g.sweep(doc, {"body.moments[0]": [1.0, 1.2], "torques[0].moment[2]": [0.0, 0.1, 0.2]}, progress=False)
    ds.to_netcdf(tmp_path / "grid.nc")
    back = xr.open_dataset(tmp_path / "grid.nc").load()
    xr.testing.assert_identical(ds, back)
    assert back["kinetic_energy"].attrs["units"] == "J" and back["time"].attrs["units"] == "s"
    assert back["torques[0].moment[2]"].attrs["units"] == "N m"
    # streamed chunk by chunk to a file: the same members (flat), reshaped by open_sweep
    streamed = g.sweep(doc, {"body.moments[0]": [1.0, 1.2], "torques[0].moment[2]": [0.0, 0.1, 0.2]},
                       progress=False, path=tmp_path / "streamed.nc", chunk_size=2)
    assert streamed.sizes["member"] == 6
    streamed.close()
    xr.testing.assert_identical(ds.drop_attrs(), sweeps.open_sweep(tmp_path / "streamed.nc").drop_attrs())


def test_solution_to_xarray(tmp_path):
    model = g.Model(g.Body([1.0, 2.0, 3.0]), [g.LinearDamping(np.diag([0.1, 0.1, 0.1]))], attitude=True)
    sol = g.solve(model, [1.0, 0.5, -0.3], (0, 10), n_out=21, events=[g.events.Event("r")])
    ds = sol.to_xarray()
    assert np.array_equal(ds["time"].values, sol.t) and np.array_equal(ds["q_z"].values, sol["q_z"])
    assert ds["kinetic_energy"].attrs["units"] == "J" and ds["p"].attrs["units"] == "rad/s"
    assert np.array_equal(ds["t_event_r_0"].values, sol.t_events[0]) and ds.attrs["status"] == "success"
    ds.to_netcdf(tmp_path / "solution.nc")
    xr.testing.assert_identical(ds, xr.open_dataset(tmp_path / "solution.nc").load())


def test_a_dask_local_cluster_gives_the_same_dataset(tmp_path, capsys):
    from distributed import Client, LocalCluster

    doc = scene("forced_damped", t_span=[0.0, 5.0], n_out=11)
    local = g.sweep(doc, DISPERSED, samples=40, seed=3, progress=False)
    with LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None) as cluster:
        with Client(cluster) as client:
            remote = g.sweep(doc, DISPERSED, samples=40, seed=3, progress=False, client=client, chunk_size=6)
        # the command line on the same cluster, by its address
        path = SCENES / "torque_free_integrated.toml"
        vary = ["--vary", "initial.omega[0]~uniform(0.5,1.5)", "--samples", "12", "--seed", "4", "--quiet"]
        assert main(["sweep", str(path), *vary, "--dask", cluster.scheduler_address,
                     "--out", str(tmp_path / "dask")]) == 0
    assert main(["sweep", str(path), *vary, "--out", str(tmp_path / "local")]) == 0
    capsys.readouterr()
    xr.testing.assert_identical(local.drop_attrs(), remote.drop_attrs())
    assert (remote["status"] == "invalid_input").any()  # failing members travel back from the workers too
    on_dask, here = (sweeps.open_sweep(tmp_path / where / "torque_free_integrated" / "sweep.nc").drop_attrs()
                     for where in ("dask", "local"))
    xr.testing.assert_identical(on_dask, here)
    assert main(["sweep", str(path), *vary, "--dask", "tcp://127.0.0.1:1", "--out", str(tmp_path / "none")]) == 2
    assert "cannot reach the scheduler" in capsys.readouterr().err


# ------------------------------------------------------------------------------------ worker processes
def test_worker_processes_give_the_dataset_of_one_process(tmp_path):
    # the same members, refusals and numbers bit for bit: each chunk is solve_chunk's, wherever it runs
    doc = scene("forced_damped", t_span=[0.0, 5.0], n_out=11)
    alone = g.sweep(doc, DISPERSED, samples=60, seed=3, progress=False, workers=1, chunk_size=7)
    forked = g.sweep(doc, DISPERSED, samples=60, seed=3, progress=False, workers=2, chunk_size=7)
    xr.testing.assert_identical(alone.drop_attrs(), forked.drop_attrs())
    assert (forked["status"] == "invalid_input").any() and (forked["status"] == "success").any()
    streamed = g.sweep(doc, DISPERSED, samples=60, seed=3, progress=False, workers=2, chunk_size=7,
                       trajectories=False, path=tmp_path / "s.nc")
    summaries = g.sweep(doc, DISPERSED, samples=60, seed=3, progress=False, workers=1, chunk_size=7,
                        trajectories=False)
    xr.testing.assert_identical(summaries.drop_attrs(), streamed.load().drop_attrs())


def test_workers_by_default_and_refused(monkeypatch, tmp_path, capsys):
    cores = runners._cores()
    monkeypatch.setattr(runners, "_forks", lambda: True)
    assert runners._processes(None, 0, sweeps.WORKERS_FROM) == cores  # a large sweep: every core's process
    assert runners._processes(None, 0, sweeps.WORKERS_FROM - 1) == 1  # small: forking costs more than it gains
    assert runners._processes(None, 1, sweeps.WORKERS_FROM) == 1  # threads=1: one core asked for
    assert runners._processes(-1, 1, 5) == cores and runners._processes(3, 0, 5) == 3
    monkeypatch.setattr(runners, "_daemon", lambda: True)  # inside a Dask task: a daemon has no children
    assert runners._processes(None, 0, sweeps.WORKERS_FROM) == 1
    with pytest.raises(ValueError, match="workers = 2: this process is a daemon"):
        runners._processes(2, 0, 5)
    monkeypatch.setattr(runners, "_daemon", lambda: False)
    monkeypatch.setattr(runners, "_forks", lambda: False)
    assert runners._processes(None, 0, 10 * sweeps.WORKERS_FROM) == 1  # no fork: no spawned surprise
    doc = scene("forced_damped", t_span=[0.0, 1.0], n_out=3)
    for bad in (0, -2, True, 2.5, "2"):
        with pytest.raises(ValueError, match=f"workers = {bad!r} must be"):
            g.sweep(doc, {"initial.omega[0]": [1.0, 2.0]}, workers=bad, progress=False)
    assert main(["sweep", str(SCENES / "forced_damped.toml"), "--vary", "initial.omega[0]=1,2", "--workers", "0",
                 "--out", str(tmp_path)]) == 2
    assert "error: workers = 0 must be a positive whole number" in capsys.readouterr().err


def test_a_failing_worker_process_is_recorded_per_member(monkeypatch):
    # the forked workers inherit the patched solve_chunk: chunk 0 raises there, the other chunk is solved
    real = sweeps.solve_chunk

    def failing(plan, start, stop, **options):
        if start == 0:
            raise RuntimeError("disk full")
        return real(plan, start, stop, **options)

    monkeypatch.setattr(runners, "solve_chunk", failing)
    ds = g.sweep(scene("forced_damped", t_span=[0.0, 1.0], n_out=3), {"initial.omega[0]": np.linspace(1, 2, 8)},
                 workers=2, chunk_size=4, progress=False)
    status = ds["status"].values
    assert list(status[:4]) == ["failed"] * 4 and list(status[4:]) == ["success"] * 4
    assert "the worker process failed: RuntimeError: disk full" in str(ds["message"].values[0])
    assert np.array_equal(ds["initial.omega[0]"].values, np.linspace(1, 2, 8))  # the values kept


def test_a_worker_process_that_dies_fails_its_members_not_the_sweep(monkeypatch):
    # a worker killed (out of memory, a signal: os._exit here) breaks the pool: the chunks it and the
    # others had not returned are recorded as failed, with the reason; the sweep returns
    real = sweeps.solve_chunk

    def dying(plan, start, stop, **options):
        if start == 4:
            os._exit(9)
        return real(plan, start, stop, **options)

    monkeypatch.setattr(runners, "solve_chunk", dying)
    ds = g.sweep(scene("forced_damped", t_span=[0.0, 1.0], n_out=3), {"initial.omega[0]": np.linspace(1, 2, 40)},
                 workers=2, chunk_size=4, progress=False)
    status, message = ds["status"].values, ds["message"].values
    assert set(status) <= {"success", "failed"} and list(status[4:8]) == ["failed"] * 4
    assert all("BrokenProcessPool" in m for m in message[status == "failed"])
    assert np.array_equal(ds["initial.omega[0]"].values, np.linspace(1, 2, 40))
    assert np.all(np.isfinite(ds["final_p"].values[status == "success"]))


# ------------------------------------------------------------------------------------ stopping and progress
@pytest.mark.parametrize("where", [{"threads": 1}, {"workers": 2}], ids=["this_process", "worker_processes"])
def test_ctrl_c_keeps_the_members_that_finished(where, ctrl_c, capfd):
    # members of ~0.1 s each: ~40 s for the 400 on one core, should the signal be lost
    doc = scene("torque_free_integrated", t_span=[0.0, 5e4], n_out=11)
    # Ctrl-C once 5 % of the work is done (some members finished, whatever the machine's load),
    # sent from another thread as a user's would be; to this process alone: with worker processes
    # it forwards the signal to them
    some_done = threading.Event()
    timer = threading.Thread(target=lambda: some_done.wait(60) and ctrl_c())
    timer.start()

    def progress(fraction):
        if fraction >= 0.05:
            some_done.set()

    with pytest.warns(RuntimeWarning, match="sweep interrupted"):
        ds = g.sweep(doc, {"initial.omega[0]": np.linspace(0.5, 1.5, 400)}, progress=progress, chunk_size=2,
                     **where)
    timer.join()
    status = ds["status"].values
    assert ds.attrs["interrupted"] == 1
    finished = status == "success"
    assert 0 < finished.sum() < 400 and set(status[~finished]) == {"interrupted"}, \
        (finished.sum(), sorted(set(zip(status[~finished], ds["message"].values[~finished]))))
    assert np.all(np.isfinite(ds["final_p"].values[finished]))
    assert np.all(ds["initial.omega[0]"].values == np.linspace(0.5, 1.5, 400))  # no member lost
    assert "Traceback" not in capfd.readouterr().err  # no worker dies of the signal


def test_progress_bar_is_on_when_asked_and_off_with_false(capsys):
    doc = scene("torque_free_integrated", t_span=[0.0, 1.0], n_out=5)
    g.sweep(doc, {"initial.omega[0]": [0.5, 1.0, 1.5]}, progress=True, chunk_size=1)
    assert "member" in capsys.readouterr().err
    g.sweep(doc, {"initial.omega[0]": [0.5, 1.0, 1.5]}, progress=False, chunk_size=1)
    assert capsys.readouterr().err == ""
    fractions = []
    g.sweep(doc, {"initial.omega[0]": [0.5, 1.0, 1.5]}, progress=fractions.append, chunk_size=1)
    assert fractions[-1] == 1.0 and fractions == sorted(fractions)


# ------------------------------------------------------------------------------------ errors
@pytest.mark.parametrize("vary, message", [
    ({"body.momnets[0]": [1.0]}, "unknown key 'momnets' in [body]; did you mean 'moments'?"),
    ({"body.moments[3]": [1.0]}, "index 3 is outside the 3 entries"),
    ({"integration.method": [1.0]}, "'integration.method' is 'dop853', not a number"),
    ({"torques[1].diagonal[0]": [1.0]}, "[torques[1]] diagonal is not set in the scene"),
    ({"torques[5].moment[0]": [1.0]}, "[torques] has 2 entries"),
    ({"body": [1.0]}, "body is a table, not a value"),
    ({"body.moments[0": [1.0]}, "is not a path"),
    ({"body.moments[0]": [1.0], "initial.omega[0]": g.Uniform(0, 1)}, "mixes grid values and distributions"),
    ({"body.moments[0]": g.Uniform(0, 1)}, "needs samples"),
    ({"body.moments[0]": [float("nan")]}, "must be finite numbers"),
    ({"integration.n_out": [11, 21]}, "trajectories differ in length"),
])
def test_bad_sweeps_are_one_line_errors(vary, message):
    doc = scene("forced_damped", t_span=[0.0, 1.0], n_out=5)
    with pytest.raises(ValueError) as error:
        g.sweep(doc, vary, progress=False)
    assert message in str(error.value) and "\n" not in str(error.value)


def test_bad_distributions_and_values_name_the_value():
    with pytest.raises(ValueError, match=r"LogUniform\(-1, 1\): needs 0 < low < high"):
        g.LogUniform(-1, 1)
    with pytest.raises(ValueError, match=r"Normal\(0, 0\): std must be positive"):
        g.Normal(0, 0)
    doc = scene("forced_damped", t_span=[0.0, 1.0], n_out=5)
    ds = g.sweep(doc, {"integration.rtol": [1e-8, -1.0]}, progress=False)  # a key's own checks, per member
    assert list(ds["status"].values) == ["success", "invalid_input"]
    assert ds["message"].values[1] == "[integration] rtol = -1.0: must be a finite positive number"  # the engine's rule


def test_a_members_numbers_are_checked_alone_only_where_that_equals_checking_the_whole_scene():
    """Plan.document checks a number set into a value by itself when every check of its field
    holds number by number (schema.elementwise); the document and the refusals must be those of
    validating the member's whole scene, and a field with another check (rtol's engine rule) is
    still validated whole."""
    from gyrostat.families import KINDS
    from gyrostat.schema import validate

    doc = scene("explorer1_flat_spin", t_span=[0.0, 10.0], n_out=5, model="full")
    vary = {"torques[0].p0": [2e-4, -1e-4, 0.0], "initial.omega[0]": [0.05, -0.1]}  # p0: positive; omega: finite
    plan = sweeps.Plan(doc, vary)
    assert [located.numbers_alone for _, _, located in plan.located] == [True, True]
    schema = KINDS[plan.kind_name].schema
    refused = 0
    for i in range(plan.size):
        values = plan.values(i)
        whole = json.loads(json.dumps(doc))  # the member's scene as a user would write it
        whole["torques"][0]["p0"], whole["initial"]["omega"][0] = values
        try:
            expected = validate(schema, whole, "scene")
        except SceneError as error:
            with pytest.raises(SceneError) as member_error:
                plan.document(values)
            assert str(member_error.value) == str(error)  # the same message, naming the key and the value
            refused += 1
            continue
        assert plan.document(values) == expected
    assert refused == 4  # p0 = -1e-4 and p0 = 0, each with two omegas
    ds = g.sweep(doc, vary, progress=False, trajectories=False)
    assert list(ds["status"].values.ravel()) == ["success", "success"] + ["invalid_input"] * 4  # p0 by omega
    assert ds["message"].values[1, 0] == "[torques[0]] p0 = -0.0001: must be positive"
    assert not sweeps.Plan(doc, {"integration.rtol": [1e-8]}).located[0][2].numbers_alone  # an engine rule


def test_a_chunks_members_share_the_body_and_torques_no_parameter_changes():
    from gyrostat.kind import reusing

    doc = scene("forced_damped", t_span=[0.0, 1.0], n_out=5)
    plan = sweeps.Plan(doc, {"torques[1].matrix[0][0]": [0.02, 0.03]})
    with reusing(plan.base):
        first, second = (plan.member(plan.values(i)).model for i in range(2))
    assert first.torques[0] is second.torques[0] and first.body is second.body  # built once
    assert first.torques[1] is not second.torques[1]  # the changed one is each member's own
    np.testing.assert_array_equal(np.asarray(second.torques[1].matrix)[0], [0.03, 0.01, 0.0])
    alone = [plan.member(plan.values(i)).model for i in range(2)]  # outside the context: nothing is shared
    assert alone[0].torques[0] is not alone[1].torques[0] and alone[0].body is not alone[1].body


def test_memory_is_checked_before_anything_runs(monkeypatch):
    doc = scene("forced_damped", t_span=[0.0, 1.0], n_out=1001)
    monkeypatch.setattr(storage, "MEMORY_LIMIT", 2**20)
    with pytest.raises(ValueError, match=r"needs about 0\.\d GiB .*trajectories=False.*path="):
        g.sweep(doc, {"initial.omega[0]": np.linspace(0, 1, 100)}, progress=False)
    summaries = g.sweep(doc, {"initial.omega[0]": np.linspace(0, 1, 100)}, progress=False, trajectories=False)
    assert "time" not in summaries.dims and summaries.sizes["initial.omega[0]"] == 100


def test_summary_expressions_are_arithmetic_only():
    doc = scene("forced_damped", t_span=[0.0, 1.0], n_out=5)
    ds = g.sweep(doc, {"initial.omega[0]": [0.5, 1.0]}, progress=False)
    np.testing.assert_array_equal(sweeps.summary(ds, "final_p * 2 - final_q").values,
                                  ds["final_p"].values * 2 - ds["final_q"].values)
    for bad in ("__import__('os')", "final_p.values", "nope + 1"):
        with pytest.raises(ValueError, match="summary"):
            sweeps.summary(ds, bad)


# ------------------------------------------------------------------------------------ the command line
def test_cli_sweep_writes_the_dataset_and_the_plot(tmp_path, capsys):
    path = SCENES / "torque_free_integrated.toml"
    code = main(["sweep", str(path), "--vary", "body.moments[0]=1.0:2.0:3", "--vary", "initial.omega[1]=0.1,0.5",
                 "--out", str(tmp_path), "--quiet", "--summary", "max_kinetic_energy - min_kinetic_energy"])
    out = capsys.readouterr().out
    assert code == 0 and "sweep of 6 members (grid)" in out and "6 success" in out
    folder = tmp_path / "torque_free_integrated"
    ds = sweeps.open_sweep(folder / "sweep.nc")
    assert ds.sizes["body.moments[0]"] == 3 and ds.sizes["initial.omega[1]"] == 2
    assert json.loads((folder / "sweep.json").read_text())["statuses"] == {"success": 6}
    assert (folder / "sweep.png").stat().st_size > 10_000

    code = main(["sweep", str(path), "--vary", "body.moments[0]~normal(1.0,0.5)", "--samples", "30", "--seed", "2",
                 "--out", str(tmp_path / "mc"), "--quiet"])
    assert code == 0 and "(dispersion, seed 2)" in capsys.readouterr().out
    assert sweeps.open_sweep(tmp_path / "mc" / "torque_free_integrated" / "sweep.nc").attrs["seed"] == 2
    # one sweep per folder: a second one is refused, --overwrite replaces it
    again = ["sweep", str(path), "--vary", "body.moments[0]=1.0:2.0:2", "--out", str(tmp_path), "--quiet"]
    assert main(again) == 2 and "holds an earlier sweep" in capsys.readouterr().err
    assert main(again + ["--overwrite"]) == 0 and "sweep of 2 members" in capsys.readouterr().out

    for bad, message in ((["--vary", "body.moments[0]=1:2"], "write PATH=START:STOP:NUM"),
                         (["--vary", "body.mass[0]=1:2:3"], "unknown key 'mass' in [body]"),
                         ([], "has no [sweep] table")):
        assert main(["sweep", str(path), "--out", str(tmp_path / "bad"), "--quiet", *bad]) == 2
        err = capsys.readouterr().err
        assert message in err and "Traceback" not in err and err.count("\n") == 1


def test_the_shipped_p001_map_finds_x_equal_y_off_the_papers_line(tmp_path):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", g.ValidityWarning)
        from gyrostat.runner import run_sweep

        report = run_sweep(SCENES / "p001_xy_ratio_map.toml", tmp_path, progress=False)
    assert report["statuses"] == {"success": 39 * 61}
    # the paper's own damper breaks its condition (4) everywhere: every member says so
    assert report["members_with_broken_assumptions"] == 39 * 61
    assert any("condition (4)" in text for text in report["broken_assumptions"])
    ds = sweeps.open_sweep(tmp_path / "p001_xy_ratio_map" / "sweep.nc")
    ratio = sweeps.summary(ds, "final_x / final_y")
    on_line = np.array([float(ratio.sel(A_over_C=a, I1_over_I3=a, method="nearest")) for a in ds["A_over_C"].values])
    # on A/C = I1/I3 the damper's S > 0 keeps pushing x above y: d ln(x/y)/dt = 2S(y^2/A + Axy/C^2)
    # (docs/papers/001_moving_mass.md, item 6): x/y - 1 is small but positive, never 0
    assert np.all(on_line - 1 > 1e-3) and np.all(on_line - 1 < 3e-2)
