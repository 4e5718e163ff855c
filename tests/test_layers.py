"""The Python package's floors, read from its source (ast): every import of every module, those
inside functions included, must point to the module's own floor or below; the import graph has
no cycle; the generic layers name no family module and no kind; the old module names that
re-export a family (``gyrostat.lagrange``, ...) hold no logic.

Floors, bottom up (FLOORS): the core (engine → schema → results → models → runs → kinds), the
families, the re-exports, the generic layers (scenes → output and plots → sweeps → runner) and
the command line. A new module must be placed in FLOORS (an unplaced module fails the test). A
family module uses another family only through its public names (no module inside another
family's package, no private name).

How the checks were seen to fail: ``test_planted_violations_are_caught`` plants each kind of
violation in a copy of the sources (an upward import closing a cycle, as ``validity.check_scene
→ scene.Scene`` once did; a generic module importing a family module; a kind's name in a
generic module; logic in a re-export module; the climbs inside functions ``plots → sweeps`` and
``solution → modelbase`` that once were there; a family importing another's private model) and
asserts that each is reported. By hand, adding
``from gyrostat.scene import Scene`` inside a function of ``gyrostat/assumptions.py``, or
``if scene.kind.name == "lagrange_top": pass`` to ``gyrostat/runner.py``, made
``test_floors_and_cycles`` / ``test_generic_layers_name_no_family`` fail with the module, the
line and the name.
"""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

PACKAGE = Path(__file__).resolve().parents[1] / "python" / "gyrostat"

FLOORS = (  # bottom up: a module imports (anywhere in it, functions included) its own floor or below
    ("engine", ("gyrostat._core", "gyrostat.arguments", "gyrostat.progress", "gyrostat.events", "gyrostat.attitude",
                "gyrostat.assumptions", "gyrostat.options")),
    ("schema", ("gyrostat.schema", "gyrostat.schema.messages", "gyrostat.schema.fields", "gyrostat.schema.checks",
                "gyrostat.schema.reference", "gyrostat.scene_code")),
    ("results", ("gyrostat.solution", "gyrostat.solution_views", "gyrostat.solution_join", "gyrostat.estimate",
                 "gyrostat.accuracy", "gyrostat.contract")),
    ("models", ("gyrostat.torques", "gyrostat.modelbase")),
    ("runs", ("gyrostat.solve", "gyrostat.answer", "gyrostat.ensemble", "gyrostat.ladder", "gyrostat.ladder.rungs",
              "gyrostat.ladder.probe", "gyrostat.ladder.choosing", "gyrostat.ladder.switching", "gyrostat.figures",
              "gyrostat.sensitivity")),
    ("kinds", ("gyrostat.kind",)),
    ("families", ("gyrostat.families",)),  # and every module under gyrostat/families/
    ("re-exports", ("gyrostat.model", "gyrostat.averaged", "gyrostat.lagrange", "gyrostat.orthogonal")),
    ("scenes", ("gyrostat.scene", "gyrostat.validity")),
    ("output and plots", ("gyrostat.output", "gyrostat.plots")),
    ("sweeps", ("gyrostat.sweeps", "gyrostat.sweeps.draws", "gyrostat.sweeps.parameters", "gyrostat.sweeps.plan",
                "gyrostat.sweeps.chunks", "gyrostat.sweeps.storage", "gyrostat.sweeps.runners",
                "gyrostat.sweeps.summaries")),
    ("runner", ("gyrostat.runner",)),
    ("command line", ("gyrostat", "gyrostat.__main__", "gyrostat.cli")),
)
FLOOR_NAMES = tuple(name for name, _ in FLOORS)
CORE = tuple(m for _, members in FLOORS[:FLOOR_NAMES.index("families")] for m in members)
REEXPORTS = dict(FLOORS)["re-exports"]
GENERIC = tuple(m for _, members in FLOORS[FLOOR_NAMES.index("scenes"):FLOOR_NAMES.index("command line")]
                for m in members)


