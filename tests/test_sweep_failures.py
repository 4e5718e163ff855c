"""A member whose run raises (a user's Python torque raising for its values) fails alone: it gets
status "failed" and its own exception, every other member its own result, equal to its single
solve bit for bit, on every runner (this process, worker processes, an in-process Dask cluster)."""

import numpy as np
import pytest

import gyrostat as g
from gyrostat import sweeps

# The torque is a module beside the scene file (a scene imports code from its own folder): a
# factory whose torque raises, naming the member's spin, when omega[0] is above `limit`.
TORQUE = '''
import numpy as np


def limited(limit, damping):
    def torque(t, omega):
        if omega[0] > limit:
            raise ValueError(f"omega[0] = {omega[0]:.3f} rad/s is above the limit {limit}")
        return -damping * omega
    return torque
'''

SCENE = """
body.moments = [1.0, 2.0, 2.5]
torques = [{ type = "custom", function = "sweep_failure_torque:limited", parameters = { limit = 1.5, damping = 0.05 } }]
initial.omega = [1.0, 0.5, -0.3]
integration = { model = "full", method = "dop853", rtol = 1e-10, atol = 1e-12, t_span = [0.0, 5.0], n_out = 11 }
"""

# chunks of 2: (1.0, 1.6), (1.2, 1.1), (1.7, 0.9): a failing member shares its chunk with one that succeeds
SPINS = [1.0, 1.6, 1.2, 1.1, 1.7, 0.9]
FAILING = {1: "ValueError: omega[0] = 1.600 rad/s is above the limit 1.5",
           4: "ValueError: omega[0] = 1.700 rad/s is above the limit 1.5"}


@pytest.fixture
def scene_file(tmp_path_factory, monkeypatch):
    folder = tmp_path_factory.getbasetemp() / "sweep_failures"
    if not folder.exists():
        folder.mkdir()
        (folder / "sweep_failure_torque.py").write_text(TORQUE)
        (folder / "limited.toml").write_text(SCENE)
    monkeypatch.syspath_prepend(str(folder))  # for a loader that imports by sys.path; harmless otherwise
    return folder / "limited.toml"


def dask_client():
    distributed = pytest.importorskip("distributed")
    cluster = distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=False, dashboard_address=None)
    return cluster, distributed.Client(cluster)


def assert_each_member_is_its_own(ds, plan: sweeps.Plan, vary_name: str, failing: dict) -> None:
    status, message = ds["status"].values, ds["message"].values
    assert np.array_equal(ds[vary_name].values, np.array([plan.values(i)[0] for i in range(plan.size)]))
    for i in range(plan.size):
        member = ds.isel({vary_name: i})
        if i in failing:
            assert status[i] == "failed" and message[i] == failing[i]
            assert np.all(np.isnan(member["final_p"].values)) and int(member["steps"]) == 0
            continue
        run = plan.member(plan.values(i))
        alone = g.solve(run.model, run.y0, run.t_span, **run.options, progress=False)
        assert alone.success and status[i] == "success" and message[i] == alone.message
        for name in plan.names:  # bit for bit: the same engine, options and inputs (no SIMD batch for a Python torque)
            assert np.array_equal(member[name].values, alone[name]), (i, name)
            assert member[f"final_{name}"].values == alone[name][-1], (i, name)
        assert np.array_equal(member["t"].values if "t" in member else member["time"].values, alone.t)
        assert int(member["steps"]) == alone.stats["steps"] and int(member["rhs_evals"]) == alone.stats["rhs_evals"]


@pytest.mark.parametrize("runner", ["this_process", "worker_processes", "dask"])
def test_a_members_exception_is_its_own_on_every_runner(scene_file, runner):
    vary = {"initial.omega[0]": SPINS}
    plan = sweeps.Plan(scene_file, vary)
    if runner == "dask":
        cluster, client = dask_client()
        with cluster, client:
            ds = g.sweep(plan, None, client=client, chunk_size=2, progress=False)
    else:
        ds = g.sweep(plan, None, workers=1 if runner == "this_process" else 2, chunk_size=2, threads=1,
                     progress=False)
    assert ds.attrs["interrupted"] == 0
    assert_each_member_is_its_own(ds, plan, "initial.omega[0]", FAILING)


def test_a_swept_torque_parameter_fails_only_its_member(scene_file):
    # the limit itself swept: member 1's limit (0.5) is below the spin, 1.0, at t = 0; a chunk of 3
    plan = sweeps.Plan(scene_file, {"torques[0].parameters.limit": [1.5, 0.5, 2.0]})
    ds = g.sweep(plan, None, workers=1, chunk_size=3, progress=False)
    assert_each_member_is_its_own(ds, plan, "torques[0].parameters.limit",
                                  {1: "ValueError: omega[0] = 1.000 rad/s is above the limit 0.5"})


def test_summaries_only_and_every_member_failing(scene_file):
    # the bulk summaries (trajectories=False) of the members that ran; a chunk whose members all fail
    plan = sweeps.Plan(scene_file, {"initial.omega[0]": [1.6, 1.7, 1.0]})
    ds = g.sweep(plan, None, workers=1, chunk_size=2, trajectories=False, progress=False)
    assert list(ds["status"].values) == ["failed", "failed", "success"]
    assert list(ds["message"].values[:2]) == [FAILING[1], FAILING[4]]
    run = plan.member(plan.values(2))
    alone = g.solve(run.model, run.y0, run.t_span, **run.options, progress=False)
    for name in plan.names:
        assert ds[f"final_{name}"].values[2] == alone[name][-1], name
