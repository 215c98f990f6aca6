pcr_add_test(NAME test_stability_verdict LABELS rods robots
             SOURCES ${CMAKE_CURRENT_LIST_DIR}/stability/test_rod_verdict.cpp
                     ${CMAKE_CURRENT_LIST_DIR}/stability/test_robot_verdict.cpp
                     ${CMAKE_CURRENT_LIST_DIR}/stability/test_passive_joint_verdict.cpp
                     ${CMAKE_CURRENT_LIST_DIR}/stability/robot_discrete.cpp
                     ${CMAKE_CURRENT_LIST_DIR}/stability/discrete_rods.cpp)
