#!/usr/bin/env python3
"""Mutation check (issues 29 and 44): do the tests catch a wrong physics equation?

Each mutation below names a file, an exact text `old` found in it exactly once, the expression
`expr` inside `old` to mutate (default: `old` itself) and its mutant: either `new` (a flipped
sign, written as an expression) or a `factor` (1.05 or 0.99) on `expr`. The script copies the
worktree's tracked files to build/mutation/src and, there only, writes each `expr` as

    (gyrostat_mutation(N) ? (new) : (expr))          a `new` mutation
    (gyrostat_mutation(N) ? 1.05 : 1.0) * (expr)     a `factor` mutation (also for Eigen and SIMD types)

and inserts once per mutated file (behind a macro guard) an inline `bool gyrostat_mutation(int id)`
that compares id with the integer in the environment variable GYROSTAT_MUTATION (read once, in a
function-local static; unset = 0 = no mutation). It builds `_core` ONCE from that copy
(build/mutation/build, -O1, GYROSTAT_TAYLOR_ORDER_STEP=8, -j1, without the SIMD plugins: 223 s
measured on the shared 2-core machine; a rerun rebuilds only what changed), copies the package
with that extension to build/mutation/pkg (the worktree's own build is never touched; without
the plugins the SSE2 built-in batch form runs), then runs the baseline (GYROSTAT_MUTATION unset: it must
pass, or a failure under a mutation would prove nothing) and, for each mutation, the tests meant
to catch it with GYROSTAT_MUTATION=N, and prints which tests failed. The tests listed compare
against references written independently of the library (SciPy runs on the test's own
equations, closed forms, phase averages, mpmath), not values pinned from an earlier run.

    /work/main/.venv/bin/python tools/mutation_check.py            # build, baseline, every mutation
    /work/main/.venv/bin/python tools/mutation_check.py --only top_gravity --skip-baseline
    /work/main/.venv/bin/python tools/mutation_check.py --list     # the mutations and their ids

After the build the baseline takes ~30 s and each mutation's tests 2-11 s (~4 min for all 35).
The results table (mutation -> the tests that catch it) is in docs/architecture.md.
Exit status 1 if the baseline fails or a mutation is caught by no test.
"""

from __future__ import annotations

import argparse
import os
import shutil
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
BUILD = ROOT / "build" / "mutation"
SRC = BUILD / "src"      # the instrumented copy of the sources
BINARY = BUILD / "build"  # its CMake build directory
OUT = BUILD / "out"
PKG = BUILD / "pkg"

TORQUE = "cpp/include/gyrostat/torque/"
MODEL = "cpp/include/gyrostat/model/"
T = "tests/test_torques.py::"
TRI = "tests/test_averaged_triaxial.py::"
ATT = "tests/test_attitude_torques.py::"
ORB = "tests/test_orbit_frame.py::"
LAG = "tests/test_lagrange.py::"
# the (a, r) model's: the phase average of the torques written in the test, SciPy on the printed and
# derived averaged systems, the full model integrated (O(ε)), the paper's closed forms
SYMMETRIC = [T + "test_averaged_rhs_is_the_phase_average_of_the_torques_written_here", "tests/test_averaged.py"]
# the triaxial averaged model's tests against references written in the tests: mpmath closed forms, a
# time average of SciPy's Euler solution, the full model integrated (|G|, T, ω at the carried phase)
# and, for a closed form, the model's own quadrature of the same torque written in Python
TRIAXIAL = [TRI + "test_rates_of_the_closed_forms_equal_the_mpmath_reference",
            TRI + "test_quadrature_and_the_medium_equal_a_time_average_of_euler_written_here",
            TRI + "test_error_of_G_and_T_is_first_order_in_epsilon",
            TRI + "test_the_carried_phase_gives_omega_along_the_run",
            TRI + "test_a_compare_scene_reports_the_error_of_omega_at_the_carried_phase",
            TRI + "test_quadrature_for_a_users_torque_equals_the_closed_forms"]

