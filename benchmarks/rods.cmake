pcr_add_benchmark(NAME bench_rods SOURCES ${CMAKE_CURRENT_LIST_DIR}/rods/bench_rods.cpp)
pcr_add_benchmark(NAME bench_rod_verdict SOURCES ${CMAKE_CURRENT_LIST_DIR}/rods/bench_rod_verdict.cpp)
if(TARGET bench_rod_verdict)
  target_include_directories(bench_rod_verdict PRIVATE ${PROJECT_SOURCE_DIR}/tests)  # rods/rod_fixtures.hpp
endif()
