"""A scene runs no code its user did not allow (gyrostat.scene_code): names outside the scene's
folder and the modules allowed are refused before anything is imported or called, through the
Python loader, the command line (run, check, sweep) and sweeps on worker processes; nothing is
imported or called while a scene is validated; what is allowed runs and gives the reference's
answer.

Every "nothing ran" assertion looks for a marker file that the named code would have written:
at import (the module's top level) or at call (the factory)."""

from __future__ import annotations

import os
import pickle
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import gyrostat as g
from gyrostat.runner import solve_scene
from gyrostat.scene import Scene
from gyrostat.scene_code import Allowance, CodeName
from gyrostat.schema import SceneError
from gyrostat.sweeps import Plan

PYTHON_DIR = str(Path(g.__file__).resolve().parent.parent)  # child processes import this gyrostat
J, W0 = [1.0, 2.0, 2.5], [1.0, 0.5, -0.3]

# a module that leaves a marker when it is imported and another when its factory is called
MODULE = '''
import pathlib
import numpy as np
pathlib.Path(__file__).with_name("imported.marker").write_text("{name}")

def drag_factory(c, a=0.0):
    pathlib.Path(__file__).with_name("called.marker").write_text("{name}")
    def drag(t, omega):
        omega = np.asarray(omega)
        return -c * np.linalg.norm(omega) * omega + np.array([0.0, 0.0, a * np.sin(t)])
    return drag

def three(c):
    return 3
'''


def scene_text(function: str, parameters: str = "{ c = 0.05, a = 0.02 }", extra: str = "") -> str:
    return f"""[body]
moments = {J}
[[torques]]
type = "custom"
function = "{function}"
parameters = {parameters}
[initial]
omega = {W0}
[integration]
model = "full"
method = "dop853"
rtol = 1e-12
atol = 1e-14
t_span = [0.0, 5.0]
n_out = 11
[outputs]
plots = []
{extra}"""


def write_module(folder: Path, dotted: str) -> Path:
    """The marker module at ``dotted`` below ``folder`` (packages made as needed)."""
    parts = dotted.split(".")
    folder.mkdir(parents=True, exist_ok=True)
    for i in range(1, len(parts)):
        package = folder.joinpath(*parts[:i])
        package.mkdir(parents=True, exist_ok=True)
        (package / "__init__.py").touch()
    path = folder.joinpath(*parts[:-1], parts[-1] + ".py")
    path.write_text(MODULE.format(name=dotted))
    return path.parent


def reference(c: float = 0.05, a: float = 0.02) -> np.ndarray:
    """The same drag through the Python API (its function written here, not imported)."""
    def drag(t, omega):
        omega = np.asarray(omega)
        return -c * np.linalg.norm(omega) * omega + np.array([0.0, 0.0, a * np.sin(t)])
    return g.solve(g.Model(g.Body(J), [g.CustomTorque(drag)]), W0, (0.0, 5.0), n_out=11, method="dop853",
                   rtol=1e-12, atol=1e-14).y


def cli(*args, cwd: Path) -> subprocess.CompletedProcess:
    env = dict(os.environ, PYTHONPATH=PYTHON_DIR + os.pathsep + os.environ.get("PYTHONPATH", ""))
    return subprocess.run([sys.executable, "-m", "gyrostat", *map(str, args)], capture_output=True, text=True,
                          env=env, cwd=cwd, timeout=300)


def one_line_refusal(stderr: str, *words: str) -> None:
    lines = [line for line in stderr.splitlines() if line.strip()]
    assert len(lines) == 1 and "Traceback" not in stderr, stderr
    for word in ("names code in module", "a scene runs only code its user allows", "--allow-import", *words):
        assert word in lines[0], lines[0]


def fresh_module_name(tmp_path: Path) -> str:
    """A module name no test imported before (sys.modules keeps modules between tests)."""
    return "scene_code_" + tmp_path.name.replace("-", "_")


# ------------------------------------------------------------------------------------ refused
def test_the_issue_scene_runs_no_shell_command(tmp_path):
    """The issue's scene: subprocess.run with shell = true. Refused by run, check and sweep with
    exit 2 and one line; the shell command never runs (no file 'pwned')."""
    path = tmp_path / "s.toml"
    path.write_text(scene_text("subprocess:run", '{ args = "touch pwned", shell = true }'))
    for command in (["run", path, "--out", tmp_path / "out"], ["check", path],
                    ["sweep", path, "--vary", "initial.omega[0]=1:2:2", "--out", tmp_path / "out"]):
        done = cli(*command, cwd=tmp_path)
        assert done.returncode == 2, (command, done.stderr)
        one_line_refusal(done.stderr, "scene 's'", "[torques[0]] function", "'subprocess:run'", "subprocess")
    assert not (tmp_path / "pwned").exists()
    assert not (tmp_path / "out" / "s").exists()  # nothing ran, nothing written


@pytest.mark.parametrize("function, module", [("os:system", "os"),               # the standard library
                                              ("numpy.testing:assert_equal", "numpy.testing"),  # site-packages
                                              ("scipy.optimize:rosen", "scipy.optimize")])