MUTATIONS = [
    # --- the sign mutations of issue 29 -----------------------------------------------------------
    {"name": "cavity_sign",
     "what": "viscous cavity (paper 002 (1)): sign of C(A−C)(A+C−B) r² in M_p",
     "file": TORQUE + "viscous_cavity.hpp", "old": "c[0] * r2", "new": "-c[0] * r2",
     "tests": [T + "test_cavity_torque_formula_and_invariants",
               T + "test_full_model_with_new_torques_against_scipy",
               "tests/test_splitting.py::test_order_of_splitting_with_the_cavity",
               "tests/test_splitting.py::test_splitting_keeps_G_when_the_perturbation_does",
               "tests/test_readme.py::test_readme_results_against_references"]},
    {"name": "damper_sign",
     "what": "moving-mass damper (paper 001 (2)-(3)): sign of the axial T_S",
     "file": TORQUE + "moving_mass_damper.hpp",
     "old": "kS * (A - B - C) * (A - B + C)", "new": "-kS * (A - B - C) * (A - B + C)",
     "tests": [T + "test_damper_torque_symmetric_and_triaxial",
               T + "test_full_model_with_new_torques_against_scipy"]},
    {"name": "top_gravity",
     "what": "Lagrange top (paper 003 (1.1)): sign of gravity's moment −μγ1 in the q equation",
     "file": MODEL + "lagrange_top.hpp", "old": "- mu_ * g[0] + M[1]", "expr": "mu_ * g[0]", "new": "-mu_ * g[0]",
     "tests": [LAG + "test_full_rhs_equals_the_tests_own",
               LAG + "test_full_model_against_scipy_reference",
               LAG + "test_every_integrator_runs_the_top",
               "tests/test_engine.py::test_every_family_solves_and_ensembles[lagrange_top]",
               "tests/test_splitting.py::test_order_of_splitting_for_the_lagrange_top",
               "tests/test_splitting.py::test_new_families_split_in_ensembles_and_scenes"]},
    {"name": "averaged_cavity",
     "what": "averaged cavity ȧ = κC(A−C)r²a/A³ → κC(C−A)r²a/A³ (paper 000's printed sign)",
     "file": TORQUE + "viscous_cavity.hpp",
     "old": "k * C * (A - C) * r * r * a / (A * A * A)", "new": "k * C * (C - A) * r * r * a / (A * A * A)",
     "tests": [T + "test_averaged_rhs_is_the_phase_average_of_the_torques_written_here",
               "tests/test_averaged.py",
               "tests/test_engine.py::test_every_family_solves_and_ensembles[averaged]",
               "tests/test_events.py::test_dense_output_of_every_family"]},
    # --- factor mutations (issue 44): averaged (a, r) contributions over the symmetric motion ------
    {"name": "avg_constant", "what": "averaged constant torque: ṙ = M_z/C × 1.05",
     "file": TORQUE + "constant.hpp", "old": "moment.z() / C", "factor": 1.05,
     "tests": SYMMETRIC},
    {"name": "avg_linear_damping", "what": "averaged linear damping: ȧ = −(D11 + D22)a/(2A) × 1.05",
     "file": TORQUE + "linear_damping.hpp", "old": "(matrix(0, 0) + matrix(1, 1)) * a / (2.0 * A)", "factor": 1.05,
     "tests": SYMMETRIC},
    {"name": "avg_medium", "what": "averaged resistive medium: ṙ = −D33(t) r/C × 0.99",
     "file": TORQUE + "resistive_medium.hpp", "old": "d(2, 2) * r / C", "factor": 0.99,
     "tests": [T + "test_resistive_medium_polynomial_in_time", "tests/test_averaged.py"]},
    {"name": "avg_cavity_r", "what": "averaged cavity: ṙ = κ(C−A)a²r/(AC) × 1.05",
     "file": TORQUE + "viscous_cavity.hpp", "old": "k * (C - A) * a * a * r / (A * C)", "factor": 1.05,
     "tests": SYMMETRIC},
    {"name": "avg_damper", "what": "averaged moving-mass damper: ȧ = S r⁴ a/A × 1.05",
     "file": TORQUE + "moving_mass_damper.hpp", "old": "s * r3 * r * a / A", "factor": 1.05,
     "tests": SYMMETRIC},
    {"name": "avg_model_rhs", "what": "the symmetric averaged model's right-hand side × 0.99",
     "file": MODEL + "averaged.hpp", "old": "torques_.averaged(t, y[0], y[1], A_, C_)", "factor": 0.99,
     "tests": SYMMETRIC},
    # --- the triaxial averaged model: its (|G|², p_b, s, φ) equations and each torque's averaged power
    {"name": "tri_G2", "what": "triaxial averaged: d|G|²/dt = 2 Σ A_i P_i × 1.05",
     "file": MODEL + "averaged_triaxial.hpp", "old": "dy[0] = 2.0 * J.dot(power)",
     "expr": "J.dot(power)", "factor": 1.05, "tests": TRIAXIAL},
    {"name": "tri_pb", "what": "triaxial averaged: dp_b/dt = 2 Σ A_i (A_i − A_b) P_i × 0.99",
     "file": MODEL + "averaged_triaxial.hpp", "old": "(J.array() - middle_).matrix().dot(power)", "factor": 0.99,
     "tests": TRIAXIAL},
    {"name": "tri_phase", "what": "triaxial averaged: the phase's rate π λ/(2K) × 1.05",
     "file": MODEL + "averaged_triaxial.hpp", "old": "dy[3] = free.phase_rate()",
     "expr": "free.phase_rate()", "factor": 1.05, "tests": TRIAXIAL},
    {"name": "tri_power_constant",
     "what": "triaxial averaged power of the folded constant torque M0_i⟨ω_i⟩ × 1.05",
     "file": TORQUE + "set.hpp", "old": "constant_.cwiseProduct(motion.mean_omega())", "factor": 1.05,
     "tests": TRIAXIAL},
    {"name": "tri_power_damping",
     "what": "triaxial averaged power of the folded linear damping −D_ii⟨ω_i²⟩ × 1.05",
     "file": TORQUE + "set.hpp", "old": "damping_.diagonal().cwiseProduct(motion.mean_square())", "factor": 1.05,
     "tests": TRIAXIAL},
    {"name": "tri_power_medium",
     "what": "triaxial averaged power of the resistive medium −D_ii(t)⟨ω_i²⟩ × 0.99",
     "file": TORQUE + "resistive_medium.hpp", "old": "at(t).diagonal().cwiseProduct(motion.mean_square())",
     "factor": 0.99,
     "tests": TRIAXIAL},
    {"name": "tri_power_cavity", "what": "triaxial averaged power of the cavity: c0 Q_pr in ⟨p M_p⟩ × 1.05",
     "file": TORQUE + "viscous_cavity.hpp", "old": "c[0] * Q(0, 2)", "factor": 1.05,
     "tests": TRIAXIAL},
    {"name": "tri_power_quadrature",
     "what": "triaxial averaged power by quadrature (the damper's, a user's) Σ/n × 1.05",
     "file": TORQUE + "set.hpp", "old": "sum / n", "factor": 1.05,
     "tests": TRIAXIAL},
    # --- each torque's full moment ----------------------------------------------------------------
    {"name": "full_constant", "what": "constant torque M0 × 1.05 (folded into the torque set: every path)",
     "file": TORQUE + "set.hpp", "old": "constant_ += c->moment", "expr": "c->moment", "factor": 1.05,
     "tests": ["tests/test_forced.py", T + "test_full_model_with_new_torques_against_scipy"]},
    {"name": "full_linear_damping", "what": "linear damping D × 0.99 (folded into the torque set: every path)",
     "file": TORQUE + "set.hpp", "old": "damping_ += d->matrix", "expr": "d->matrix", "factor": 0.99,
     "tests": ["tests/test_forced.py", "tests/test_invariants.py"]},
    {"name": "full_medium", "what": "resistive medium M = −D(t)ω × 1.05",
     "file": TORQUE + "resistive_medium.hpp", "old": "at(t) * omega", "factor": 1.05,
     "tests": [T + "test_resistive_medium_polynomial_in_time", T + "test_full_model_with_new_torques_against_scipy"]},
    {"name": "full_cavity", "what": "viscous cavity: B(A−B)(A+B−C) q² in M_p × 1.05",
     "file": TORQUE + "viscous_cavity.hpp", "old": "c[1] * q2", "factor": 1.05,
     "tests": [T + "test_cavity_torque_formula_and_invariants",
               T + "test_full_model_with_new_torques_against_scipy"]},
    {"name": "full_damper_TS", "what": "moving-mass damper: the p²r² term of the axial T_S × 1.05",
     "file": TORQUE + "moving_mass_damper.hpp", "old": "c.s2[0] * p2r2", "factor": 1.05,
     "tests": [T + "test_damper_torque_symmetric_and_triaxial",
               T + "test_damper_in_a_model_uses_the_coefficients_made_for_its_body",
               T + "test_full_model_with_new_torques_against_scipy"]},
    {"name": "full_damper_kL", "what": "moving-mass damper: k_L = mρ²/Ω² of the conservative T_L × 1.05",
     "file": TORQUE + "moving_mass_damper.hpp", "old": "mass_arm2 / omega2", "factor": 1.05,
     "tests": [T + "test_damper_torque_symmetric_and_triaxial",
               T + "test_damper_in_a_model_uses_the_coefficients_made_for_its_body",
               T + "test_full_model_with_new_torques_against_scipy"]},
    {"name": "gravity_gradient", "what": "gravity gradient 3n² ĉ × (Jĉ): the cross product × 1.05",
     "file": TORQUE + "gravity_gradient.hpp", "old": "c.cross(moments.cwiseProduct(c))", "factor": 1.05,
     "tests": [ATT + "test_attitude_torque_against_scipy", ATT + "test_torque_value_against_the_written_formula",
               ATT + "test_gravity_gradient_precession_matches_the_classical_rate"]},
    {"name": "magnetic", "what": "magnetic torque m × Rᵀ B × 0.99",
     "file": TORQUE + "magnetic.hpp", "old": "dipole.cross(rotation_matrix(quaternion).transpose() * field)",
     "factor": 0.99,
     "tests": [ATT + "test_attitude_torque_against_scipy", ATT + "test_torque_value_against_the_written_formula"]},
    {"name": "dipole_field", "what": "tilted dipole field B0 [3 (d·ĉ) ĉ − d]: the 3 (d·ĉ) ĉ term × 1.05",
     "file": TORQUE + "dipole_field.hpp", "old": "3.0 * axis.dot(c) * c", "factor": 1.05,
     "tests": [ATT + "test_attitude_torque_against_scipy", ATT + "test_torque_value_against_the_written_formula"]},
    {"name": "inertial", "what": "inertially fixed torque Rᵀ M_I × 1.05",
     "file": TORQUE + "inertial.hpp", "old": "rotation_matrix(quaternion).transpose() * moment", "factor": 1.05,
     "tests": [ATT + "test_attitude_torque_against_scipy", ATT + "test_torque_value_against_the_written_formula",
               ATT + "test_inertial_torque_grows_the_inertial_momentum_linearly"]},
    # --- the orbit and the attitude relative to it (torque/orbit.hpp, model/orbiting.hpp) ----------
    {"name": "orbit_position", "what": "the body's place on the orbit: the e2 term of ĉ(t) × 1.05",
     "file": TORQUE + "orbit.hpp", "old": "std::sin(u) * quadrant", "factor": 1.05,
     "tests": [ORB + "test_orbit_frame_outputs_equal_the_tests_own_formulas", ATT + "test_attitude_torque_against_scipy"]},
    {"name": "orbit_relative_rate", "what": "ω relative to the orbit frame: n Rᵀ N × 1.05",
     "file": MODEL + "orbiting.hpp", "old": "omega - orbit_.rate * (R.transpose() * orbit_.normal)",
     "expr": "orbit_.rate * (R.transpose() * orbit_.normal)", "factor": 1.05,
     "tests": [ORB + "test_orbit_frame_outputs_equal_the_tests_own_formulas"]},
    {"name": "orbit_frame_start", "what": "a state given relative to the orbit frame: n Rᵀ N × 1.05",
     "file": MODEL + "orbiting.hpp", "old": "omega_rel + orbit_.rate * (R.transpose() * orbit_.normal)",
     "expr": "orbit_.rate * (R.transpose() * orbit_.normal)", "factor": 1.05,
     "tests": [ORB + "test_large_pitch_libration_has_the_pendulums_exact_period"]},
    # --- each model's right-hand side -------------------------------------------------------------
    {"name": "euler_gyroscopic", "what": "Euler's equations (gyrostat.hpp rhs): ω × (Jω + k) × 1.05",
     "file": MODEL + "gyrostat.hpp", "old": "omega.cross(momentum)", "factor": 1.05,
     "tests": ["tests/test_forced.py", T + "test_full_model_with_new_torques_against_scipy",
               "tests/test_torque_free.py::test_integrators_against_elliptic_solution[10-1e-09-dop853]",
               "tests/test_torque_free.py::test_integrators_against_elliptic_solution[10-1e-09-cvode_bdf]"]},
    {"name": "affine_euler", "what": "the Taylor recursion's and SIMD batches' Euler equations: A_j − A_k × 1.05",
     "file": MODEL + "affine_euler.hpp", "old": "e.differences[i] = J[(i + 1) % 3] - J[(i + 2) % 3]",
     "expr": "J[(i + 1) % 3] - J[(i + 2) % 3]", "factor": 1.05,
     "tests": ["tests/test_forced.py::test_forced_gyrostat_against_scipy[taylor]",
               "tests/test_batch.py::test_batched_members_against_scipy_and_their_single_runs"]},
    {"name": "moving_mass_spring", "what": "explicit moving mass: the spring Ω² u1 in R1 × 1.05",
     "file": MODEL + "moving_mass.hpp", "old": "- omega2_ * u1 - lambda_ * v1",
     "expr": "omega2_ * u1", "factor": 1.05,
     "tests": [T + "test_explicit_moving_mass_rhs_against_the_test_formula", "tests/test_auto_method.py"]},
    {"name": "top_gravity_factor", "what": "Lagrange top: gravity's moment μγ2 in the p equation × 1.05",
     "file": MODEL + "lagrange_top.hpp", "old": "+ mu_ * g[1] + M[0]", "expr": "mu_ * g[1]", "factor": 1.05,
     "tests": [LAG + "test_full_rhs_equals_the_tests_own", LAG + "test_full_model_against_scipy_reference",
               LAG + "test_nutation_matches_the_sn_solution"]},
    {"name": "lagrange_averaged", "what": "averaged Lagrange top: f (G_z − C r v)/A in Ġ_z × 1.05",
     "file": MODEL + "lagrange_averaged.hpp", "old": "f * (Gz - C * r * v) / A", "factor": 1.05,
     "tests": [LAG + "test_averaged_rhs_is_the_nutation_average_of_the_exact_rates", LAG + "test_averaged_r_is_exact",
               LAG + "test_averaged_against_full_is_first_order_in_eps"]},
    {"name": "orthogonal_gain", "what": "orthogonal servo torque: its gain L(t)/n_δ(|Q|) × 1.05",
     "file": MODEL + "orthogonal.hpp", "old": "law_(t) / denominator(q_norm, delta)", "factor": 1.05,
     "tests": ["tests/test_orthogonal.py::test_full_model_against_scipy",
               "tests/test_orthogonal.py::test_magnitude_laws_evaluate_as_written",
               "tests/test_orthogonal.py::test_omega_is_torque_free_solution_at_tau"]},
    {"name": "torque_free_frequency", "what": "torque-free closed form: the frequency ν of the argument u × 1.05",
     "file": "cpp/src/torque_free.cpp", "old": "k.nu = DoubleDouble(nu)",
     "expr": "DoubleDouble(nu)", "new": "DoubleDouble(Real(1.05) * nu)",
     "tests": ["tests/test_torque_free.py::test_closed_form_matches_independent_reference"]},
]

