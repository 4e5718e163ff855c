"""Runs that stop (max_steps, Ctrl-C, a terminal event, a failure) say where, and continue from
there to the same trajectory; output folders hold one run each; write errors are told."""

import json
import threading
import time

import numpy as np
import pytest

import gyrostat as g
from gyrostat import lagrange, orthogonal
from gyrostat.cli import main

BODY = g.Body([1.0, 2.0, 3.0])
W0 = [1.0, 0.5, -0.3]


def models():
    """One model per family, with a state to start from."""
    damped = g.Model(BODY, [g.ConstantTorque([0, 0, 0.02]), g.LinearDamping(np.diag([0.01, 0.02, 0.03]))],
                     attitude=True)
    top = lagrange.LagrangeTop(1.5, 1.0, 0.5, [lagrange.paper_torque(0.01)])
    top_y0 = lagrange.initial_state([0.0, 0.0, 1.7], theta=0.5)
    return {
        "gyrostat": (damped, W0),
        "averaged": (g.AveragedModel(g.Body([2.0, 2.0, 1.0]), [g.LinearDamping(np.diag([0.1, 0.1, 0.05]))]), [1.0, 1.0]),
        "moving_mass": (g.MovingMassModel(g.Body([4.0, 4.0, 2.0]), mass=1, arm=1, frequency=10, damping=20),
                        None),
        "lagrange_top": (top, top_y0),
        "orthogonal": (orthogonal.OrthogonalModel(g.Body([2, 3, 4], [0.3, -0.2, 0.5]), orthogonal.constant(0.1)),
                       [1.0, 0.5, -0.8]),
    }


@pytest.mark.parametrize("family, method", [(family, method)
                                            for family in ("gyrostat", "averaged", "moving_mass", "lagrange_top", "orthogonal")
                                            for method in ("dop853", "cvode_bdf")] + [("gyrostat", "taylor")])