def test_names_outside_the_folder_are_refused_before_import(tmp_path, function, module):
    with pytest.raises(SceneError) as raised:
        Scene.from_dict({"body": {"moments": J}, "initial": {"omega": W0},
                         "torques": [{"type": "custom", "function": function}]}, name="shared")
    message = str(raised.value)
    assert "\n" not in message and f"'{function}'" in message and f"allow_import=[{module!r}]" in message, message
    assert "scene 'shared'" in message and "[torques[0]] function" in message, message


def test_a_module_outside_the_scene_folder_is_neither_imported_nor_called(tmp_path, monkeypatch):
    """A module importable from sys.path but outside the scene's folder (a sibling folder):
    refused, its top level never run (no import marker); allowed by name, it runs."""
    name = fresh_module_name(tmp_path)
    elsewhere = write_module(tmp_path / "elsewhere", name)
    monkeypatch.syspath_prepend(str(elsewhere))
    scene_dir = tmp_path / "scenes"
    scene_dir.mkdir()
    path = scene_dir / "s.toml"
    path.write_text(scene_text(f"{name}:drag_factory"))
    with pytest.raises(SceneError, match=f"which is neither in the scene's folder .* nor allowed"):
        Scene.from_file(path)
    assert name not in sys.modules and not (elsewhere / "imported.marker").exists()
    done = cli("run", path, "--out", tmp_path / "out", "--quiet", cwd=elsewhere)  # importable from the cwd too
    assert done.returncode == 2, done.stderr
    one_line_refusal(done.stderr, f"'{name}:drag_factory'")
    assert not (elsewhere / "imported.marker").exists()
    # allowed: it runs, and gives the reference's answer (rounding of the same steps: 1e-14)
    solution = solve_scene(Scene.from_file(path, allow_import=[name]), progress=False)[0]["full"]
    assert np.abs(solution.y - reference()).max() < 1e-14
    assert (elsewhere / "called.marker").exists()


def test_a_module_shadowing_an_imported_one_is_refused(tmp_path):
    """A file json.py beside the scene does not replace the standard library's json: the import
    finds the module loaded already, which is not the scene's file."""
    (tmp_path / "json.py").write_text("def loads(t, omega):\n    return [0.0, 0.0, 0.0]\n")
    path = tmp_path / "s.toml"
    path.write_text(scene_text("json:loads", "{ }"))
    with pytest.raises(SceneError, match="already imported from .*json.*not from the scene's folder"):
        Scene.from_file(path)


def test_allow_import_must_be_module_names():
    with pytest.raises(SceneError, match="allow_import: 'os; rm' is not a module name"):
        Scene.from_dict({"body": {"moments": J}}, allow_import=["os; rm"])
    with pytest.raises(SceneError, match=r"function = 'os\.system': must be an importable name 'module:attribute'"):
        Scene.from_dict({"body": {"moments": J}, "initial": {"omega": W0},
                         "torques": [{"type": "custom", "function": "os.system"}]})


# ------------------------------------------------------------------------------------ allowed
@pytest.mark.parametrize("where", ["beside", "package"])
def test_modules_in_the_scene_folder_run(tmp_path, where):
    """A module beside the scene, or in a package below its folder: allowed without asking,
    imported from that folder (not from sys.path), and the answer is the reference's."""
    name = fresh_module_name(tmp_path)
    dotted = name if where == "beside" else f"lib_{name}.torques"
    folder = write_module(tmp_path, dotted)
    path = tmp_path / "s.toml"
    path.write_text(scene_text(f"{dotted}:drag_factory"))
    solution = solve_scene(Scene.from_file(path), progress=False)[0]["full"]
    assert np.abs(solution.y - reference()).max() < 1e-14  # the same steps: rounding only
    assert Path(sys.modules[dotted].__file__).parent == folder
    assert str(tmp_path) not in sys.path  # the folder was on the path only while importing


def test_the_command_line_runs_an_allowed_scene(tmp_path):
    name = fresh_module_name(tmp_path)
    write_module(tmp_path, name)
    path = tmp_path / "s.toml"
    path.write_text(scene_text(f"{name}:drag_factory"))
    done = cli("check", path, cwd=tmp_path)
    assert done.returncode == 0 and "ok: kind rigid_body" in done.stdout and "not imported by the check" in done.stdout
    assert not (tmp_path / "imported.marker").exists()  # check imports nothing
    done = cli("run", path, "--out", tmp_path / "out", "--quiet", cwd=tmp_path)
    assert done.returncode == 0, done.stderr
    result = np.loadtxt(tmp_path / "out" / "s" / "result.csv", delimiter=",", skiprows=1)
    # the CSV's 17 significant digits: the reference to rounding
    assert np.abs(result[:, 1:4] - reference()).max() < 1e-14
    assert (tmp_path / "called.marker").exists()


