#!/usr/bin/env bash
# terrace quick start, for a fresh Debian 12 machine as root (or with sudo):
#   ./quickstart.sh run       install what running needs, build terrace and paper_tools only, run
#                             the built-in default scene with both engines and print them side by
#                             side (experiments/versus.sh: table in out/versus/versus.txt, figure
#                             out/versus/versus.png)
#   ./quickstart.sh test      install what building and testing need (the test packages while
#                             what `run` builds is compiled), then the test command of CI
#                             (.ci/run): 1. build/: Release with assertions, the tests and
#                             benchmarks and the Python module; 2. the whole test suite (ctest,
#                             the Python module's pytest suite in a step of its own); then the
#                             sanitiser tier (fuzz/README.md): 3. build-asan/: the unit tests and
#                             fuzzers under AddressSanitizer and UBSan (clang); 4. the unit tests
#                             there; 5. each fuzzer for TERRACE_FUZZ_SECONDS (default 30)
#   ./quickstart.sh sanitise  steps 3 to 5 alone
# Arguments after `run` go to `terrace run` instead (e.g. ./quickstart.sh run --set engine=smd).
# Each step says what it does and how long it took; `test` ends with a table of the steps' times.
set -euo pipefail
cd "$(dirname "$0")"

# What building and running terrace needs (gnuplot-nox: versus.sh's figure). git is not needed:
# without it the provenance of a run names its revision "unknown".
run_packages=(build-essential cmake ninja-build pkg-config libeigen3-dev libfftw3-dev
              libboost-program-options-dev libboost-math-dev nlohmann-json3-dev gnuplot-nox)
# What the tests need besides:
# - git: the revision that the build writes into every run's provenance;
# - libgtest-dev, libgmock-dev, libbenchmark-dev: the test suite and benchmarks;
# - python3-ase, python3-gsd: the test suite reads our trajectories with ASE and with gsd
#   (tests/cli/cli_checks.sh ase_read, gsd_read);
# - libopenmpi-dev, openmpi-bin: terrace sweep under mpirun (a build without them sweeps locally
#   and says so; the test suite runs a sweep under mpirun);
# - lammps: Debian's LAMMPS (lmp), which runs the decks of `terrace export lammps` in the test
#   suite (cli_checks.sh lammps_energy: the first frame's U against terrace's); cheap beside the
#   MPI packages above, whose runtime it shares: it adds liblammps0, lammps-data and their own
#   few libraries. Without it that check is skipped, saying so;
# - pybind11-dev, python3-dev, python3-numpy: the Python module terrace (python/), which a
#   build without them leaves out and says so; python3-pytest: its tests (python/tests);
# - ccache: a compiler cache for the two builds (build() below);
# - clang, libclang-rt-14-dev: the sanitiser tier's compiler and its runtimes (libFuzzer among
#   them, which clang only recommends); llvm-14: llvm-symbolizer, so that a sanitiser's report
#   names files and lines.
test_packages=(git libgtest-dev libgmock-dev libbenchmark-dev python3-ase python3-gsd libopenmpi-dev
               openmpi-bin lammps pybind11-dev python3-dev python3-numpy python3-pytest ccache
               clang libclang-rt-14-dev llvm-14)

jobs=$(nproc)
# Debian's interpreter, which python3-numpy and pybind11-dev serve (a python3 of pyenv or a venv
# found first on PATH would lack them).
python=/usr/bin/python3
say() { echo "quickstart: $*" >&2; }

