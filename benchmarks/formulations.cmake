# Condensed against mixed rods over the element count (crossover of the formulation choice); prints a
# Markdown table.
pcr_add_benchmark(NAME bench_formulations SOURCES ${CMAKE_CURRENT_LIST_DIR}/formulations/bench_formulations.cpp)
