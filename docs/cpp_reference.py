"""The C++ API page, generated at build time from the core headers' own documentation.

Each header of ``cpp/include/gyrostat/`` gives its opening ``//`` comment (what the header is) and
every ``///`` comment block with the declaration that follows it, so the page cannot drift from
the headers. Headers of implementation detail are listed by name only.
"""

from __future__ import annotations

from pathlib import Path

INCLUDE = Path(__file__).resolve().parent.parent / "cpp" / "include"
DETAIL = {"solve_system.hpp", "dop853_tableau.hpp", "sundials.hpp", "sundials_driver.hpp"}
SECTIONS = [("", "Engine, bodies, ensembles, attitude"), ("model", "Models"), ("torque", "Torques"),
            ("integrate", "Integrators"),
            ("numeric", "Numeric tools (double-double, dual numbers, SIMD lanes, elliptic integrals, tableaux)")]


def header_entries(text: str) -> tuple[str, list[tuple[str, str]]]:
    """(the opening comment, [(doc comment, declaration)]) of one header."""
    lines = text.splitlines()
    opening = []
    for line in lines:
        if not line.startswith("//") or line.startswith("///"):
            break
        opening.append(line[2:].strip())
    entries, doc = [], []
    for line in lines:
        stripped = line.strip()
        if stripped.startswith("///"):
            doc.append(stripped[3:].strip())
        elif doc:
            if stripped:
                entries.append((" ".join(doc), stripped.rstrip("{").rstrip()))
            doc = []
    return " ".join(opening), entries


def generate(out: Path) -> None:
    page = ["# C++ API (core headers)", "",
            "The C++ core is the library `gyrostat::core` (see {doc}`../install` for `find_package`).",
            "This page is generated from the headers in `cpp/include/gyrostat/`: each header's summary,",
            "then each documented declaration with its comment. Everything is in namespace `gyrostat`",
            "(models in `gyrostat::model`, torques in `gyrostat::torque`, integrators in",
            "`gyrostat::integrate`).", ""]
    for folder, title in SECTIONS:
        page += [f"## {title}", ""]
        for header in sorted((INCLUDE / "gyrostat" / folder).glob("*.hpp")):
            name = header.relative_to(INCLUDE).as_posix()
            summary, entries = header_entries(header.read_text())
            page += [f"### `{name}`", "", summary, ""]
            if header.name in DETAIL:
                page += ["(implementation detail, included by the headers above)", ""]
                continue
            for doc, declaration in entries:
                page += ["```cpp", declaration, "```", "", doc, ""]
    out.mkdir(parents=True, exist_ok=True)
    (out / "cpp_api.md").write_text("\n".join(page))
