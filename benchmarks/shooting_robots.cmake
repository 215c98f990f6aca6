pcr_add_benchmark(NAME bench_shooting_robots SOURCES ${CMAKE_CURRENT_LIST_DIR}/shooting/bench_shooting_robots.cpp)
