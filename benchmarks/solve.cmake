pcr_add_benchmark(NAME bench_solve SOURCES ${CMAKE_CURRENT_LIST_DIR}/solve/bench_solve.cpp)