# ------------------------------------------------------------------------------------ nothing called while checking
def test_nothing_is_imported_or_called_while_a_scene_is_validated(tmp_path):
    """A scene that names allowed code but is wrong elsewhere (a key after the torque, a
    tolerance): refused, and its module never imported, its factory never called."""
    name = fresh_module_name(tmp_path)
    write_module(tmp_path, name)
    for wrong in (scene_text(f"{name}:drag_factory", extra="[oops]\nx = 1\n"),
                  scene_text(f"{name}:drag_factory").replace("rtol = 1e-12", "rtol = -1.0"),
                  scene_text(f"{name}:drag_factory").replace('model = "full"', 'model = "averaged"')):
        path = tmp_path / "s.toml"
        path.write_text(wrong)
        with pytest.raises(SceneError):
            Scene.from_file(path)
        assert name not in sys.modules and not (tmp_path / "imported.marker").exists(), wrong
    path.write_text(scene_text(f"{name}:drag_factory"))
    checked = Scene.from_file(path, check_only=True)
    assert checked.names_code and name not in sys.modules and not (tmp_path / "called.marker").exists()
    # the checked scene's stand-in refuses to run: never a silent zero torque
    with pytest.raises(RuntimeError, match="is a stand-in: the scene was only checked"):
        g.solve(checked.runs[0].model, W0, (0.0, 1.0))
    Scene.from_file(path)
    assert (tmp_path / "called.marker").exists()


def test_what_the_factory_returns_is_checked(tmp_path):
    name = fresh_module_name(tmp_path)
    write_module(tmp_path, name)
    path = tmp_path / "s.toml"
    path.write_text(scene_text(f"{name}:three", "{ c = 1.0 }"))
    with pytest.raises(TypeError, match=f"CustomTorque '{name}:three': the function must be a Python callable.*got 3"):
        Scene.from_file(path)
    done = cli("run", path, "--out", tmp_path / "out", cwd=tmp_path)
    assert done.returncode == 2 and len(done.stderr.strip().splitlines()) == 1 and "Traceback" not in done.stderr
    # a factory named without its parameters (issue 44): one line, the signature named
    path.write_text(scene_text(f"{name}:three").replace("parameters = { c = 0.05, a = 0.02 }\n", ""))
    with pytest.raises(SceneError, match=r"function = '.*:three' takes \(c\), but a torque function takes \(t, omega\)"):
        Scene.from_file(path)
    path.write_text(scene_text(f"{name}:drag_factory", "{ wrong = 1.0 }"))
    with pytest.raises(SceneError, match="the factory refused the scene's `parameters` \\(wrong\\)"):
        Scene.from_file(path)


# ------------------------------------------------------------------------------------ sweeps
def test_sweep_workers_apply_the_rule(tmp_path):
    """A sweep on two worker processes of a scene naming a module in its folder: every member
    equals its own solve; the plan that travels to a worker carries the allowance (pickled), and
    a name the allowance does not cover is refused there before it is imported."""
    name = fresh_module_name(tmp_path)
    write_module(tmp_path, name)
    path = tmp_path / "s.toml"
    path.write_text(scene_text(f"{name}:drag_factory"))
    ds = g.sweep(path, {"initial.omega[0]": [1.0, 1.2]},
                 workers=2, chunk_size=1, progress=False, trajectories=True)
    assert list(ds["status"].values.astype(str)) == ["success", "success"]
    first = np.column_stack([ds.isel({list(ds.sizes)[0]: 0})[n].values for n in ("p", "q", "r")])
    assert np.abs(first - reference()).max() < 1e-14
    plan = Plan(path, {"initial.omega[0]": [1.0, 1.2]})
    shipped = pickle.loads(pickle.dumps(plan))
    function = shipped.base["torques"][0]["function"]
    assert isinstance(function, CodeName) and function.allowance.folder == str(tmp_path.resolve())
    # the worker's check: a name its allowance does not cover is refused, nothing imported
    stray = CodeName("os:system", Allowance("s", str(tmp_path), ()), "[torques[0]] function")
    with pytest.raises(SceneError, match="names code in module 'os'"):
        pickle.loads(pickle.dumps(stray)).load()


def test_a_dask_cluster_builds_the_torque_under_the_same_rule(tmp_path):
    """Dask workers are fresh processes: each imports the scene folder's module itself, through
    the allowance the plan carries, and the members equal this process's sweep bit for bit."""
    from distributed import Client, LocalCluster

    name = fresh_module_name(tmp_path)
    write_module(tmp_path, name)
    path = tmp_path / "s.toml"
    path.write_text(scene_text(f"{name}:drag_factory"))
    vary = {"initial.omega[0]": [1.0, 1.1, 1.2]}
    here = g.sweep(path, vary, progress=False, workers=1)
    with LocalCluster(n_workers=1, threads_per_worker=1, processes=True, dashboard_address=None) as cluster:
        with Client(cluster) as client:
            remote = g.sweep(path, vary, progress=False, client=client, chunk_size=1)
    assert list(remote["status"].values.astype(str)) == ["success"] * 3
    import xarray as xr
    xr.testing.assert_identical(here.drop_attrs(), remote.drop_attrs())