# Each mutation runs the tests meant to catch it; --tests runs other tests (files or node ids)
# for every mutation instead, e.g. whole files to see everything a mutation breaks.

SWITCH = """
#ifndef GYROSTAT_MUTATION_SWITCH
#define GYROSTAT_MUTATION_SWITCH
#include <cstdlib>
// tools/mutation_check.py: mutation `id` is on when the environment's GYROSTAT_MUTATION is id.
inline bool gyrostat_mutation(int id) {
    static const int active = [] {
        const char* value = std::getenv("GYROSTAT_MUTATION");
        return value ? std::atoi(value) : 0;
    }();
    return id == active;
}
#endif
"""


def mutant(number: int, mutation: dict) -> str:
    expr = mutation.get("expr", mutation["old"])
    if "factor" in mutation:
        return f"(gyrostat_mutation({number}) ? {mutation['factor']} : 1.0) * ({expr})"
    return f"(gyrostat_mutation({number}) ? ({mutation['new']}) : ({expr}))"


def instrumented() -> dict[str, str]:
    """The mutated files' instrumented text (every mutation in it, each behind its switch)."""
    texts: dict[str, str] = {}
    for number, mutation in enumerate(MUTATIONS, start=1):
        name, old = mutation["name"], mutation["old"]
        original = (ROOT / mutation["file"]).read_text()
        if original.count(old) != 1:
            sys.exit(f"{name}: {old!r} is found {original.count(old)} times in {mutation['file']}, not once")
        expr = mutation.get("expr", old)
        if old.count(expr) != 1:
            sys.exit(f"{name}: the expression {expr!r} is not found once in {old!r}")
        text = texts.get(mutation["file"], original)
        if text.count(old) != 1:
            sys.exit(f"{name}: {old!r} overlaps another mutation's text in {mutation['file']}")
        texts[mutation["file"]] = text.replace(old, old.replace(expr, mutant(number, mutation)))
    for file, text in texts.items():
        if "#pragma once\n" in text:
            texts[file] = text.replace("#pragma once\n", "#pragma once\n" + SWITCH, 1)
        else:
            texts[file] = SWITCH.lstrip() + text
    return texts