def floor(module: str) -> int:
    if module.startswith("gyrostat.families."):
        return FLOOR_NAMES.index("families")
    for index, (_, members) in enumerate(FLOORS):
        if module in members:
            return index
    raise AssertionError(f"{module} is in no floor: add it to FLOORS in tests/test_layers.py")


def family_of(module: str) -> str | None:
    """``gyrostat.families.lagrange_top.models`` → ``lagrange_top`` (None outside a family)."""
    parts = module.split(".")
    return parts[2] if len(parts) > 2 and parts[:2] == ["gyrostat", "families"] else None


def sources() -> dict[str, str]:
    """Module name → source of every module of the package."""
    found = {}
    for path in sorted(PACKAGE.rglob("*.py")):
        parts = path.relative_to(PACKAGE.parent).with_suffix("").parts
        name = ".".join(parts[:-1] if parts[-1] == "__init__" else parts)
        found[name] = path.read_text()
    return found


def imports(name: str, source: str, known: set[str]) -> list[tuple[int, str]]:
    """(line, module) of every gyrostat module that ``source`` imports, anywhere in it."""
    package = name if name == "gyrostat" or name == "gyrostat.families" else name.rsplit(".", 1)[0]
    found = []
    for node in ast.walk(ast.parse(source)):
        if isinstance(node, ast.Import):
            found += [(node.lineno, a.name) for a in node.names if a.name.split(".")[0] == "gyrostat"]
        elif isinstance(node, ast.ImportFrom):
            base = node.module or ""
            if node.level:
                base = ".".join(package.split(".")[: len(package.split(".")) - node.level + 1] + ([base] if base else []))
            if base.split(".")[0] != "gyrostat":
                continue
            for alias in node.names:  # `from gyrostat import ladder` imports the module gyrostat.ladder
                sub = f"{base}.{alias.name}"
                found.append((node.lineno, sub if sub in known else base))
    return [(line, module) for line, module in found if module != name]


def docstrings(tree: ast.AST) -> set[int]:
    """ids of the docstring constants of a module, its classes and functions."""
    ids = set()
    for node in ast.walk(tree):
        if isinstance(node, (ast.Module, ast.ClassDef, ast.FunctionDef, ast.AsyncFunctionDef)) and node.body:
            first = node.body[0]
            if isinstance(first, ast.Expr) and isinstance(first.value, ast.Constant):
                ids.add(id(first.value))
        if isinstance(node, (ast.Module, ast.ClassDef)):  # attribute docstrings: a string after an assignment
            for before, after in zip(node.body, node.body[1:]):
                if isinstance(before, (ast.Assign, ast.AnnAssign)) and isinstance(after, ast.Expr) \
                        and isinstance(after.value, ast.Constant):
                    ids.add(id(after.value))
    return ids


def violations(modules: dict[str, str], kinds: set[str]) -> dict[str, list[str]]:
    """Every broken rule, by rule: floors, cycles, generic (names a family), reexports (logic)."""
    known = set(modules) | {"gyrostat._core"}
    graph = {name: imports(name, source, known) for name, source in modules.items()}
    found: dict[str, list[str]] = {"floors": [], "cycles": [], "generic": [], "reexports": [], "families": []}
    for name, edges in graph.items():
        for line, target in edges:
            if floor(target) > floor(name):
                found["floors"].append(f"{name}:{line} ({FLOOR_NAMES[floor(name)]}) imports {target} "
                                       f"({FLOOR_NAMES[floor(target)]})")
    # cycles: depth-first search over module → imported modules
    state: dict[str, int] = {}

    def visit(node: str, path: list[str]) -> None:
        state[node] = 1
        for _, target in graph.get(node, []):
            if state.get(target) == 1:
                found["cycles"].append(" → ".join(path[path.index(target):] + [target]))
            elif target not in state:
                visit(target, path + [target])
        state[node] = 2

    for name in sorted(graph):
        if name not in state:
            visit(name, [name])
    for name, source in modules.items():  # a family uses another only through its public names
        if family_of(name) is None:
            continue
        for node in ast.walk(ast.parse(source)):
            if not isinstance(node, ast.ImportFrom) or family_of(node.module or "") in (None, family_of(name)):
                continue
            inside = len(node.module.split(".")) > 3  # a module inside another family's package
            private = [a.name for a in node.names if a.name.startswith("_")]
            if inside or private:
                found["families"].append(f"{name}:{node.lineno} imports the internals of another family: "
                                         f"{node.module} {', '.join(private)}".rstrip())
    for name in GENERIC:
        if name not in modules:
            continue
        for line, target in graph[name]:
            if target.startswith("gyrostat.families.") or target in REEXPORTS:
                found["generic"].append(f"{name}:{line} imports the family module {target}")
        tree = ast.parse(modules[name])
        skip = docstrings(tree)
        for node in ast.walk(tree):
            if isinstance(node, ast.Constant) and isinstance(node.value, str) and id(node) not in skip \
                    and node.value in kinds:
                found["generic"].append(f"{name}:{node.lineno} names the kind {node.value!r}")
    for name in REEXPORTS:
        if name not in modules:
            continue
        body = ast.parse(modules[name]).body
        for i, node in enumerate(body):
            docstring = i == 0 and isinstance(node, ast.Expr) and isinstance(node.value, ast.Constant)
            dunder_all = isinstance(node, ast.Assign) and [getattr(t, "id", "") for t in node.targets] == ["__all__"]
            if not (docstring or dunder_all or isinstance(node, ast.ImportFrom)):
                found["reexports"].append(f"{name}:{node.lineno} holds {type(node).__name__}, not a re-export")
    return found


