#!/usr/bin/env bash
# README command (2): install, build and run every test (CTest; Boost.Test executables).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
mkdir -p "$root/build"
bash "$root/scripts/build.sh" "$root/build/release"
cd "$root/build/release"
ctest --output-on-failure -j "$(nproc)"
