pcr_add_test(NAME test_ik_objectives LABELS robots SOURCES ${CMAKE_CURRENT_LIST_DIR}/robots/test_ik_objectives.cpp)
