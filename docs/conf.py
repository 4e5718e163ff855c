"""Sphinx configuration of gyrostat's documentation site (``bash run.sh docs`` builds it).

The Markdown pages (architecture, integrators, scenes, papers) are read by MyST; the Python API
comes from the docstrings (autodoc + napoleon, NumPy style); the gallery is generated at build
time by running every shipped scene (``gallery.py``), the C++ API page from the headers
(``cpp_reference.py``).
"""

import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))

import cpp_reference  # noqa: E402  (docs/cpp_reference.py, beside this file)
import gallery  # noqa: E402  (docs/gallery.py)

project = "gyrostat"
author = "gyrostat developers"
extensions = ["myst_parser", "sphinx.ext.autodoc", "sphinx.ext.napoleon", "sphinx.ext.mathjax"]
source_suffix = {".rst": "restructuredtext", ".md": "markdown"}
exclude_patterns = ["_build", "papers"]  # the papers' records are included by _generated/paper_*.md
myst_heading_anchors = 3
myst_enable_extensions = ["dollarmath"]
autodoc_member_order = "bysource"
autodoc_typehints = "description"
napoleon_numpy_docstring = True
napoleon_google_docstring = False
html_theme = "alabaster"
html_title = "gyrostat"


def plain_bars(app, what, name, obj, options, lines):
    """The docstrings write norms as |G| (plain text, not reST substitutions): escape the bars."""
    lines[:] = [line.replace("|", r"\|") for line in lines]


def registries(folder: Path) -> None:
    """The reference entries of what registers itself: every torque class of the core (from its
    C++ declaration) and every family module (gyrostat/families/), so that adding either needs
    no edit here."""
    import pkgutil

    import gyrostat
    import gyrostat.families

    folder.mkdir(parents=True, exist_ok=True)
    torques = "".join(f".. autoclass:: gyrostat.{cls.__name__}\n   :members:\n   :special-members: __call__\n\n"
                      for cls in gyrostat._core.torque_types)
    (folder / "torques.inc").write_text(torques)
    families = "".join(f".. automodule:: gyrostat.families.{m.name}\n   :members:\n   :no-index:\n\n"
                       for m in pkgutil.iter_modules(gyrostat.families.__path__))
    (folder / "families.inc").write_text(families)


def setup(app):
    app.connect("autodoc-process-docstring", plain_bars)
    def generate(app):
        gallery.generate(HERE / "_generated")
        cpp_reference.generate(HERE / "_generated")
        registries(HERE / "_generated")

    app.connect("builder-inited", generate)
