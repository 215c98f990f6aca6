pcr_add_test(NAME test_shooting_robots LABELS robots SOURCES ${CMAKE_CURRENT_LIST_DIR}/shooting_robots/test_shooting_robots.cpp)
pcr_add_test(NAME test_shooting_joints LABELS robots
             SOURCES ${CMAKE_CURRENT_LIST_DIR}/shooting_robots/test_shooting_joints.cpp
                     ${CMAKE_CURRENT_LIST_DIR}/shooting_robots/test_shooting_pinned_robots.cpp
                     ${CMAKE_CURRENT_LIST_DIR}/shooting_robots/joint_robots.cpp)
# Collocation against shooting on the robots with universal / revolute ends and passive joints.
pcr_add_test(NAME test_joint_crosscheck LABELS robots
             SOURCES ${CMAKE_CURRENT_LIST_DIR}/shooting_robots/test_joint_crosscheck.cpp)
