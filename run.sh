#!/usr/bin/env bash
# gyrostat's set-up and entry points; every command first installs what is missing:
# Debian packages (compiler, Eigen, SUNDIALS, GSL), a virtual environment in .venv, the package
# (built in build/release, kept: no rebuild when no source changed since the last install).
#
#   bash run.sh main [OUT]   run every example scene, results and plots in OUT/<scene>/ (default: results/);
#                            ends with a summary table and writes OUT/index.html (and index.md) linking them
#   bash run.sh test         run the test suite: the C++ tests (Release, on the package's core), then pytest
#   bash run.sh sanitize     the C++ tests under AddressSanitizer + UBSan and the ensemble stress test under
#                            ThreadSanitizer (their own -O0 builds; CI runs it after `test`)
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

# The package's CMake build folder, kept between runs: pip builds in it without build isolation
# (the build requirements live in the venv), so a run with no source changed recompiles nothing
# and a change recompiles what it touches. The C++ tests build in it too (one Release core).
PACKAGE_BUILD=$ROOT/build/release
# Written after each install: the extras installed; its time is the start of that install.
INSTALLED_STAMP=$VENV/.gyrostat-installed

# True when the package is installed with extra $1 and no file it is built from changed since.
package_up_to_date() {
    [[ -f $INSTALLED_STAMP && -x $VENV/bin/gyrostat ]] || return 1
    grep -qx "$1" "$INSTALLED_STAMP" || return 1
    local changed
    changed=$(find "$ROOT/cpp" "$ROOT/python" "$ROOT/cmake" "$ROOT/CMakeLists.txt" "$ROOT/pyproject.toml" \
        "$ROOT/README.md" -name __pycache__ -prune -o -newer "$INSTALLED_STAMP" -print -quit)
    [[ -z $changed ]]
}

