#!/usr/bin/env bash
# gyrostat's set-up and entry points; every command first installs what is missing:
# Debian packages (compiler, Eigen, SUNDIALS, GSL), a virtual environment in .venv, the package.
#
#   bash run.sh main [OUT]   run every example scene, results and plots in OUT/<scene>/ (default: results/);
#                            ends with a summary table and writes OUT/index.html (and index.md) linking them
#   bash run.sh test         run the whole test suite (C++ tests, plain and under sanitizers, then pytest)
#   bash run.sh bench        build the benchmark executable and chart work-precision (bench/)
#   bash run.sh docs         build the documentation site into docs/_build/html (warnings are errors)
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")"
ROOT=$PWD
VENV=$ROOT/.venv
DEBIAN_PACKAGES=(g++ cmake ninja-build pkg-config libeigen3-dev libsundials-dev libgsl-dev python3-dev python3-venv)

say() { printf '\n== %s\n' "$*" >&2; }

install_debian_packages() {
    local missing=()
    for pkg in "${DEBIAN_PACKAGES[@]}"; do
        dpkg-query -W -f='${Status}' "$pkg" 2>/dev/null | grep -q "install ok installed" || missing+=("$pkg")
    done
    # python3-dev/-venv matter only when python3 is Debian's; skip them when another python3 has venv
    if python3 -m venv --help >/dev/null 2>&1; then
        local keep=()
        for pkg in "${missing[@]}"; do [[ $pkg == python3-dev || $pkg == python3-venv ]] || keep+=("$pkg"); done
        missing=("${keep[@]}")
    fi
    # a cmake newer than Debian's on PATH is fine
    if command -v cmake >/dev/null 2>&1; then
        local keep=()
        for pkg in "${missing[@]}"; do [[ $pkg == cmake ]] || keep+=("$pkg"); done
        missing=("${keep[@]}")
    fi
    [[ ${#missing[@]} -eq 0 ]] && return 0
    say "installing Debian packages: ${missing[*]}"
    local sudo=""
    [[ $(id -u) -ne 0 ]] && sudo="sudo"
    $sudo apt-get update -qq
    DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq "${missing[@]}" >/dev/null
}

setup_python() {
    if [[ ! -x $VENV/bin/python ]]; then
        say "creating the virtual environment $VENV"
        python3 -m venv "$VENV"
    fi
    "$VENV/bin/python" -m pip install -q --upgrade pip >/dev/null
    say "building and installing gyrostat (C++ core + Python package)"
    "$VENV/bin/python" -m pip install -q "$ROOT[$1]"
}

run_cpp_tests() {
    say "C++ tests"
    cmake -S "$ROOT" -B "$ROOT/build/cpp-tests" -G Ninja -DGYROSTAT_TESTS=ON -DGYROSTAT_BENCH=ON \
        -DCMAKE_BUILD_TYPE=Release >/dev/null
    cmake --build "$ROOT/build/cpp-tests" --target gyrostat_cpp_tests gyrostat_auto_tests gyrostat_batch_tests gyrostat_stress gyrostat_bench
    (cd "$ROOT/build/cpp-tests" && ctest --output-on-failure)
}

# The C++ tests again under AddressSanitizer + UndefinedBehaviorSanitizer, and the ensemble stress
# test under ThreadSanitizer: any report fails the run. -O0: the sanitizers' instrumentation of the
# unrolled Taylor recursion takes minutes to optimise, and -O0 finds the same faults.
run_sanitizer_tests() {
    local flags=(-G Ninja -DGYROSTAT_TESTS=ON -DCMAKE_BUILD_TYPE=Debug "-DCMAKE_CXX_FLAGS_DEBUG=-O0 -g1")
    say "C++ tests under AddressSanitizer + UndefinedBehaviorSanitizer"
    cmake -S "$ROOT" -B "$ROOT/build/asan" "${flags[@]}" -DGYROSTAT_SANITIZE=address,undefined >/dev/null
    cmake --build "$ROOT/build/asan" --target gyrostat_cpp_tests gyrostat_auto_tests gyrostat_batch_tests gyrostat_stress
    (cd "$ROOT/build/asan" &&
        export ASAN_OPTIONS=halt_on_error=1:detect_leaks=1 UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1 &&
        ./gyrostat_cpp_tests >/dev/null && ./gyrostat_auto_tests >/dev/null && ./gyrostat_batch_tests >/dev/null &&
        ./gyrostat_stress)
    say "the ensemble stress test under ThreadSanitizer"
    cmake -S "$ROOT" -B "$ROOT/build/tsan" "${flags[@]}" -DGYROSTAT_SANITIZE=thread >/dev/null
    cmake --build "$ROOT/build/tsan" --target gyrostat_stress
    (cd "$ROOT/build/tsan" && TSAN_OPTIONS=halt_on_error=1:second_deadlock_stack=1 ./gyrostat_stress)
}

command=${1:-}
case $command in
    main)
        install_debian_packages
        setup_python test
        out=${2:-$ROOT/results}
        say "running the example scenes; results and plots go to $out"
        "$VENV/bin/gyrostat" examples --out "$out" --overwrite
        ;;
    test)
        install_debian_packages
        setup_python test
        run_cpp_tests
        run_sanitizer_tests
        say "Python tests"
        cd "$ROOT" && "$VENV/bin/python" -m pytest -q
        ;;
    bench)
        install_debian_packages
        setup_python bench
        say "building the benchmark executable"
        cmake -S "$ROOT" -B "$ROOT/build/bench" -G Ninja -DGYROSTAT_BENCH=ON -DCMAKE_BUILD_TYPE=Release >/dev/null
        cmake --build "$ROOT/build/bench" --target gyrostat_bench
        "$VENV/bin/python" "$ROOT/bench/work_precision.py" --bench-exe "$ROOT/build/bench/gyrostat_bench" "${@:2}"
        "$VENV/bin/python" "$ROOT/bench/python_overhead.py"
        "$VENV/bin/python" "$ROOT/bench/sweep_throughput.py"
        "$VENV/bin/python" "$ROOT/bench/stiff_radau.py"
        "$VENV/bin/python" "$ROOT/bench/auto_method.py"
        "$VENV/bin/python" "$ROOT/bench/ladder.py"
        ;;
    docs)
        install_debian_packages
        setup_python test
        say "building the documentation site into docs/_build/html"
        "$VENV/bin/python" -m sphinx -W --keep-going -b html "$ROOT/docs" "$ROOT/docs/_build/html"
        ;;
    *)
        echo "usage: bash run.sh main [OUT] | test | bench | docs" >&2
        exit 2
        ;;
esac