def write_if_changed(path: Path, data: bytes) -> None:
    """Unchanged files keep their time stamps: a rerun rebuilds only what changed."""
    if path.exists() and path.read_bytes() == data:
        return
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_bytes(data)


def prepare_sources() -> None:
    """The worktree's tracked files (as they are on disk) in SRC, the mutated ones instrumented."""
    files = subprocess.run(["git", "ls-files", "-z"], cwd=ROOT, check=True, capture_output=True).stdout.split(b"\0")
    mutated = instrumented()
    # _core without the SIMD plugins it otherwise waits for (they are not copied to the package)
    cmake = (ROOT / "CMakeLists.txt").read_text()
    if cmake.count("    add_dependencies(_core _batch_${isa})\n") != 1:
        sys.exit("CMakeLists.txt: the plugins' add_dependencies(_core _batch_${isa}) line is not found once")
    mutated["CMakeLists.txt"] = cmake.replace("    add_dependencies(_core _batch_${isa})\n", "")
    for name in filter(None, (f.decode() for f in files)):
        source = ROOT / name
        if not source.is_file():
            continue
        data = mutated[name].encode() if name in mutated else source.read_bytes()
        write_if_changed(SRC / name, data)


def log(message: str) -> None:
    print(f"[{time.strftime('%H:%M:%S')}] {message}", flush=True)


