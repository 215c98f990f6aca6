#!/usr/bin/env bash
# README command (2): install, build and run every test (CTest; Boost.Test executables), twice:
#  1. Release (-Werror) in build/release: the whole suite, without the benchmarks;
#  2. ASan + UBSan (PCR_SANITIZE, -Og, no debug info, no benchmarks, no Python) in build/sanitize: the
#     suite except the executables in sanitizer_skip below (not even built there) and the install test,
#     to keep CI under 20 minutes on 2 cores; the test executables' own code is linked with the sanitizers
#     but not instrumented (cmake/PcrCompileOptions.cmake). -Og rather than -O1: condensed_forms.cpp
#     compiles in 66 s against 126 s. -g0: 8 % less compile time than line tables; reports still name the
#     functions (UBSan's also file:line); to read an ASan report with lines, rebuild with -g1.
# Both builds use Ninja and precompiled headers (scripts/build.sh, PCR_PRECOMPILE_HEADERS).
set -euo pipefail
# Elapsed time of each stage in the log (CI budget: 20 minutes for the whole of .ci/run).
stage() { echo "test.sh: $1 at $((SECONDS / 60)) min $((SECONDS % 60)) s"; }
root=$(cd "$(dirname "$0")/.." && pwd)
mkdir -p "$root/build"
bash "$root/scripts/install-deps.sh"
stage "dependencies installed"
# No benchmarks (their smoke test, bench_all_smoke, runs in a build with -DPCR_BUILD_BENCHMARKS=ON:
# docs/benchmarks.md); building bench_all took about 1.5 of the 20 minutes CI may take.
# Test executables at -Og (the libraries keep -O3): a test source compiles in about 20 % less time than at
# -O1 (test_structured_lu.cpp: 12.9 s against 16.1 s), their work runs in the libraries.
# -Wno-maybe-uninitialized: GCC's false positives inside Eigen at low optimisation levels.
bash "$root/scripts/build.sh" "$root/build/release" -DPCR_BUILD_BENCHMARKS=OFF \
  "-DPCR_TEST_CXX_FLAGS=-Og -Wno-maybe-uninitialized"
stage "Release build done"
(cd "$root/build/release" && ctest --output-on-failure -j "$(nproc)")
stage "Release tests done"

# Left out of the sanitizer pass (not even built, to keep CI under 20 minutes; the libraries are most
# of its build time): studies of code the other tests cover, and unit tests of code that the sanitized
# end-to-end tests run too (the pcr tool through test_cli/test_cli_tools - fk, ik with objectives,
# path, workspace, --stability -, test_kinematics, test_joints, test_concurrent_solves, test_workspace,
# test_collocation_rod, test_structured_lu, the loader's corpus and checks).
sanitizer_skip="test_hard_rods;test_rod_convergence;test_shooting_crosscheck;test_singular_poses"
sanitizer_skip+=";test_stability_verdict;test_shooting;test_six_rus;test_splines;test_joint_crosscheck"
sanitizer_skip+=";test_problem;test_newton;test_ik_objectives;test_shooting_robots;test_rod_validation"
sanitizer_skip+=";test_ipopt;test_math;test_path_predictor;test_stability_monitor;test_sparse_lu"
sanitizer_skip+=";test_reference_curve;test_rod_stability;test_input_continuation;test_joint_ends"
sanitizer_skip+=";test_paths_through_folds"  # the fold code runs sanitized through test_cli (pcr path --folds)
sanitizer_skip+=";test_contact_edges"  # edges, points, rollers: Release only (test_contact runs the contact rows)
sanitizer_skip+=";test_contact_adhesion"  # adhesive rollers: Release only (as test_contact_edges)
sanitizer_skip+=";test_contact_ipopt;test_moving_obstacles"  # Ipopt as test_ipopt; moving obstacles: Release only
sanitizer_skip+=";test_robot_model"  # the loader runs sanitized through test_fuzz_corpus, test_model_file_checks
sanitizer_skip+=";test_random_sweeps"  # the FK strategies run sanitized through test_kinematics and test_cli
sanitizer_skip+=";test_drawn_rod;test_shooting_joints"  # drawn rods, robot shooting with joints: Release only (CI time)
bash "$root/scripts/build.sh" "$root/build/sanitize" -DPCR_SANITIZE=ON -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-Og -g0" -DPCR_BUILD_BENCHMARKS=OFF -DPCR_BUILD_PYTHON=OFF \
  -DPCR_SKIP_TESTS="$sanitizer_skip"
stage "sanitizer build done"
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1:strict_string_checks=1
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
cd "$root/build/sanitize"
ctest --output-on-failure -j "$(nproc)" -LE "stress|install|bench"
stage "sanitizer tests done"
