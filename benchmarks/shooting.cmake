pcr_add_benchmark(NAME bench_shooting SOURCES ${CMAKE_CURRENT_LIST_DIR}/shooting/bench_shooting.cpp)
