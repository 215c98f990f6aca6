# Single-rod shooting: one executable of several files (shooting/shooting_fixtures.hpp: shared set-up).
pcr_add_test(NAME test_shooting LABELS rods
             SOURCES ${CMAKE_CURRENT_LIST_DIR}/shooting/test_shooting.cpp
                     ${CMAKE_CURRENT_LIST_DIR}/shooting/test_shooting_pairings.cpp
                     ${CMAKE_CURRENT_LIST_DIR}/shooting/test_shooting_joint_ends.cpp
                     ${CMAKE_CURRENT_LIST_DIR}/shooting/test_shooting_integration.cpp)
