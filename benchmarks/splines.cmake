pcr_add_benchmark(NAME bench_splines SOURCES ${CMAKE_CURRENT_LIST_DIR}/splines/bench_basis.cpp)
