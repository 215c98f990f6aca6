# The two contact solvers (semismooth Newton, Ipopt in Scholtes' relaxation) against beam theory and each
# other, with robustness over perturbed cases (docs/benchmarks.md "Contact solvers").
pcr_add_benchmark(NAME bench_contact_methods SOURCES ${CMAKE_CURRENT_LIST_DIR}/contact/bench_contact_methods.cpp)
