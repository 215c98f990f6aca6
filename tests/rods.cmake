pcr_add_test(NAME test_collocation_rod LABELS rods SOURCES ${CMAKE_CURRENT_LIST_DIR}/rods/test_collocation_rod.cpp
                                                        ${CMAKE_CURRENT_LIST_DIR}/rods/test_rod_start.cpp
                                                        ${CMAKE_CURRENT_LIST_DIR}/rods/test_condensed_form.cpp
                                                        ${CMAKE_CURRENT_LIST_DIR}/rods/test_rod_continuation.cpp)
pcr_add_test(NAME test_rod_validation LABELS rods SOURCES ${CMAKE_CURRENT_LIST_DIR}/rods/test_rod_validation.cpp)
pcr_add_test(NAME test_reference_curve LABELS rods SOURCES ${CMAKE_CURRENT_LIST_DIR}/rods/test_reference_curve.cpp)
pcr_add_test(NAME test_rod_stability LABELS rods SOURCES ${CMAKE_CURRENT_LIST_DIR}/rods/test_rod_stability.cpp)
