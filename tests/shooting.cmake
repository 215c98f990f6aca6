pcr_add_test(NAME test_shooting LABELS rods SOURCES ${CMAKE_CURRENT_LIST_DIR}/shooting/test_shooting.cpp)