def configure() -> None:
    if (BINARY / "build.ninja").exists():
        return
    pybind11_dir = subprocess.run([sys.executable, "-m", "pybind11", "--cmakedir"], check=True, capture_output=True,
                                  text=True).stdout.strip()
    # -O1 and every 8th Taylor order (as the sanitizer builds): the one build in a few minutes at -j1
    subprocess.run(["cmake", "-S", str(SRC), "-B", str(BINARY), "-G", "Ninja", "-DGYROSTAT_PYTHON=ON",
                    "-DCMAKE_BUILD_TYPE=Release", "-DCMAKE_CXX_FLAGS_RELEASE=-O1 -DNDEBUG",
                    "-DCMAKE_CXX_FLAGS=-DGYROSTAT_TAYLOR_ORDER_STEP=8", f"-DCMAKE_LIBRARY_OUTPUT_DIRECTORY={OUT}",
                    f"-DPython_EXECUTABLE={sys.executable}", f"-Dpybind11_DIR={pybind11_dir}"],
                   check=True, stdout=subprocess.DEVNULL)


def build(jobs: int) -> None:
    started = time.monotonic()
    done = subprocess.run(["cmake", "--build", str(BINARY), "--target", "_core", f"-j{jobs}"], capture_output=True,
                          text=True)
    if done.returncode != 0:
        sys.exit(f"build failed:\n{done.stdout[-4000:]}\n{done.stderr[-4000:]}")
    log(f"built in {time.monotonic() - started:.0f} s")


