#!/usr/bin/env bash
# Installs the dependencies, then configures and builds pcr (Release, warnings as errors).
# usage: [PCR_BENCHMARK_TARGETS=a;b] scripts/build.sh [BUILD_DIR] [extra cmake arguments...]
# (PCR_BENCHMARK_TARGETS: only these benchmark executables; unset: all of them)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build_dir=${1:-"$root/build/release"}
shift || true
bash "$root/scripts/install-deps.sh"
cmake -S "$root" -B "$build_dir" -DCMAKE_BUILD_TYPE=Release -DPCR_WERROR=ON \
  -DPCR_BENCHMARK_TARGETS="${PCR_BENCHMARK_TARGETS:-}" "$@" > "$build_dir.configure.log" 2>&1 ||
  { mkdir -p "$(dirname "$build_dir")"; cat "$build_dir.configure.log"; exit 1; }
cmake --build "$build_dir" -j "$(nproc)"
