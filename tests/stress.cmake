# Stress tests of numerical stability: random FK sweeps, hard single rods and nearly singular platform
# poses (label `stress`), and the fuzzing corpus of the model loader replayed as a regression test
# (label `robots`).
pcr_add_test(NAME test_random_sweeps LABELS stress SOURCES ${CMAKE_CURRENT_LIST_DIR}/stress/test_random_sweeps.cpp
             ${CMAKE_CURRENT_LIST_DIR}/stress/solution_consistency.cpp)
pcr_add_test(NAME test_hard_rods LABELS stress SOURCES ${CMAKE_CURRENT_LIST_DIR}/stress/test_hard_rods.cpp)
pcr_add_test(NAME test_fuzz_corpus LABELS robots SOURCES ${CMAKE_CURRENT_LIST_DIR}/stress/test_fuzz_corpus.cpp)
pcr_add_test(NAME test_singular_poses LABELS stress SOURCES ${CMAKE_CURRENT_LIST_DIR}/stress/test_singular_poses.cpp)
