pcr_add_test(NAME test_robot_model LABELS robots SOURCES ${CMAKE_CURRENT_LIST_DIR}/robots/test_robot_model.cpp
                                                      ${CMAKE_CURRENT_LIST_DIR}/robots/test_model_rejections.cpp)
pcr_add_test(NAME test_model_file_checks LABELS robots SOURCES ${CMAKE_CURRENT_LIST_DIR}/robots/test_model_file_checks.cpp)
