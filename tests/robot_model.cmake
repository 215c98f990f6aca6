pcr_add_test(NAME test_robot_model LABELS robots SOURCES ${CMAKE_CURRENT_LIST_DIR}/robots/test_robot_model.cpp)