setup_python() {
    local extra=$1
    if [[ ! -x $VENV/bin/python ]]; then
        say "creating the virtual environment $VENV"
        python3 -m venv "$VENV"
    fi
    if package_up_to_date "$extra"; then
        say "gyrostat is installed and no source changed since (delete $INSTALLED_STAMP to reinstall)"
        return 0
    fi
    "$VENV/bin/python" -m pip install -q --upgrade pip >/dev/null
    # the build requirements of pyproject.toml, installed in the venv once: no build isolation
    local requires
    requires=$("$VENV/bin/python" -c 'import re, sys
text = open(sys.argv[1]).read()
print("\n".join(re.findall(r"\"([^\"]+)\"", re.search(r"^requires\s*=\s*\[(.*?)\]", text, re.M | re.S).group(1))))' \
        "$ROOT/pyproject.toml")
    mapfile -t requires <<<"$requires"
    "$VENV/bin/python" -m pip install -q "${requires[@]}"
    say "building and installing gyrostat (C++ core + Python package) in $PACKAGE_BUILD"
    local start=$INSTALLED_STAMP.start log=$ROOT/build/pip-install.log
    mkdir -p "$ROOT/build"
    touch "$start"  # a file changed during the build is newer than the stamp: the next run rebuilds
    # -v and the filter: the compiler's progress lines ([n/N]) as they come; all of it in $log
    if ! "$VENV/bin/python" -m pip install -v --no-build-isolation -C build-dir="$PACKAGE_BUILD" \
        -C build.targets=_core "$ROOT[$extra]" </dev/null 2>&1 | tee "$log" |
        { grep --line-buffered -E '^\s*\[[0-9]+/[0-9]+\] |^\*\*\* ' >&2 || true; }; then
        tail -n 60 "$log" >&2
        echo "pip install failed; its whole output: $log" >&2
        return 1
    fi
    # the extras installed before stay when nothing was rebuilt for them
    { [[ -f $INSTALLED_STAMP ]] && package_up_to_date "$(head -n1 "$INSTALLED_STAMP")" && cat "$INSTALLED_STAMP"
      echo "$extra"; } | sort -u >"$start.extras"
    mv "$start.extras" "$INSTALLED_STAMP"
    touch -r "$start" "$INSTALLED_STAMP"
    rm -f "$start"
}

# Configures the package's build folder (above) with more targets: one Release core for the
# package, the C++ tests and the benchmark. A folder pip has not made yet gets pip's generator.
configure_package_build() {
    local generator=()
    [[ -f $PACKAGE_BUILD/CMakeCache.txt ]] || generator=(-G Ninja)
    cmake -S "$ROOT" -B "$PACKAGE_BUILD" "${generator[@]}" "$@" >/dev/null
}

build_cpp_tests() {
    configure_package_build -DGYROSTAT_TESTS=ON -DGYROSTAT_BENCH=ON
    cmake --build "$PACKAGE_BUILD" --target gyrostat_cpp_tests gyrostat_auto_tests gyrostat_batch_tests gyrostat_stress \
        gyrostat_bench
}

run_cpp_tests() {
    (cd "$PACKAGE_BUILD" && ctest --output-on-failure)
}

# The C++ tests again under AddressSanitizer + UndefinedBehaviorSanitizer, and the ensemble stress
# test under ThreadSanitizer: any report fails the run. -O0: the sanitizers' instrumentation of the
# unrolled Taylor recursion takes minutes to optimise, and -O0 finds the same faults.
SANITIZER_FLAGS=(-G Ninja -DGYROSTAT_TESTS=ON -DCMAKE_BUILD_TYPE=Debug "-DCMAKE_CXX_FLAGS_DEBUG=-O0 -g1")
build_asan_tests() {
    cmake -S "$ROOT" -B "$ROOT/build/asan" "${SANITIZER_FLAGS[@]}" -DGYROSTAT_SANITIZE=address,undefined >/dev/null
    cmake --build "$ROOT/build/asan" --target gyrostat_cpp_tests gyrostat_auto_tests gyrostat_batch_tests gyrostat_stress
}

run_asan_tests() {
    (cd "$ROOT/build/asan" &&
        export ASAN_OPTIONS=halt_on_error=1:detect_leaks=1 UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1 &&
        ./gyrostat_cpp_tests >/dev/null && ./gyrostat_auto_tests >/dev/null && ./gyrostat_batch_tests >/dev/null &&
        ./gyrostat_stress)
}

build_tsan_tests() {
    cmake -S "$ROOT" -B "$ROOT/build/tsan" "${SANITIZER_FLAGS[@]}" -DGYROSTAT_SANITIZE=thread >/dev/null
    cmake --build "$ROOT/build/tsan" --target gyrostat_stress
}

run_tsan_tests() {
    (cd "$ROOT/build/tsan" && TSAN_OPTIONS=halt_on_error=1:second_deadlock_stack=1 ./gyrostat_stress)
}

run_python_tests() {
    (cd "$ROOT" && "$VENV/bin/python" -m pytest -q)
}

# stage NAME COMMAND...: announces NAME, runs COMMAND and records its wall and CPU time (user +
# sys of every process it ran) for stage_table.
STAGE_ROWS=()
cpu_so_far() {  # the shell's and its finished children's user + sys seconds, from `times`
    awk '{ for (i = 1; i <= NF; i++) { split($i, p, "m"); s += p[1] * 60 + p[2] } } END { printf "%.1f", s }' "$1"
}
stage() {
    local name=$1 times_file=$ROOT/build/.times
    shift
    say "$name"
    mkdir -p "$ROOT/build"
    times >"$times_file"
    local wall0=$SECONDS cpu0
    cpu0=$(cpu_so_far "$times_file")
    "$@"
    times >"$times_file"
    STAGE_ROWS+=("$name|$((SECONDS - wall0))|$(awk -v a="$(cpu_so_far "$times_file")" -v b="$cpu0" 'BEGIN { printf "%.0f", a - b }')")
}
stage_table() {
    local row name wall cpu total_wall=0 total_cpu=0
    printf '\n%-58s %8s %8s\n' "stage" "wall s" "CPU s" >&2
    for row in "${STAGE_ROWS[@]}"; do
        IFS='|' read -r name wall cpu <<<"$row"
        printf '%-58s %8d %8d\n' "$name" "$wall" "$cpu" >&2
        total_wall=$((total_wall + wall)) total_cpu=$((total_cpu + cpu))
    done
    printf '%-58s %8d %8d\n' "total" "$total_wall" "$total_cpu" >&2
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
        trap stage_table EXIT  # the table so far, also when a stage fails
        stage "building and installing the package" setup_python test
        stage "building the C++ tests and the benchmark (Release)" build_cpp_tests
        stage "C++ tests" run_cpp_tests
        stage "Python tests" run_python_tests
        ;;
    sanitize)
        install_debian_packages
        trap stage_table EXIT
        stage "building the C++ tests under ASan + UBSan (-O0)" build_asan_tests
        stage "C++ tests under AddressSanitizer + UndefinedBehaviorSanitizer" run_asan_tests
        stage "building the stress test under TSan (-O0)" build_tsan_tests
        stage "the ensemble stress test under ThreadSanitizer" run_tsan_tests
        ;;
    bench)
        install_debian_packages
        setup_python bench
        say "building the benchmark executable (on the package's core, in $PACKAGE_BUILD)"
        configure_package_build -DGYROSTAT_BENCH=ON
        cmake --build "$PACKAGE_BUILD" --target gyrostat_bench
        "$VENV/bin/python" "$ROOT/bench/work_precision.py" --bench-exe "$PACKAGE_BUILD/gyrostat_bench" "${@:2}"
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
        echo "usage: bash run.sh main [OUT] | test | sanitize | bench | docs" >&2
        exit 2
        ;;
esac
