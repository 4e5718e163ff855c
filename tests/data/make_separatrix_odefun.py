"""Writes separatrix_odefun.json: ω(t) of Euler's torque-free equations by mpmath's Taylor
integrator (mp.odefun) at 30 digits, for the cases of tests/test_separatrix.py's ODEFUN_CASES
(~25 s). The test compares its own closed-form reference with these values, and recomputes one
case live to show the stored values still are mp.odefun's.

Run:  .venv/bin/python tests/data/make_separatrix_odefun.py
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

import mpmath as mp

HERE = Path(__file__).resolve().parent
DPS = 30  # the digits test_separatrix.odefun_omega works at


def main() -> int:
    sys.path.insert(0, str(HERE.parent))
    from test_separatrix import ODEFUN_CASES, odefun_omega

    with mp.workdps(DPS + 5):
        table = _table(ODEFUN_CASES, odefun_omega)
    (HERE / "separatrix_odefun.json").write_text(json.dumps(table, indent=1) + "\n")
    return 0


def _table(cases, odefun_omega) -> list[dict]:
    """Each case's moments, ω0, times and ω(t) (decimal strings of DPS + 2 digits)."""
    return [{"moments": [float(x) for x in moments], "omega0": [float(x) for x in omega0], "times": list(times),
             "omega": [[mp.nstr(x, DPS + 2) for x in row] for row in odefun_omega(moments, omega0, times)]}
            for moments, omega0, times in cases]


if __name__ == "__main__":
    sys.exit(main())
