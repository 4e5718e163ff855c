"""The C++ library for C++ users: `cmake --install` gives headers, the core library and a CMake
package; examples/cpp/ is configured with find_package(gyrostat), linked to gyrostat::core and
run. Reuses the build of `bash run.sh test` (build/release: the package's core and the C++ tests)
when it is there."""

import shutil
import subprocess
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
BUILD = ROOT / "build" / "release"


def run(*command):
    done = subprocess.run([str(c) for c in command], capture_output=True, text=True)
    assert done.returncode == 0, f"{' '.join(map(str, command))}\n{done.stdout}\n{done.stderr}"
    return done.stdout


@pytest.mark.skipif(shutil.which("cmake") is None, reason="needs cmake (run.sh installs it)")
def test_installed_package_builds_and_runs_the_example(tmp_path):
    build = BUILD
    if not (build / "CMakeCache.txt").is_file():  # outside run.sh test: a build of the core alone
        build = tmp_path / "core"
        run("cmake", "-S", ROOT, "-B", build, "-DCMAKE_BUILD_TYPE=Release")
    run("cmake", "--build", build, "--target", "gyrostat_core", "-j", "1")
    prefix = tmp_path / "prefix"
    run("cmake", "--install", build, "--prefix", prefix, "--component", "development")
    assert (prefix / "include" / "gyrostat" / "engine.hpp").is_file()
    configs = list(prefix.glob("lib*/cmake/gyrostat/gyrostatConfig.cmake"))
    assert len(configs) == 1 and (configs[0].parent / "gyrostatConfigVersion.cmake").is_file()

    example = tmp_path / "example"
    run("cmake", "-S", ROOT / "examples" / "cpp", "-B", example, f"-DCMAKE_PREFIX_PATH={prefix}",
        "-DCMAKE_BUILD_TYPE=Release")
    run("cmake", "--build", example, "-j", "1")
    out = run(example / "torque_free")
    error = float(out.split("max |omega - closed form| = ")[1].split()[0])
    assert error < 1e-8, out


@pytest.mark.skipif(shutil.which("cmake") is None, reason="needs cmake (run.sh installs it)")
def test_benchmark_documents_its_options():
    """The benchmark executable of `bash run.sh test`'s C++ build (configured with GYROSTAT_BENCH
    there; configured so here when it is not) prints its usage and refuses an unknown option."""
    if not (BUILD / "CMakeCache.txt").is_file():
        run("cmake", "-S", ROOT, "-B", BUILD, "-G", "Ninja", "-DGYROSTAT_TESTS=ON", "-DCMAKE_BUILD_TYPE=Release")
    run("cmake", "-S", ROOT, "-B", BUILD, "-DGYROSTAT_BENCH=ON")
    run("cmake", "--build", BUILD, "--target", "gyrostat_bench")
    usage = run(BUILD / "gyrostat_bench", "--help")
    for text in ("usage: gyrostat_bench [--quick | --taylor [RTOLS] | --taylor-profile | --averaged-rhs] [--help]",
                 "--quick", "--taylor-profile", "--averaged-rhs", "problem,method,rtol,error,steps,rhs_evals,seconds"):
        assert text in usage, usage
    wrong = subprocess.run([str(BUILD / "gyrostat_bench"), "--fast"], capture_output=True, text=True)
    assert wrong.returncode == 2 and "usage: gyrostat_bench" in wrong.stderr + wrong.stdout
