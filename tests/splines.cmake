pcr_add_test(NAME test_splines LABELS core
             SOURCES ${CMAKE_CURRENT_LIST_DIR}/splines/test_knot_vector.cpp
                     ${CMAKE_CURRENT_LIST_DIR}/splines/test_basis.cpp
                     ${CMAKE_CURRENT_LIST_DIR}/splines/test_spline_curve.cpp)
