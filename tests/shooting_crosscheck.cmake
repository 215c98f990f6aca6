pcr_add_test(NAME test_shooting_crosscheck LABELS rods
             SOURCES ${CMAKE_CURRENT_LIST_DIR}/shooting_crosscheck/test_shooting_crosscheck.cpp
                     ${CMAKE_CURRENT_LIST_DIR}/shooting_crosscheck/shooting_centerline.cpp)
