#!/usr/bin/env bash
# Installs the dependencies, then configures and builds pcr (Release, warnings as errors).
# usage: [PCR_BENCHMARK_TARGETS=a;b] scripts/build.sh [BUILD_DIR] [extra cmake arguments...]
# (PCR_BENCHMARK_TARGETS: only these benchmark executables; unset: all of them)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build_dir=${1:-"$root/build/release"}
shift || true
bash "$root/scripts/install-deps.sh"
# Ninja (it compiles the sources of several targets at once, where make finishes one library before the
# next starts); a build directory configured earlier keeps its generator.
generator=()
[ -f "$build_dir/CMakeCache.txt" ] || generator=(-G Ninja)
cmake -S "$root" -B "$build_dir" "${generator[@]}" -DCMAKE_BUILD_TYPE=Release -DPCR_WERROR=ON \
  -DPCR_BENCHMARK_TARGETS="${PCR_BENCHMARK_TARGETS:-}" "$@" > "$build_dir.configure.log" 2>&1 ||
  { mkdir -p "$(dirname "$build_dir")"; cat "$build_dir.configure.log"; exit 1; }
cmake --build "$build_dir" -j "$(nproc)"
