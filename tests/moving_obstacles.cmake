# Obstacles on links that actuated joints move (docs/contact.md, "Obstacles on moving links").
pcr_add_test(NAME test_moving_obstacles LABELS robots
             SOURCES ${CMAKE_CURRENT_LIST_DIR}/robots/test_moving_obstacles.cpp)
