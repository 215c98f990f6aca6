# bench_all (issue #7): every method on every scene into one CSV; scripts/bench_report.sh makes the
# PNGs and the Markdown tables from it.
pcr_add_benchmark(NAME bench_all SOURCES ${CMAKE_CURRENT_LIST_DIR}/all/bench_all.cpp
                  ${CMAKE_CURRENT_LIST_DIR}/all/all_recorder.cpp ${CMAKE_CURRENT_LIST_DIR}/all/all_rods.cpp
                  ${CMAKE_CURRENT_LIST_DIR}/all/all_robots.cpp ${CMAKE_CURRENT_LIST_DIR}/all/all_contact.cpp)
# Smoke test (quick R1 sweep, a few seconds), label "bench"; not part of the sanitizer pass.
if(PCR_BUILD_TESTS AND TARGET bench_all)
  add_test(NAME bench_all_smoke COMMAND bash ${CMAKE_CURRENT_LIST_DIR}/all/smoke_test.sh $<TARGET_FILE:bench_all>
                                        ${CMAKE_CURRENT_BINARY_DIR}/bench_all_smoke.csv)
  set_tests_properties(bench_all_smoke PROPERTIES LABELS bench)
endif()
# One bench_all workload in a function of its own, for callgrind profiles (docs/benchmarks.md, Time split).
pcr_add_benchmark(NAME bench_time_split SOURCES ${CMAKE_CURRENT_LIST_DIR}/all/time_split.cpp)
