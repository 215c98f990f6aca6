pcr_add_test(NAME test_math LABELS core SOURCES ${CMAKE_CURRENT_LIST_DIR}/core/test_math.cpp)
