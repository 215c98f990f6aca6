pcr_add_test(NAME test_problem LABELS core SOURCES ${CMAKE_CURRENT_LIST_DIR}/solve/test_problem.cpp
             ${CMAKE_CURRENT_LIST_DIR}/solve/test_problem_structure.cpp ${CMAKE_CURRENT_LIST_DIR}/solve/allocation_counter.cpp)
pcr_add_test(NAME test_newton LABELS core SOURCES ${CMAKE_CURRENT_LIST_DIR}/solve/test_newton.cpp
             ${CMAKE_CURRENT_LIST_DIR}/solve/test_newton_loop.cpp)
pcr_add_test(NAME test_ipopt LABELS core SOURCES ${CMAKE_CURRENT_LIST_DIR}/solve/test_ipopt.cpp)
pcr_add_test(NAME test_sparse_lu LABELS core SOURCES ${CMAKE_CURRENT_LIST_DIR}/solve/test_sparse_lu.cpp)
pcr_add_test(NAME test_structured_lu LABELS core SOURCES ${CMAKE_CURRENT_LIST_DIR}/solve/test_structured_lu.cpp)
pcr_add_test(NAME test_band_ordering LABELS core SOURCES ${CMAKE_CURRENT_LIST_DIR}/solve/test_band_ordering.cpp)
if(TARGET test_band_ordering)  # the ordering is internal to pcr_core: its header from the sources
  target_include_directories(test_band_ordering PRIVATE ${PROJECT_SOURCE_DIR}/libpcr/src)
endif()
