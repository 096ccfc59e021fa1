#!/usr/bin/env bash
# terrace quick start, for a fresh Debian 12 machine as root (or with sudo):
#   ./quickstart.sh run    install what is missing, build, run the built-in default scene with
#                          both engines and print them side by side (experiments/versus.sh:
#                          table in out/versus/versus.txt, figure out/versus/versus.png)
#   ./quickstart.sh test   install what is missing, build, run the whole test suite
#   ./quickstart.sh sanitise  also install clang, then the sanitiser tier (fuzz/README.md): the
#                          unit tests under ASan and UBSan, and each fuzzer for a while
#                          (TERRACE_FUZZ_SECONDS, default 30); not yet part of `test`
# Arguments after `run` go to `terrace run` instead (e.g. ./quickstart.sh run --set engine=smd).
set -euo pipefail
cd "$(dirname "$0")"

# python3-ase: the test suite reads our trajectories with ASE (tests/cli/cli_checks.sh ase_read).
# libopenmpi-dev, openmpi-bin: terrace sweep under mpirun (optional for a build of your own: without
# them terrace builds and sweeps locally, and says so; the test suite runs a sweep under mpirun).
packages=(build-essential cmake pkg-config git libeigen3-dev libfftw3-dev
          libboost-program-options-dev libboost-math-dev nlohmann-json3-dev
          libgtest-dev libgmock-dev libbenchmark-dev gnuplot-nox python3-ase
          libopenmpi-dev openmpi-bin)
# clang, libclang-rt-14-dev: the sanitiser tier's build, whose fuzzers need libFuzzer (clang's
# runtime libraries, which clang only recommends).
sanitiser_packages=(clang libclang-rt-14-dev)

install_missing() {
    local missing=()
    for p in "${packages[@]}"; do
        dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" ||
            missing+=("$p")
    done
    if [ ${#missing[@]} -gt 0 ]; then
        echo "quickstart: installing ${missing[*]}" >&2
        local sudo=""
        [ "$(id -u)" -eq 0 ] || sudo="sudo"
        $sudo apt-get update -qq
        DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq "${missing[@]}" >/dev/null
    fi
}

# Two passes: an instrumented terrace runs a short training (experiments/train-profile.sh, a few
# seconds), then the build proper compiles the engines with the profile it recorded
# (cli/CMakeLists.txt, TERRACE_PROFILE; the same events, ~6 % less CPU time for DMD).
# TERRACE_PROFILE=off skips the first pass, as does a compiler other than GCC.
build() {
    local jobs data="$PWD/build-profile/data" profile=on
    jobs=$(nproc)
    case "${TERRACE_PROFILE:-on}" in
    on | ON | 1 | yes) ;;
    off | OFF | 0 | no) profile=off ;;
    *)
        echo "quickstart: TERRACE_PROFILE must be on or off (got '$TERRACE_PROFILE')" >&2
        exit 2
        ;;
    esac
    # GCC names the Free Software Foundation in its version text (g++, c++, g++-12, …); clang does not.
    if ! "${CXX:-c++}" --version 2>/dev/null | grep -q 'Free Software Foundation'; then
        profile=off
    fi
    if [ "$profile" = off ]; then
        cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DTERRACE_PROFILE= >/dev/null
    else
        cmake -S . -B build-profile -DCMAKE_BUILD_TYPE=Release -DTERRACE_TESTS=OFF \
            -DTERRACE_BENCH=OFF -DTERRACE_PROFILE=generate -DTERRACE_PROFILE_DATA="$data" >/dev/null
        cmake --build build-profile -j"$jobs" --target terrace
        rm -rf "$data"
        experiments/train-profile.sh build-profile/terrace build-profile/training
        cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DTERRACE_PROFILE=use \
            -DTERRACE_PROFILE_DATA="$data" >/dev/null
    fi
    cmake --build build -j"$jobs"
}

# The sanitiser tier: one clang build in build-asan with AddressSanitizer and UBSan (undefined
# behaviour fatal) and libFuzzer's coverage, no profile and no benchmarks. Its unit tests run
# but for those labelled unsanitised (tests/cli/CMakeLists.txt says why each is); then each
# fuzzer runs TERRACE_FUZZ_SECONDS from the committed corpus, its new inputs kept in
# build-asan/fuzz-corpus and any finding in build-asan/fuzz-findings.
sanitised() {
    local jobs seconds="${TERRACE_FUZZ_SECONDS:-30}"
    jobs=$(nproc)
    CXX=clang++ cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=Release -DTERRACE_PROFILE= \
        -DTERRACE_SANITIZE=ON -DTERRACE_FUZZ=ON -DTERRACE_BENCH=OFF \
        -DCMAKE_CXX_FLAGS=-gline-tables-only >/dev/null
    cmake --build build-asan -j"$jobs"
    ctest --test-dir build-asan --output-on-failure -j"$jobs" -L unit -LE unsanitised
    local target dirs
    for target in scene sweep restart trajectory csv; do
        mkdir -p "build-asan/fuzz-corpus/$target" "build-asan/fuzz-findings/$target"
        dirs=("build-asan/fuzz-corpus/$target" "fuzz/corpus/$target")
        [ ! -d "fuzz/regressions/$target" ] || dirs+=("fuzz/regressions/$target")
        echo "quickstart: fuzzing $target for ${seconds} s" >&2
        "build-asan/fuzz/fuzz_$target" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 \
            -print_final_stats=1 -artifact_prefix="build-asan/fuzz-findings/$target/" "${dirs[@]}"
    done
}

case "${1:-}" in
run)
    shift
    install_missing
    build
    if [ $# -gt 0 ]; then exec ./build/terrace run "$@"; fi
    exec experiments/versus.sh out/versus
    ;;
test)
    install_missing
    build
    exec ctest --test-dir build --output-on-failure -j"$(nproc)"
    ;;
sanitise)
    packages+=("${sanitiser_packages[@]}")
    install_missing
    sanitised
    ;;
*)
    echo "usage: ./quickstart.sh run [terrace run options] | ./quickstart.sh test | ./quickstart.sh sanitise" >&2
    exit 2
    ;;
esac
