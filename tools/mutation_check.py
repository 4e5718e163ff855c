#!/usr/bin/env python3
"""Mutation check (issue 29): do the tests catch a wrong physics equation?

For each mutation below (a flipped sign in the equations of three torques and of one averaged
contribution) this script edits the C++ header in place, rebuilds the extension in its own build
directory (build/mutation, -j1), runs the test files against that extension (a copy of the
package in build/mutation/pkg, so the worktree's own build is never touched), restores the
header in a `finally`, and prints which tests failed. A first run without any mutation (the
baseline) must pass: otherwise a failure under a mutation would prove nothing.

    /work/main/.venv/bin/python tools/mutation_check.py            # baseline + every mutation
    /work/main/.venv/bin/python tools/mutation_check.py --only top_gravity --skip-baseline

A header change recompiles twelve translation units: ~5-15 min per mutation at -j1 (more on a
loaded machine); the tests take a minute.
Exit status 1 if the baseline fails or a mutation is caught by no test.
"""

from __future__ import annotations

import argparse
import shutil
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
BUILD = ROOT / "build" / "mutation"
OUT = BUILD / "out"
PKG = BUILD / "pkg"

TORQUES = "tests/test_torques.py::"
MUTATIONS = [
    {"name": "cavity_sign",
     "what": "viscous cavity (paper 002 (1)): sign of C(A−C)(A+C−B) r² in M_p",
     "file": "cpp/include/gyrostat/torque/viscous_cavity.hpp",
     "old": "return {k * w[0] * (c[0] * r2 + c[1] * q2),",
     "new": "return {k * w[0] * (-c[0] * r2 + c[1] * q2),",
     "tests": [TORQUES + "test_cavity_torque_formula_and_invariants",
               TORQUES + "test_full_model_with_new_torques_against_scipy",
               "tests/test_splitting.py::test_order_of_splitting_with_the_cavity",
               "tests/test_splitting.py::test_splitting_keeps_G_when_the_perturbation_does",
               "tests/test_readme.py::test_readme_results_against_references"]},
    {"name": "damper_sign",
     "what": "moving-mass damper (paper 001 (2)-(3)): sign of the axial T_S",
     "file": "cpp/include/gyrostat/torque/moving_mass_damper.hpp",
     "old": "const double TS2 = kS * r * (A - B - C) * (A - B + C) * (",
     "new": "const double TS2 = -kS * r * (A - B - C) * (A - B + C) * (",
     "tests": [TORQUES + "test_damper_torque_symmetric_and_triaxial",
               TORQUES + "test_full_model_with_new_torques_against_scipy"]},
    {"name": "top_gravity",
     "what": "Lagrange top (paper 003 (1.1)): sign of gravity's moment −μγ1 in the q equation",
     "file": "cpp/include/gyrostat/model/lagrange_top.hpp",
     "old": "dy[1] = ((C_ - A_) * p * r - mu_ * g[0] + M[1]) / A_;",
     "new": "dy[1] = ((C_ - A_) * p * r + mu_ * g[0] + M[1]) / A_;",
     "tests": ["tests/test_lagrange.py::test_full_rhs_equals_the_tests_own",
               "tests/test_lagrange.py::test_full_model_against_scipy_reference",
               "tests/test_lagrange.py::test_every_integrator_runs_the_top",
               "tests/test_engine.py::test_every_family_solves_and_ensembles[lagrange_top]",
               "tests/test_splitting.py::test_order_of_splitting_for_the_lagrange_top",
               "tests/test_splitting.py::test_new_families_split_in_ensembles_and_scenes"]},
    {"name": "averaged_cavity",
     "what": "averaged cavity ȧ = κC(A−C)r²a/A³ → κC(C−A)r²a/A³ (paper 000's printed sign)",
     "file": "cpp/include/gyrostat/torque/viscous_cavity.hpp",
     "old": "return {k * C * (A - C) * r * r * a / (A * A * A), k * (C - A) * a * a * r / (A * C)};",
     "new": "return {k * C * (C - A) * r * r * a / (A * A * A), k * (C - A) * a * a * r / (A * C)};",
     "tests": [TORQUES + "test_averaged_rhs_is_the_phase_average_of_the_torques_written_here",
               "tests/test_averaged.py",
               "tests/test_engine.py::test_every_family_solves_and_ensembles[averaged]",
               "tests/test_events.py::test_dense_output_of_every_family"]},
]

# Each mutation runs the tests meant to catch it (references written in the tests: SciPy on the
# tests' own equations, closed forms, phase averages); --tests runs other tests (files or node
# ids) for every mutation instead, e.g. whole files to see everything a mutation breaks.


