"""The type stubs of the C++ extension, generated from the built module: ``python/gyrostat/_core.pyi``.

    python docs/stubs.py            # rewrite python/gyrostat/_core.pyi
    python docs/stubs.py --check    # exit 1 when it is stale (tests/test_generated.py runs this)

pybind11-stubgen (pinned in the ``test`` extra) writes the stubs; this script adds the header
docstring and compares.
"""

from __future__ import annotations

import re
import subprocess
import sys
import tempfile
from pathlib import Path

STUB = Path(__file__).resolve().parent.parent / "python" / "gyrostat" / "_core.pyi"
HEADER = '''"""Type stubs for the C++ extension gyrostat._core: bodies, torques, models, integrators, ensembles
(the bindings only translate types). Generated from the built module by docs/stubs.py
(pybind11-stubgen); `python docs/stubs.py` regenerates it after a binding changes, and
tests/test_generated.py fails while it is stale.
"""
'''

MACHINE = ("simd_instruction_set", "simd_lanes", "taylor_kernel")


def generate() -> str:
    """The stub text of the importable gyrostat._core."""
    with tempfile.TemporaryDirectory() as out:
        subprocess.run([sys.executable, "-m", "pybind11_stubgen", "gyrostat._core", "-o", out],
                       check=True, capture_output=True, text=True)
        text = (Path(out) / "gyrostat" / "_core.pyi").read_text()
    if text.startswith('"""'):  # the module's own docstring gives way to the header
        text = text[text.index('"""', 3) + 3:].lstrip("\n")
    # what the build and the CPU decide (the SIMD set, the Taylor kernel) is typed, not valued
    text = re.sub(rf"^({'|'.join(MACHINE)}): (\w+) = .*$", r"\1: \2", text, flags=re.M)
    return HEADER + text


def main(argv: list[str]) -> int:
    text = generate()
    if "--check" in argv:
        if STUB.read_text() != text:
            print(f"{STUB} is stale: run `python docs/stubs.py`", file=sys.stderr)
            return 1
        return 0
    STUB.write_text(text)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