def package() -> None:
    """python/gyrostat without its extension, plus the one just built."""
    shutil.rmtree(PKG, ignore_errors=True)
    shutil.copytree(ROOT / "python" / "gyrostat", PKG / "gyrostat",
                    ignore=shutil.ignore_patterns("_core*.so", "_batch_*.so", "__pycache__"))
    for so in OUT.glob("_core*.so"):
        shutil.copy2(so, PKG / "gyrostat" / so.name)


def run_tests(files: list[str], number: int | None) -> tuple[list[str], str]:
    env = {**os.environ, "PYTHONPATH": str(PKG)}
    env.pop("GYROSTAT_MUTATION", None)
    if number is not None:
        env["GYROSTAT_MUTATION"] = str(number)
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
    parser.add_argument("--list", action="store_true", help="list the mutations with their ids and stop")
    parser.add_argument("--build-only", action="store_true", help="build the instrumented extension and stop")
    parser.add_argument("--jobs", type=int, default=1, help="build jobs (default 1: the machine is shared)")
    args = parser.parse_args()
    numbers = {m["name"]: n for n, m in enumerate(MUTATIONS, start=1)}
    if args.list:
        for mutation in MUTATIONS:
            print(f"{numbers[mutation['name']]:3d} {mutation['name']}: {mutation['what']}")
        return 0
    unknown = set(args.only or ()) - set(numbers)
    if unknown:
        sys.exit(f"unknown mutations: {', '.join(sorted(unknown))}")
    mutations = [m for m in MUTATIONS if not args.only or m["name"] in args.only]
    prepare_sources()
    configure()
    log("building the instrumented extension (every mutation, each off unless GYROSTAT_MUTATION names it)")
    build(args.jobs)
    package()
    if args.build_only:
        return 0
    if not args.skip_baseline:
        log("baseline (GYROSTAT_MUTATION unset)")
        failed, summary = run_tests(args.tests or sorted({t for m in mutations for t in m["tests"]}), None)
        if failed:
            print("the baseline fails; fix that first:\n  " + "\n  ".join(failed))
            return 1
    results = {}
    ok = True
    for mutation in mutations:
        log(f"mutation {numbers[mutation['name']]} {mutation['name']}: {mutation['what']}")
        results[mutation["name"]] = run_tests(args.tests or mutation["tests"], numbers[mutation["name"]])
        if not results[mutation["name"]][0]:
            ok = False
    print("\nmutation -> tests that failed")
    for mutation in mutations:
        failed, summary = results[mutation["name"]]
        print(f"\n{mutation['name']} ({mutation['what']}): {summary}")
        print("  " + ("\n  ".join(failed) if failed else "NOT CAUGHT"))
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
