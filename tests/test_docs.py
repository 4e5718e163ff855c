"""The documentation site builds with warnings as errors (a broken reference fails), holds every
page the issue asks for, shows every shipped scene in its gallery, and its tutorial runs."""

import re
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
DOCS = ROOT / "docs"


@pytest.fixture(scope="module")
def site(tmp_path_factory):
    html = tmp_path_factory.mktemp("html")
    run = subprocess.run([sys.executable, "-m", "sphinx", "-W", "--keep-going", "-q", "-b", "html", str(DOCS), str(html)],
                         capture_output=True, text=True)
    assert run.returncode == 0, run.stderr
    return html


def test_every_page_is_built(site):
    pages = ["install", "tutorial", "choosing", "scenes", "python_api", "architecture", "integrators",
             "_generated/gallery", "_generated/cpp_api", "_generated/paper_000_002_cavity_and_medium",
             "_generated/paper_001_moving_mass", "_generated/paper_003_lagrange_top",
             "_generated/paper_004_orthogonal_torque"]
    for page in pages:
        assert (site / f"{page}.html").is_file(), page
    api = (site / "python_api.html").read_text()
    for name in ("gyrostat.solve.solve", "gyrostat.solve.solve_ensemble", "gyrostat.solution.Solution",
                 "gyrostat.Body", "gyrostat.model.Model",
                 "gyrostat.lagrange.LagrangeTop", "gyrostat.orthogonal.OrthogonalModel", "gyrostat.events.Event"):
        assert f'id="{name}"' in api, name
    cpp = (site / "_generated" / "cpp_api.html").read_text()
    for header in ("gyrostat/engine.hpp", "gyrostat/ensemble.hpp", "gyrostat/integrate/options.hpp",
                   "gyrostat/model/gyrostat.hpp", "gyrostat/torque/constant.hpp"):
        assert header in cpp, header


def test_gallery_shows_every_shipped_scene_and_papers_their_figures(site):
    gallery = (site / "_generated" / "gallery.html").read_text()
    for scene in sorted((ROOT / "python" / "gyrostat" / "scenes").glob("*.toml")):
        images = re.findall(rf'<img alt="{re.escape(scene.stem)}: [^"]*" src="\.\./(_images/[^"]*)"', gallery)
        assert images, scene.stem
        assert all((site / image).stat().st_size > 10_000 for image in images)
    assert len(set(re.findall(r'src="(\.\./_images/[^"]*)"', gallery))) == gallery.count("<img")  # no clashes
    paper = (site / "_generated" / "paper_000_002_cavity_and_medium.html").read_text()
    assert "p002_paper_scene: phase" in paper and "p000_A8_C4_M3-0p1: xy" in paper


def test_work_precision_charts_are_shipped_and_shown(site):
    choosing = (site / "choosing.html").read_text()
    readme = (ROOT / "bench" / "README.md").read_text()
    for problem in ("torque_free", "forced", "stiff", "moving_mass"):
        chart = ROOT / "bench" / "results" / f"work_precision_{problem}.png"
        assert chart.is_file() and chart.stat().st_size > 10_000, chart
        assert f"results/work_precision_{problem}.png" in readme
        assert f"work_precision_{problem}.png" in choosing
    tracked = subprocess.run(["git", "check-ignore", "bench/results/work_precision_forced.png"], cwd=ROOT,
                             capture_output=True, text=True)
    assert tracked.returncode == 1, "bench/results/ must not be ignored by git"


def test_tutorial_runs_as_written(tmp_path, monkeypatch):
    blocks = re.findall(r"```python\n(.*?)```", (DOCS / "tutorial.md").read_text(), flags=re.S)
    assert len(blocks) >= 5
    monkeypatch.chdir(tmp_path)
    namespace = {"__name__": "tutorial"}
    for index, block in enumerate(blocks):
        exec(compile(block, f"tutorial.md python block {index}", "exec"), namespace)
    assert (tmp_path / "invariants.png").stat().st_size > 10_000
    assert namespace["final_energy"].shape == (100,)
