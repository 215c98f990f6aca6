#!/usr/bin/env bash
# Fuzzes the model loader (parse_robot_model) with libFuzzer under ASan + UBSan.
# usage: scripts/fuzz.sh [SECONDS=60] [extra libFuzzer arguments...]
# Separate clang build in build/fuzz (libraries with -fsanitize=fuzzer-no-link,address,undefined, the
# target with -fsanitize=fuzzer). Seed corpus: models/*.urdf and tests/data/fuzz_corpus/* (copied to
# build/fuzz/corpus, which grows). Crashes, leaks and escaping non-InputError exceptions are written to
# build/fuzz/artifacts/; keep the interesting ones in tests/data/fuzz_corpus/ (replayed by
# test_fuzz_corpus).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
seconds=${1:-60}
shift || true
PCR_EXTRA_PACKAGES="clang libclang-rt-14-dev" bash "$root/scripts/install-deps.sh"
build="$root/build/fuzz"
mkdir -p "$build/corpus" "$build/artifacts"
flags="-g -O1 -fno-omit-frame-pointer -fsanitize=fuzzer-no-link,address,undefined -fno-sanitize-recover=undefined"
cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_COMPILER=clang++ \
  -DCMAKE_CXX_FLAGS="$flags" -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=address,undefined" \
  -DPCR_BUILD_TESTS=OFF -DPCR_BUILD_BENCHMARKS=OFF -DPCR_BUILD_FUZZERS=ON > "$build.configure.log" 2>&1 ||
  { cat "$build.configure.log"; exit 1; }
cmake --build "$build" -j "$(nproc)" --target fuzz_model_loader
cp "$root"/models/*.urdf "$root"/tests/data/fuzz_corpus/* "$build/corpus/"
cd "$build"
# -rss_limit_mb: ASan's shadow memory; -max_len: the largest model file is ~5 kB.
./fuzz/fuzz_model_loader corpus -dict="$root/fuzz/model_loader.dict" -max_total_time="$seconds" \
  -max_len=16384 -rss_limit_mb=4096 -artifact_prefix=artifacts/ -print_final_stats=1 "$@"
