pcr_add_test(NAME test_drawn_rod LABELS rods
             SOURCES ${CMAKE_CURRENT_LIST_DIR}/drawn/test_drawn_rod.cpp
                     ${CMAKE_CURRENT_LIST_DIR}/drawn/test_drawn_references.cpp
                     ${CMAKE_CURRENT_LIST_DIR}/drawn/test_drawn_divergence.cpp)