# Recommended packages are left out: for `test` on a fresh Debian 12 they are 120 of 423 packages
# (ImageMagick, Ghostscript, gnupg, LLVM's headers, …), none of which a step here uses
# (docs/PERFORMANCE.md, "The quick start's cost").
# missing PACKAGE... : those of the packages that are not installed, one per line.
missing() {
    local p
    for p in "$@"; do
        dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || echo "$p"
    done
}
install_missing() {
    local missing_now=()
    mapfile -t missing_now < <(missing "$@")
    if [ ${#missing_now[@]} -eq 0 ]; then
        say "the $# packages needed are installed"
        return
    fi
    local sudo="" count
    [ "$(id -u)" -eq 0 ] || sudo="sudo"
    say "missing ${#missing_now[@]} of $# packages: ${missing_now[*]}; reading the package lists"
    $sudo apt-get update -qq
    count=$(apt-get install -s --no-install-recommends "${missing_now[@]}" | grep -c '^Inst ' || true)
    say "installing $count packages with their dependencies (some minutes: progress every 20)"
    $sudo env DEBIAN_FRONTEND=noninteractive apt-get install -y -q --no-install-recommends \
        "${missing_now[@]}" |
        awk -v n="$count" '
            /^Get:/ { g++; if (g % 20 == 0 || g == n) printf "quickstart:   downloaded %d of %d\n", g, n > "/dev/stderr" }
            /^Setting up / { s++; if (s % 20 == 0 || s == n) printf "quickstart:   set up %d of %d\n", s, n > "/dev/stderr" }'
}

# step NAME WHAT COMMAND...: runs one step, saying what it does, and keeps its time for the table
# at the end.
step_names=() step_seconds=()
step() {
    local name=$1 start
    say "[$name] $2"
    shift 2
    start=$SECONDS
    "$@"
    step_names+=("$name")
    step_seconds+=($((SECONDS - start)))
    say "[$name] done in $((SECONDS - start)) s"
}
step_table() {
    local i total=0
    say "times of the steps (s):"
    for i in "${!step_names[@]}"; do
        printf 'quickstart:   %-22s %6d\n' "${step_names[$i]}" "${step_seconds[$i]}" >&2
        total=$((total + step_seconds[i]))
    done
    printf 'quickstart:   %-22s %6d\n' total "$total" >&2
}

# build DIR TARGET... with the given cmake options before `--`: configure, then build the targets
# (none: all).
# A compiler cache where one is installed (Debian's ccache; `test` installs it): a second build of
# the same sources, in this checkout or a clone elsewhere (CCACHE_BASEDIR: paths below the
# checkout count relative to it), takes the objects from the cache. CCACHE_DISABLE=1 builds
# without it. The sloppiness lets it cache what reads a precompiled header (TERRACE_PCH): the
# header's own hash stands for its contents, and no source reads __DATE__ or __TIME__. Under clang
# (the sanitised build) a clone elsewhere misses those: CMake passes the header's path behind
# -Xclang, which the base directory does not reach (docs/PERFORMANCE.md, precompiled headers).
if [ -z "${CMAKE_CXX_COMPILER_LAUNCHER:-}" ] && command -v ccache >/dev/null; then
    export CMAKE_CXX_COMPILER_LAUNCHER=ccache CCACHE_BASEDIR="${CCACHE_BASEDIR:-$PWD}"
    export CCACHE_NOHASHDIR=1
    export CCACHE_SLOPPINESS="${CCACHE_SLOPPINESS:+$CCACHE_SLOPPINESS,}pch_defines,time_macros,include_file_mtime,include_file_ctime"
fi
build() {
    local dir=$1 options=() targets=()
    shift
    while [ $# -gt 0 ] && [ "$1" != -- ]; do
        options+=("$1")
        shift
    done
    [ $# -eq 0 ] || shift
    targets=("$@")
    # Ninja where a new tree is made: it compiles a target's files while the libraries they link
    # are still being built, where make waits for each library first and leaves a core idle
    # (docs/PERFORMANCE.md, "The quick start's cost"). A tree made before keeps its generator.
    if [ ! -f "$dir/CMakeCache.txt" ] && command -v ninja >/dev/null; then
        options=(-G Ninja "${options[@]}")
    fi
    cmake -S . -B "$dir" -DCMAKE_BUILD_TYPE=Release "${options[@]}" >/dev/null
    if [ ${#targets[@]} -gt 0 ]; then
        cmake --build "$dir" -j"$jobs" --target "${targets[@]}"
    else
        cmake --build "$dir" -j"$jobs"
    fi
}

# `run` builds terrace and versus.sh's paper_tools only, and without the profile-guided pass
# (cli/CMakeLists.txt, TERRACE_PROFILE): on two cores its instrumented build and training cost
# minutes, and it saves ~6 % of DMD's CPU time, seconds of the default run (README, quick start).
# TERRACE_PROFILE=on ./quickstart.sh run builds with it, as the paper's timings were.
# The Python tests (python/tests) against the module in build/python. pytest's exit status 5
# (no tests collected) fails the step as any other failure does.
python_tests() {
    if ! compgen -G "build/python/terrace/_terrace*.so" >/dev/null; then
        say "the Python module was not built in build/python (the configure step says why)"
        return 1
    fi
    local status=0
    PYTHONPATH="$PWD/build/python" TERRACE_BUILD="$PWD/build" \
        "$python" -m pytest -q -p no:cacheprovider python/tests || status=$?
    [ "$status" -ne 5 ] || say "pytest collected no tests in python/tests"
    return "$status"
}

build_run() {
    local options=(-DTERRACE_TESTS=OFF -DTERRACE_BENCH=OFF) data="$PWD/build-profile/data"
    case "${TERRACE_PROFILE:-off}" in
    off | OFF | 0 | no)
        step build "building terrace and paper_tools in build/" \
            build build "${options[@]}" -DTERRACE_PROFILE= -DPython3_EXECUTABLE="$python" -- \
            terrace paper_tools
        ;;
    on | ON | 1 | yes)
        # The same events as without the profile (no reassociation), only faster.
        step build-profile "building an instrumented terrace in build-profile/" \
            build build-profile "${options[@]}" -DTERRACE_PROFILE=generate \
            -DTERRACE_PROFILE_DATA="$data" -- terrace
        rm -rf "$data"
        step train "training the profile (experiments/train-profile.sh)" \
            experiments/train-profile.sh build-profile/terrace build-profile/training
        step build "building terrace and paper_tools in build/ with the profile" \
            build build "${options[@]}" -DTERRACE_PROFILE=use \
            -DTERRACE_PROFILE_DATA="$data" -- terrace paper_tools
        ;;
    *)
        say "TERRACE_PROFILE must be on or off (got '$TERRACE_PROFILE')"
        exit 2
        ;;
    esac
}

# The sanitiser tier: a clang build in build-asan with AddressSanitizer and UBSan (undefined
# behaviour fatal) and libFuzzer's coverage, of the unit tests' executables and the fuzzers only:
# not the benchmarks, not the paper's tools, not terrace for the end-to-end tests (label
# end_to_end), which the Release build runs. Of cli's unit tests only those of what a run reads
# and leaves (test_cli_io, with the fuzzers' library terrace_cli_io): the commands' tests need
# the engines' instantiations for every body kind (cli/run_dmd.cpp, run_smd.cpp), which took a
# third of this build's CPU time. At the Release build's -O2: -O1 compiled no faster
# (docs/PERFORMANCE.md). Each test executable runs whole, as one ctest test
# (TERRACE_TESTS_WHOLE), but for those labelled unsanitised (their files say why).
sanitised_build() {
    CXX=clang++ build build-asan -DTERRACE_PROFILE= -DTERRACE_SANITIZE=ON -DTERRACE_FUZZ=ON \
        -DTERRACE_BENCH=OFF -DTERRACE_TESTS=ON -DTERRACE_TESTS_WHOLE=ON \
        -DCMAKE_CXX_FLAGS=-gline-tables-only -- unit_tests fuzzers
}
sanitised_tests() {
    ctest --test-dir build-asan --output-on-failure -j"$jobs" -L unit -LE 'unsanitised|end_to_end'
}
# Each fuzzer runs TERRACE_FUZZ_SECONDS from the committed corpus and regressions, its new inputs
# kept in build-asan/fuzz-corpus, its output in build-asan/fuzz-findings/<target>.log and any
# finding beside it in build-asan/fuzz-findings/<target>/. A fuzzer uses one core, so as many run
# at once as there are cores: on two, the five take three rounds of TERRACE_FUZZ_SECONDS, not five.
fuzz_one() {
    local target=$1 seconds=$2 dirs
    mkdir -p "build-asan/fuzz-corpus/$target" "build-asan/fuzz-findings/$target"
    rm -f "build-asan/fuzz-findings/$target.failed"
    dirs=("build-asan/fuzz-corpus/$target" "fuzz/corpus/$target")
    [ ! -d "fuzz/regressions/$target" ] || dirs+=("fuzz/regressions/$target")
    "build-asan/fuzz/fuzz_$target" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 \
        -print_final_stats=1 -artifact_prefix="build-asan/fuzz-findings/$target/" "${dirs[@]}" \
        >"build-asan/fuzz-findings/$target.log" 2>&1 || touch "build-asan/fuzz-findings/$target.failed"
}
fuzz_all() {
    local seconds="${TERRACE_FUZZ_SECONDS:-30}" target log failed=()
    local targets=(scene sweep restart trajectory csv)
    for target in "${targets[@]}"; do
        while [ "$(jobs -rp | wc -l)" -ge "$jobs" ]; do wait -n || true; done
        say "fuzzing $target for $seconds s"
        fuzz_one "$target" "$seconds" &
    done
    wait
    for target in "${targets[@]}"; do
        log=build-asan/fuzz-findings/$target.log
        if [ -e "build-asan/fuzz-findings/$target.failed" ]; then
            cat "$log" >&2
            say "fuzz_$target failed; its input is in build-asan/fuzz-findings/$target/ (fuzz/README.md)"
            failed+=("$target")
        else
            say "  $target: $(awk '/^stat::number_of_executed_units/ { e = $NF } /^stat::new_units_added/ { n = $NF }
                                 END { printf "%d inputs run, %d new kept", e, n }' "$log")"
        fi
    done
    if [ ${#failed[@]} -gt 0 ]; then
        say "fuzz targets with findings: ${failed[*]}"
        return 1
    fi
}
sanitiser_tier() {
    step sanitised-build "building the unit tests and fuzzers under ASan and UBSan in build-asan/" \
        sanitised_build
    step sanitised-tests "the unit tests under ASan and UBSan" sanitised_tests
    step fuzz "each fuzzer for ${TERRACE_FUZZ_SECONDS:-30} s, $jobs at a time" fuzz_all
}

case "${1:-}" in
run)
    shift
    step install "the packages that building and running need" install_missing "${run_packages[@]}"
    build_run
    if [ $# -gt 0 ]; then exec ./build/terrace run "$@"; fi
    step run "the default scene with DMD and SMD (experiments/versus.sh)" \
        experiments/versus.sh out/versus
    step_table
    ;;
test)
    # The test packages take minutes to download and set up: where some are missing, what `run`
    # builds is compiled meanwhile, and the build of everything then reuses it (the libraries'
    # flags do not depend on what the test packages add). Setting packages up takes CPU too, so
    # on two cores this saved ~40 s of the 167 that the install took alone (docs/PERFORMANCE.md,
    # "The quick start's cost").
    if [ -n "$(missing "${test_packages[@]}")" ]; then
        step install "the packages that building and running need" \
            install_missing "${run_packages[@]}"
        # Its progress lines come between the build's.
        install_missing "${test_packages[@]}" &
        install_pid=$!
        step build-run-part "building terrace and paper_tools in build/ while they install" \
            build build -DTERRACE_PROFILE= -DTERRACE_TESTS=OFF -DTERRACE_BENCH=OFF \
            -DPython3_EXECUTABLE="$python" -- terrace paper_tools
        step install-tests "waiting for the test packages to be installed" wait "$install_pid"
    else
        step install "the packages that building and testing need" \
            install_missing "${run_packages[@]}" "${test_packages[@]}"
    fi
    # No profile-guided pass: it changes the engines' speed only, not what they compute.
    step build "building everything in build/ (Release, assertions on)" \
        build build -DTERRACE_PROFILE= -DTERRACE_TESTS=ON -DTERRACE_BENCH=ON \
        -DPython3_EXECUTABLE="$python"
    # The pytest suite, which ctest holds too (label python), runs in its own step below.
    step tests "the whole test suite" ctest --test-dir build --output-on-failure -j"$jobs" -LE python
    step python-tests "the Python module's tests (pytest, python/tests)" python_tests
    sanitiser_tier
    step_table
    ;;
sanitise)
    step install "the packages that building and testing need" \
        install_missing "${run_packages[@]}" "${test_packages[@]}"
    sanitiser_tier
    step_table
    ;;
*)
    echo "usage: ./quickstart.sh run [terrace run options] | ./quickstart.sh test | ./quickstart.sh sanitise" >&2
    exit 2
    ;;
esac
