pcr_add_test(NAME test_contact_edges LABELS rods robots
             SOURCES ${CMAKE_CURRENT_LIST_DIR}/contact/test_contact_mesh_check.cpp
                     ${CMAKE_CURRENT_LIST_DIR}/contact/test_contact_sharp.cpp
                     ${CMAKE_CURRENT_LIST_DIR}/contact/test_contact_rollers.cpp
                     ${CMAKE_CURRENT_LIST_DIR}/contact/contact_fixtures.cpp)