@pytest.fixture(scope="module")
def kinds() -> set[str]:
    from gyrostat.families import KINDS

    return set(KINDS)


def test_floors_and_cycles(kinds):
    found = violations(sources(), kinds)
    assert not found["floors"], "\n".join(found["floors"])
    assert not found["cycles"], "\n".join(found["cycles"])


def test_generic_layers_name_no_family(kinds):
    found = violations(sources(), kinds)
    assert not found["generic"], "\n".join(found["generic"])


def test_reexport_modules_hold_no_logic(kinds):
    found = violations(sources(), kinds)
    assert not found["reexports"], "\n".join(found["reexports"])


def test_no_family_imports_another_familys_internals(kinds):
    found = violations(sources(), kinds)
    assert not found["families"], "\n".join(found["families"])


def test_every_family_module_registers_a_kind(kinds):
    """A module under families/ is a family: it registers at least one scene kind, and says what a
    family module provides in its docstring (the recipe)."""
    from gyrostat.families import KINDS

    modules = {kind.__class__.__module__ for kind in KINDS.values()}
    families = [path for path in sorted((PACKAGE / "families").iterdir())
                if (path.suffix == ".py" and path.stem != "__init__") or (path / "__init__.py").is_file()]
    assert len(families) >= 4, families
    for path in families:  # a module, or a package (its modules: models, scene kind, analyses, plots)
        name = f"gyrostat.families.{path.stem}"
        assert any(m == name or m.startswith(name + ".") for m in modules), path.stem
        source = (path / "__init__.py" if path.is_dir() else path).read_text()
        assert "A family module provides" in ast.get_docstring(ast.parse(source)), path.stem


def test_planted_violations_are_caught(kinds):
    """Each rule fails on a violation planted in a copy of the sources."""
    clean = sources()
    planted = dict(clean)
    planted["gyrostat.assumptions"] += "\n\ndef _planted():\n    from gyrostat.scene import Scene\n"
    planted["gyrostat.runner"] += "\n\nfrom gyrostat.families import rigid_body\n\nif 'lagrange_top':\n    pass\n"
    planted["gyrostat.lagrange"] += "\n\nSEPARATRIX = 2 * 1e-3\n"
    # the climbs inside functions the finer floors catch (each was once written so)
    planted["gyrostat.plots"] += "\n\ndef _planted():\n    from gyrostat.sweeps import summary\n"
    planted["gyrostat.solution"] += "\n\ndef _planted():\n    from gyrostat.modelbase import floats\n"
    planted["gyrostat.sweeps.storage"] += "\n\ndef _planted():\n    from gyrostat import runner\n"
    planted["gyrostat.families.moving_mass"] += "\n\nfrom gyrostat.families.lagrange_top.models import _TopModel\n"
    found = violations(planted, kinds)
    for low, high in (("gyrostat.plots", "gyrostat.sweeps"), ("gyrostat.solution", "gyrostat.modelbase"),
                      ("gyrostat.sweeps.storage", "gyrostat.runner")):
        assert any(v.startswith(low + ":") and f"imports {high} " in v for v in found["floors"]), (low, found["floors"])
    assert any("gyrostat.families.moving_mass" in v and "_TopModel" in v for v in found["families"]), found["families"]
    assert any("gyrostat.assumptions" in v and "gyrostat.scene" in v for v in found["floors"]), found["floors"]
    assert any("gyrostat.assumptions" in v and "gyrostat.scene" in v for v in found["cycles"]), found["cycles"]
    assert any("rigid_body" in v for v in found["generic"]) and any("'lagrange_top'" in v for v in found["generic"])
    assert any("gyrostat.lagrange" in v for v in found["reexports"]), found["reexports"]
    assert not any(violations(clean, kinds).values())


