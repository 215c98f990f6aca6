#!/usr/bin/env bash
# README command (1): install, build, and run the main job; results go to out/.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
mkdir -p "$root/build" "$root/out"
bash "$root/scripts/build.sh" "$root/build/release"
"$root/build/release/robots/pcr" demo --out "$root/out"