def log(message: str) -> None:
    print(f"[{time.strftime('%H:%M:%S')}] {message}", flush=True)


def configure() -> None:
    if (BUILD / "build.ninja").exists():
        return
    pybind11_dir = subprocess.run([sys.executable, "-m", "pybind11", "--cmakedir"], check=True, capture_output=True,
                                  text=True).stdout.strip()
    subprocess.run(["cmake", "-S", str(ROOT), "-B", str(BUILD), "-G", "Ninja", "-DGYROSTAT_PYTHON=ON",
                    "-DCMAKE_BUILD_TYPE=Release", f"-DCMAKE_LIBRARY_OUTPUT_DIRECTORY={OUT}",
                    f"-DPython_EXECUTABLE={sys.executable}", f"-Dpybind11_DIR={pybind11_dir}"],
                   check=True, stdout=subprocess.DEVNULL)


def build() -> None:
    started = time.monotonic()
    done = subprocess.run(["cmake", "--build", str(BUILD), "--target", "_core", "-j1"], capture_output=True, text=True)
    if done.returncode != 0:
        sys.exit(f"build failed:\n{done.stdout[-4000:]}\n{done.stderr[-4000:]}")
    log(f"built in {time.monotonic() - started:.0f} s")


def package() -> None:
    """python/gyrostat without its extension, plus the one just built."""
    shutil.rmtree(PKG, ignore_errors=True)
    shutil.copytree(ROOT / "python" / "gyrostat", PKG / "gyrostat",
                    ignore=shutil.ignore_patterns("_core*.so", "__pycache__"))
    for so in OUT.glob("_core*.so"):
        shutil.copy2(so, PKG / "gyrostat" / so.name)


def run_tests(files: list[str]) -> tuple[list[str], str]:
    env = {**__import__("os").environ, "PYTHONPATH": str(PKG)}
    where = subprocess.run([sys.executable, "-c", "import gyrostat; print(gyrostat.__file__)"], env=env,
                           capture_output=True, text=True, cwd=ROOT).stdout.strip()
    if not where.startswith(str(PKG)):
        sys.exit(f"the tests would import gyrostat from {where}, not from {PKG}")
    started = time.monotonic()
    done = subprocess.run([sys.executable, "-m", "pytest", "-q", "-p", "no:cacheprovider", "-rf", "--tb=no", *files],
                          env=env, capture_output=True, text=True, cwd=ROOT, timeout=1800)
    failed = sorted({line.split(" - ")[0].removeprefix("FAILED ").strip()
                     for line in done.stdout.splitlines() if line.startswith("FAILED ")})
    summary = done.stdout.strip().splitlines()[-1] if done.stdout.strip() else done.stderr[-500:]
    log(f"tests in {time.monotonic() - started:.0f} s: {summary}")
    return failed, summary


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--only", action="append", help="run this mutation only (repeatable)")
    parser.add_argument("--skip-baseline", action="store_true", help="do not run the unmutated baseline first")
    parser.add_argument("--tests", nargs="+", help="tests (files or node ids) to run for every mutation instead")
    args = parser.parse_args()
    mutations = [m for m in MUTATIONS if not args.only or m["name"] in args.only]
    configure()
    results = {}
    ok = True
    if not args.skip_baseline:
        log("baseline (no mutation)")
        build()
        package()
        failed, summary = run_tests(args.tests or sorted({t for m in mutations for t in m["tests"]}))
        if failed:
            print("the baseline fails; fix that first:\n  " + "\n  ".join(failed))
            return 1
    for mutation in mutations:
        path = ROOT / mutation["file"]
        original = path.read_text()
        if original.count(mutation["old"]) != 1:
            sys.exit(f"{mutation['name']}: the line to mutate is not found exactly once in {mutation['file']}")
        log(f"mutation {mutation['name']}: {mutation['what']}")
        try:
            path.write_text(original.replace(mutation["old"], mutation["new"]))
            build()
            package()
            results[mutation["name"]] = run_tests(args.tests or mutation["tests"])
        finally:
            path.write_text(original)
        if not results[mutation["name"]][0]:
            ok = False
    print("\nmutation -> tests that failed")
    for mutation in mutations:
        failed, summary = results[mutation["name"]]
        print(f"\n{mutation['name']} ({mutation['what']}): {summary}")
        print("  " + ("\n  ".join(failed) if failed else "NOT CAUGHT"))
    print("\n(the extension in build/mutation/out is the last mutant's; the headers are restored)")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
