# FK time against the number of rods (generated ring PCRs); prints a Markdown table.
pcr_add_benchmark(NAME bench_scaling SOURCES ${CMAKE_CURRENT_LIST_DIR}/stress/bench_scaling.cpp)