def test_a_run_stopped_by_max_steps_continues_to_the_uninterrupted_trajectory(family, method):
    model, y0 = models()[family]
    if y0 is None:
        y0 = model.quasi_static_state([1.0, 0.0, 1.0])
    t1 = 20.0
    times = np.linspace(0.0, t1, 41)
    whole = g.solve(model, y0, (0.0, t1), method=method, rtol=1e-10, atol=1e-12, t_eval=times)
    # the last accepted state is the last output (both projected: a unit quaternion)
    assert whole.success and whole.t_last == t1 and np.array_equal(whole.y_last, whole.y[-1])
    part = g.solve(model, y0, (0.0, t1), method=method, rtol=1e-10, atol=1e-12, t_eval=times,
                   max_steps=whole.stats["steps"] // 2)
    assert part.status == "max_steps_reached" and 0.0 < part.t_last < t1
    assert len(part.y_last) == len(model.state_names) and np.all(np.isfinite(part.y_last))
    later = times[times > part.t_last]
    rest = g.solve(model, part, (part.t_last, t1), method=method, rtol=1e-10, atol=1e-12, t_eval=later)
    assert rest.success and rest.t_last == t1
    if method == "dop853" and "q_w" not in model.state_names:
        # the same steps from the same state with the same next step: bit for bit
        assert np.array_equal(rest.y, whole.y[-len(later):])
    elif method == "dop853":
        # the same steps, but the start's quaternion is normalised once more (a last-bit change):
        # 1e-12 relative is a thousand ulps, far below the tolerance
        np.testing.assert_allclose(rest.y, whole.y[-len(later):], rtol=1e-12, atol=1e-13)
    elif method == "taylor":
        # Taylor's step prediction (taylor.hpp: OneTaylorRun::step_size) restarts: the continued run
        # takes the allowed step until the prediction has two steps to go on, then its own, each
        # within the rule, so the two agree to their global error, not bit for bit (measured: 9.2e-13
        # at most, 1.4e-12 of a component's size; bounds 1e-9 relative and 1e-10 absolute, the
        # size of the error two runs at rtol 1e-10 may each make over t = 20)
        np.testing.assert_allclose(rest.y, whole.y[-len(later):], rtol=1e-9, atol=1e-10)
    else:
        # CVODE restarts its BDF history at order 1: the same solution to the tolerance (1e-10 relative;
        # 1e-7 absolute covers the global error accumulated over t = 20 by two runs at rtol 1e-10)
        np.testing.assert_allclose(rest.y, whole.y[-len(later):], rtol=1e-6, atol=1e-7)


def test_ctrl_c_and_terminal_events_say_where_they_stopped(ctrl_c):
    model = g.Model(BODY, attitude=True)
    # Ctrl-C from another thread once the run has started (its first progress report), whatever
    # the machine's load; the run would take ~10 s (2e7 steps at ~2e6 a second): a lost signal
    # fails the test instead of waiting for minutes
    started = threading.Event()
    timer = threading.Thread(target=lambda: started.wait(60) and (time.sleep(0.1), ctrl_c()))
    timer.start()
    with pytest.warns(RuntimeWarning, match="interrupted"):
        stopped = g.solve(model, W0, (0, 1e8), n_out=11, max_steps=2 * 10**7, progress=lambda fraction: started.set())
    timer.join()
    assert stopped.status == "interrupted" and 0 < stopped.t_last < 1e8 and stopped.h_next > 0
    # the state there is the body's: its |G| is the torque-free motion's, to the drift that rtol 1e-8
    # allows over the ~1e5 steps taken in 0.3 s (1e-3 relative)
    G0 = np.linalg.norm(np.array([1.0, 2.0, 3.0]) * W0)
    assert abs(np.linalg.norm(np.array([1.0, 2.0, 3.0]) * stopped.y_last[:3]) - G0) < 1e-3 * G0
    more = g.solve(model, stopped, (stopped.t_last, stopped.t_last + 10.0), n_out=3)
    assert more.success and more.t[0] == stopped.t_last

    event = g.solve(model, W0, (0, 100), events=[g.events.Event("r", terminal=True)])
    assert event.terminal_event == 0 and event.t_last == event.t_events[0][0]
    # the state at the crossing, its quaternion projected like every recorded one (a few ulps)
    np.testing.assert_allclose(event.y_last, event.y_events[0][0], rtol=1e-14, atol=1e-15)


def test_continuing_refuses_a_wrong_start():
    model = g.Model(BODY)
    part = g.solve(model, W0, (0, 10), max_steps=5)
    with pytest.raises(ValueError, match=r"start at its t_last = .*, not at t0 = 0.0"):
        g.solve(model, part, (0.0, 10.0))


def test_closed_form_and_failures_keep_their_last_state():
    exact = g.solve(g.TorqueFreeModel(BODY), W0, (0, 5), n_out=6)
    assert exact.t_last == 5.0 and np.array_equal(exact.y_last, exact.y[-1])
    blown = g.solve(g.Model(BODY, [g.LinearDamping(-np.eye(3) * 50)]), W0, (0, 100))
    assert not blown.success and np.all(np.isfinite(blown.y_last)) and blown.t_last < 100
    assert np.linalg.norm(blown.y_last) > 1e3  # where it stopped, the state had grown like e^(50 t)


# ------------------------------------------------------------------------------------ output folders
SCENE = g.scene.SCENES / "torque_free_triaxial.toml"


def test_one_run_per_output_folder(tmp_path, capsys):
    assert main(["run", str(SCENE), "--out", str(tmp_path), "--quiet"]) == 0
    capsys.readouterr()
    stale = tmp_path / "torque_free_triaxial" / "stale.png"
    stale.write_bytes(b"an earlier run's plot")
    assert main(["run", str(SCENE), "--out", str(tmp_path), "--quiet"]) == 1
    err = capsys.readouterr().err
    assert "holds an earlier run" in err and "--overwrite" in err and "Traceback" not in err
    assert main(["run", str(SCENE), "--out", str(tmp_path), "--quiet", "--overwrite"]) == 0
    assert not stale.exists() and (tmp_path / "torque_free_triaxial" / "report.json").exists()
    foreign = tmp_path / "mine" / "torque_free_triaxial"
    foreign.mkdir(parents=True)
    (foreign / "thesis.tex").write_text("not gyrostat's")
    assert main(["run", str(SCENE), "--out", str(tmp_path / "mine"), "--quiet", "--overwrite"]) == 1
    assert "did not write" in capsys.readouterr().err and (foreign / "thesis.tex").exists()


def test_a_write_error_is_told_and_no_results_are_claimed(tmp_path, capsys, monkeypatch):
    from gyrostat import output

    def full_disk(*args, **kwargs):
        raise OSError(28, "No space left on device")

    monkeypatch.setattr(output, "write_columns", full_disk)
    assert main(["run", str(SCENE), "--out", str(tmp_path), "--quiet"]) == 1
    captured = capsys.readouterr()
    assert "No space left on device" in captured.err and "results in" not in captured.out


def test_a_scene_report_says_where_each_run_stopped():
    from gyrostat import runner

    scene = g.scene.load(g.scene.SCENES / "forced_damped.toml")
    solutions, report, _ = runner.solve_scene(scene, progress=False)
    entry = report["runs"]["full"]
    assert entry["t_last"] == scene.runs[0].t_span[1] and len(entry["y_last"]) == len(scene.runs[0].model.state_names)
    from gyrostat import output

    json.dumps(output.clean(report))
