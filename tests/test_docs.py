"""The documentation site builds with warnings as errors (a broken reference fails), holds every
page it promises, documents every public name with its parameters, shows every shipped scene in
its gallery, describes what the scene kinds share once, and speaks to users, not to the project's
bookkeeping. The tutorial's code and numbers are checked by test_tutorial.py."""

import os
import re
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
DOCS = ROOT / "docs"


@pytest.fixture(scope="module")
def site(tmp_path_factory, examples):
    html = tmp_path_factory.mktemp("html")
    assert examples.code == 0, examples.out
    # the gallery's plots from the session's run of the shipped scenes (docs/gallery.py): not a second run
    environment = {**os.environ, "GYROSTAT_GALLERY_FROM": str(examples.folder)}
    run = subprocess.run([sys.executable, "-m", "sphinx", "-W", "--keep-going", "-q", "-b", "html", str(DOCS), str(html)],
                         capture_output=True, text=True, env=environment)
    assert run.returncode == 0, run.stderr
    return html


def test_every_page_is_built(site):
    pages = ["install", "tutorial", "coming_from", "orbit_frame", "choosing", "scenes", "python_api", "architecture", "integrators",
             "_generated/gallery", "_generated/cpp_api", "_generated/paper_000_002_cavity_and_medium",
             "_generated/paper_001_moving_mass", "_generated/paper_003_lagrange_top",
             "_generated/paper_004_orthogonal_torque"]
    for page in pages:
        assert (site / f"{page}.html").is_file(), page
    api = (site / "python_api.html").read_text()
    for name in ("gyrostat.solve.solve", "gyrostat.solve.solve_ensemble", "gyrostat.solution.Solution",
                 "gyrostat.Body", "gyrostat.model.Model",
                 "gyrostat.lagrange.LagrangeTop", "gyrostat.orthogonal.OrthogonalModel", "gyrostat.events.Event",
                 "gyrostat.solution.Solution.__call__", "gyrostat.solution.Solution.state_names",
                 "gyrostat.solution.Solution.output_names", "gyrostat.solution.Solution.event_names",
                 "gyrostat.solution.Solution.success", "gyrostat.ViscousCavity.__call__"):
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


def section(html: str, anchor: str) -> str:
    """The HTML of one documented object: from its anchor to the next one."""
    start = html.index(f'id="{anchor}"')
    end = html.find('<dt class="sig', start + 1)
    return html[start:end if end > 0 else None]


def test_the_api_page_shows_parameters_units_and_examples(site):
    api = (site / "python_api.html").read_text()
    body = section(api, "gyrostat.Body")
    assert "moments" in body and "kg m^2" in body and "Examples" in body and "rotor" in body
    cavity = section(api, "gyrostat.ViscousCavity")
    for unit in ("kg/m^3", "m^2/s", "m^5"):  # from the C++ declaration
        assert unit in cavity, unit
    call = section(api, "gyrostat.solution.Solution.__call__")
    assert "name" in call and "theta" in call
    solve = section(api, "gyrostat.solve.solve")
    paragraphs = re.findall(r"<li><p><strong>\w+</strong>.*?</p>", solve, flags=re.S)
    descriptions = [re.sub(r"<strong>\w+</strong>", "", p) for p in paragraphs]
    assert len(paragraphs) >= 15 and len(set(descriptions)) == len(descriptions), "solve() repeats a description"


def test_scene_reference_describes_shared_tables_once():
    text = (DOCS / "scenes.md").read_text()
    for heading in ("### [[events]]", "### [sweep]", "### [[torques]]", "### Keys of [integration]"):
        assert text.count(heading + "\n") == 1, heading
    kinds = re.findall(r'^## kind = "(\w+)"$', text, flags=re.M)
    assert len(kinds) >= 5
    assert len(re.findall(r"And the shared keys `kind`, `title`, `description`, (`\w+`, )*`events`, `sweep`", text)) == len(kinds)
    assert len(text.splitlines()) < 600


def test_no_bookkeeping_words_in_docs():
    pages = [*DOCS.glob("*.md"), *DOCS.glob("*.rst"), *(DOCS / "papers").glob("*.md"), ROOT / "bench" / "README.md",
             ROOT / "README.md"]
    for page in pages:
        if page.name == "README.md" and page.parent.name == "papers":
            continue  # the papers' index, kept by its own owners
        found = re.findall(r"\b(?:issue|PR|pull request)s? #?\d+|\bthe issue\b", page.read_text(), flags=re.I)
        assert not found, (page.name, found)


def test_coming_from_maps_the_other_libraries_calls():
    text = (DOCS / "coming_from.md").read_text()
    for name in ("solve_ivp", "dense_output", "t_eval", "taylor_adaptive", "propagate_until", "propagate_grid",
                 "taylor_adaptive_batch", "ensemble_propagate_until", "ExtForceTorque", "IHubPntBc_B", "recorder",
                 "Monte"):
        assert name in text, name
    for call in ("gyrostat.solve(", "gyrostat.solve_ensemble(", "gyrostat.sweep(", "sol(t"):
        assert call in text, call
    assert "does not do" in text
