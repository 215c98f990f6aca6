pcr_add_benchmark(NAME bench_rods SOURCES ${CMAKE_CURRENT_LIST_DIR}/rods/bench_rods.cpp)
