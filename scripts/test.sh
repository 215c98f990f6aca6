#!/usr/bin/env bash
# README command (2): install, build and run every test (CTest; Boost.Test executables), twice:
#  1. Release (-Werror) in build/release: the whole suite;
#  2. ASan + UBSan (PCR_SANITIZE, -O1, line tables, no benchmarks) in build/sanitize: the whole suite
#     except the `stress` label (test_hard_rods runs in the Release pass only; the random sweep runs
#     shortened, -- --solves=3), the install test and the bench smoke test (benchmarks are not built
#     there), to keep CI under 20 minutes.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
mkdir -p "$root/build"
bash "$root/scripts/build.sh" "$root/build/release"
(cd "$root/build/release" && ctest --output-on-failure -j "$(nproc)")

bash "$root/scripts/build.sh" "$root/build/sanitize" -DPCR_SANITIZE=ON -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1" -DPCR_BUILD_BENCHMARKS=OFF
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1:strict_string_checks=1
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
cd "$root/build/sanitize"
ctest --output-on-failure -j "$(nproc)" -LE "stress|install|bench"
./tests/test_random_sweeps --log_level=warning -- --solves=3
