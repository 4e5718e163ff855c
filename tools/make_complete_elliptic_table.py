"""Writes cpp/include/gyrostat/numeric/complete_elliptic_table.hpp: the polynomial pieces of
numeric/complete_elliptic.hpp (K(m) and ⟨sn²⟩ = (K − E)/(m K) without the AGM's serial square roots).

Run:  .venv/bin/python tools/make_complete_elliptic_table.py      (~1 s; mpmath at 60 digits)

Four functions of x ∈ [0, ½], each a polynomial of degree DEGREE in t = (x − c_i)/h on each of
INTERVALS equal pieces (centre c_i, half-width h = 1/(4 INTERVALS)):

* ``K``: K(x);
* ``S``: S(x) = (K(x) − E(x))/(x K(x)), S(0) = ½ (⟨sn²⟩ over a period);
* ``B``: B(x) = K(1 − x) − K(x) ln(16/x)/π;
* ``F``: F(x) = K(1 − x) − E(1 − x) − E(x) ln(16/x)/π.

B and F are the analytic parts of K and K − E next to m = 1 (DLMF 19.12.1, 19.12.2: the
logarithmic term's coefficient of K(1 − x) is K(x)/π, of E(1 − x) it is (K(x) − E(x))/π, so that of
K − E is E(x)/π; B(0) = 0, F(0) = −1); both are power series in x of radius 1.

Each piece interpolates its function at DEGREE + 1 Chebyshev nodes (computed at 60 digits), turned
into the monomial coefficients in t and rounded once to double. The degree is the least for which
every piece of every function is within 1e-17 of the function (relative for K and S, absolute for B
and F, whose sizes are ~1) before that rounding: checked below on 41 points per piece, which also
prints the largest error after it.
"""

from __future__ import annotations

from pathlib import Path

import mpmath as mp

INTERVALS = 8
DEGREE = 10
OUT = Path(__file__).resolve().parents[1] / "cpp/include/gyrostat/numeric/complete_elliptic_table.hpp"

mp.mp.dps = 60


def _log16(x):
    return mp.log(16 / x)


FUNCTIONS = {
    "K": lambda x: mp.ellipk(x),
    "S": lambda x: (mp.ellipk(x) - mp.ellipe(x)) / (x * mp.ellipk(x)) if x != 0 else mp.mpf(1) / 2,
    "B": lambda x: mp.ellipk(1 - x) - mp.ellipk(x) / mp.pi * _log16(x),
    "F": lambda x: mp.ellipk(1 - x) - mp.ellipe(1 - x) - mp.ellipe(x) / mp.pi * _log16(x),
}
RELATIVE = {"K": True, "S": True, "B": False, "F": False}


def piece(f, i: int) -> list:
    """The monomial coefficients in t of f's interpolant at Chebyshev nodes on piece i (mpmath)."""
    a, b = mp.mpf(i) / (2 * INTERVALS), mp.mpf(i + 1) / (2 * INTERVALS)
    c, h = (a + b) / 2, (b - a) / 2
    nodes = [mp.cos(mp.pi * (j + mp.mpf(1) / 2) / (DEGREE + 1)) for j in range(DEGREE + 1)]
    vandermonde = mp.matrix([[t**k for k in range(DEGREE + 1)] for t in nodes])
    coefficients = mp.lu_solve(vandermonde, mp.matrix([f(c + h * t) for t in nodes]))
    return [coefficients[k] for k in range(DEGREE + 1)]


def horner(coefficients, t):
    value = coefficients[-1]
    for c in reversed(coefficients[:-1]):
        value = value * t + c
    return value


def table_text(verbose: bool = False) -> str:
    """The header's text (each function's largest errors printed with ``verbose``)."""
    tables, worst = {}, {}
    for name, f in FUNCTIONS.items():
        tables[name], worst[name] = [], (0.0, 0.0)
        for i in range(INTERVALS):
            exact_coefficients = piece(f, i)
            rounded = [float(c) for c in exact_coefficients]
            tables[name].append(rounded)
            a, h = mp.mpf(i) / (2 * INTERVALS), mp.mpf(1) / (4 * INTERVALS)
            for j in range(41):
                t = -1 + 2 * mp.mpf(j) / 40
                x = a + h * (t + 1)
                exact = f(x) if x != 0 else f(mp.mpf("1e-40"))
                scale = abs(exact) if RELATIVE[name] else 1
                truncation = abs(horner(exact_coefficients, t) - exact) / scale
                after = abs(horner([mp.mpf(c) for c in rounded], t) - exact) / scale
                worst[name] = (max(worst[name][0], float(truncation)), max(worst[name][1], float(after)))
        if verbose:
            print(f"{name}: largest error {worst[name][0]:.2e} (interpolation), {worst[name][1]:.2e} (coefficients rounded)")
        assert worst[name][0] < 1e-17, name
    lines = [
        "// Written by tools/make_complete_elliptic_table.py (mpmath at 60 digits); do not edit by hand.",
        "// The pieces of numeric/complete_elliptic.hpp: on each of `intervals` equal pieces of x in [0, 1/2],",
        "// centre c_i = (i + 1/2)/(2 intervals), each function is sum_k coefficient[k] t^k, t = (x - c_i)/h,",
        "// h = 1/(4 intervals), interpolated at Chebyshev nodes. Largest error over each function's pieces:",
    ]
    for name in FUNCTIONS:
        kind = "relative" if RELATIVE[name] else "absolute"
        lines.append(f"//   {name}: {worst[name][0]:.1e} interpolation, {worst[name][1]:.1e} with the coefficients rounded ({kind}).")
    lines += ["#pragma once", "", "namespace gyrostat::model::complete_elliptic_table {", "",
              f"constexpr int intervals = {INTERVALS};", f"constexpr int degree = {DEGREE};", ""]
    comments = {"K": "K(x)", "S": "(K(x) - E(x)) / (x K(x))", "B": "K(1 - x) - K(x) ln(16/x) / pi",
                "F": "K(1 - x) - E(1 - x) - E(x) ln(16/x) / pi"}
    for name in FUNCTIONS:
        lines.append(f"/// {comments[name]}")
        lines.append(f"constexpr double {name}[intervals][degree + 1] = {{")
        for row in tables[name]:
            lines.append("    {" + ", ".join(repr(c) for c in row) + "},")
        lines.append("};")
    lines += ["", "}  // namespace gyrostat::model::complete_elliptic_table", ""]
    return "\n".join(lines)


def main() -> None:
    OUT.write_text(table_text(verbose=True))
    print(f"wrote {OUT}")


if __name__ == "__main__":
    main()
