"""Build-time pages of the documentation site, generated from the shipped scenes.

:func:`generate` runs every shipped scene once (``gyrostat examples``), copies its plots, and
writes ``gallery.md`` (every scene with its plots) and one page per paper of ``docs/papers/``
(the paper's record followed by the figures of its scenes, the scenes whose name starts with
``p<number>_``). Everything goes to ``docs/_generated/`` (not in git).
"""

from __future__ import annotations

import os
import re
import shutil
import subprocess
import sys
import tomllib
from pathlib import Path

HERE = Path(__file__).resolve().parent
SCENES = HERE.parent / "python" / "gyrostat" / "scenes"


def paper_numbers(record: Path) -> list[str]:
    """``000_002_cavity_and_medium.md`` -> ``["000", "002"]``: the papers a record covers."""
    return re.findall(r"(?:^|_)(\d{3})(?=_)", record.stem)


def run_command(scene: Path) -> str:
    """The command that runs a shipped scene from the root of a clone (after ``bash run.sh main``
    or ``pip install .``): the scene's path in the repository; its results go to results/<scene>/."""
    return f"gyrostat run {scene.relative_to(HERE.parent).as_posix()} --out results   # results in results/{scene.stem}/"


def scene_pages(scene: Path, plots: Path, heading: str) -> list[str]:
    """Markdown of one scene: its title, description, how to run it, and its plots."""
    spec = tomllib.loads(scene.read_text())
    lines = [f"{heading} {scene.stem}", "", f"**{spec.get('title', scene.stem)}**", ""]
    if spec.get("description"):
        lines += [" ".join(spec["description"].split()), ""]
    lines += ["```bash", run_command(scene), "```", ""]
    for png in sorted((plots / scene.stem).glob("*.png")):
        plot = png.stem.removeprefix(f"{scene.stem}_")
        lines += [f"![{scene.stem}: {plot}](gallery/{scene.stem}/{png.name})", ""]
    return lines


def run_scenes(out: Path) -> None:
    """Every shipped scene's results and plots in out/<scene>/ (fails loudly if one fails). With
    ``GYROSTAT_GALLERY_FROM`` naming the folder of a finished ``gyrostat examples`` run of this
    library (the test suite's, tests/conftest.py), that run's files are copied instead: the main
    job is not run twice."""
    done = os.environ.get("GYROSTAT_GALLERY_FROM")
    if done:
        shutil.copytree(done, out)
        return
    run = subprocess.run([sys.executable, "-m", "gyrostat", "examples", "--out", str(out), "--quiet", "--overwrite"],
                         capture_output=True, text=True)
    if run.returncode != 0:
        raise RuntimeError(f"gyrostat examples failed (exit {run.returncode}):\n{run.stdout}\n{run.stderr}")


def generate(out: Path) -> None:
    shutil.rmtree(out, ignore_errors=True)
    plots = out / "gallery"
    run_scenes(plots)
    for scene_dir in plots.iterdir():  # keep the plots only, named after their scene (Sphinx copies
        if not scene_dir.is_dir():       # every image into one folder); the run's index is not needed
            scene_dir.unlink()
            continue
        for f in scene_dir.iterdir():
            if f.suffix == ".png":
                f.rename(scene_dir / f"{scene_dir.name}_{f.name}")
            else:
                f.unlink()
    scenes = sorted(SCENES.glob("*.toml"))
    gallery = ["# Gallery: every shipped scene", "",
               "Generated when the site is built: each shipped scene (`gyrostat examples`) run with the",
               "installed library, and its plots. Each scene's command runs from the root of a clone once the",
               "package is installed (`bash run.sh main` installs it into `.venv`: `source .venv/bin/activate`).", ""]
    for scene in scenes:
        gallery += scene_pages(scene, plots, "##")
    (out / "gallery.md").write_text("\n".join(gallery))

    for record in sorted((HERE / "papers").glob("[0-9]*.md")):
        numbers = paper_numbers(record)
        page = ["```{include} ../papers/" + record.name, ":relative-images:", ":relative-docs: ../papers/", "```", "",
                "## Figures reproduced by the library", "",
                "Each scene of the paper, run by the library when this site was built.", ""]
        for scene in scenes:
            if any(scene.stem.startswith(f"p{n}_") for n in numbers):
                page += scene_pages(scene, plots, "###")
        (out / f"paper_{record.stem}.md").write_text("\n".join(page))
