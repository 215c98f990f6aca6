pcr_add_test(NAME test_rod_convergence LABELS rods SOURCES ${CMAKE_CURRENT_LIST_DIR}/rods/test_convergence.cpp)
