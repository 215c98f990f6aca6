pcr_add_benchmark(NAME bench_robots SOURCES ${CMAKE_CURRENT_LIST_DIR}/robots/bench_robots.cpp
                  ${CMAKE_CURRENT_LIST_DIR}/robots/six_rus_rows.cpp)
