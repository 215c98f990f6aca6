pcr_add_benchmark(NAME bench_rods SOURCES ${CMAKE_CURRENT_LIST_DIR}/rods/bench_rods.cpp)
# The analytic references (arc, helix, elliptic-integral elastica) are the rod tests' fixtures.
target_include_directories(bench_rods PRIVATE ${PROJECT_SOURCE_DIR}/tests)