# ------------------------------------------------------------------------------------ C++ headers
CPP_INCLUDE = Path(__file__).resolve().parents[1] / "cpp" / "include"


def header_graph() -> dict[str, set[str]]:
    """Header → the gyrostat headers it includes (``#include "gyrostat/..."``), for every header."""
    import re

    pattern = re.compile(r'^\s*#\s*include\s*"(gyrostat/[^"]+)"', re.M)
    return {path.relative_to(CPP_INCLUDE).as_posix(): set(pattern.findall(path.read_text()))
            for path in sorted(CPP_INCLUDE.rglob("*.hpp"))}


def reached(graph: dict[str, set[str]], start: str) -> set[str]:
    seen, todo = set(), [start]
    while todo:
        for header in graph.get(todo.pop(), ()):
            if header not in seen:
                seen.add(header)
                todo.append(header)
    return seen


def test_integrators_include_neither_the_engine_nor_a_cycle():
    """The integrators (integrate/) know no model family: no header of theirs reaches the engine
    (engine.hpp, which lists every model) or solve_system.hpp, even through others; and no header
    reaches itself (a cycle that #pragma once would hide). Seen to fail: integrate/solve.hpp once
    ended by including solve_system.hpp → engine.hpp → every model (the integrators' layer pulled
    in every model and sat in a cycle with the engine)."""
    graph = header_graph()
    assert "gyrostat/integrate/solve.hpp" in graph and "gyrostat/engine.hpp" in graph, sorted(graph)[:5]
    for header in graph:
        if header.startswith("gyrostat/integrate/"):
            climbs = reached(graph, header) & {"gyrostat/engine.hpp", "gyrostat/solve_system.hpp"}
            assert not climbs, f"{header} reaches {sorted(climbs)}"
        assert header not in reached(graph, header), f"{header} includes itself through others"


def test_the_header_check_sees_a_planted_cycle():
    graph = header_graph()
    graph["gyrostat/integrate/solve.hpp"] = graph["gyrostat/integrate/solve.hpp"] | {"gyrostat/solve_system.hpp"}
    assert "gyrostat/engine.hpp" in reached(graph, "gyrostat/integrate/solve.hpp")
    assert "gyrostat/integrate/solve.hpp" in reached(graph, "gyrostat/integrate/solve.hpp")


def test_importing_the_package_leaves_matplotlib_until_it_draws():
    """`import gyrostat` (the command line, every sweep worker) does not import matplotlib (~0.3 s
    of ~0.45 s, measured with -X importtime) nor set the user's backend; the first drawing does
    (gyrostat.figures.plt), on Agg."""
    import subprocess
    import sys

    code = ("import sys, gyrostat; before = 'matplotlib' in sys.modules; "
            "from gyrostat import figures; figures.plt.figure(); import matplotlib; "
            "print(before, matplotlib.get_backend().lower())")
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                          env={k: v for k, v in __import__("os").environ.items() if k != "MPLBACKEND"})
    assert done.returncode == 0, done.stderr
    assert done.stdout.split() == ["False", "agg"], done.stdout
