pcr_add_test(NAME test_contact_adhesion LABELS rods robots
             SOURCES ${CMAKE_CURRENT_LIST_DIR}/contact/test_contact_adhesion.cpp
                     ${CMAKE_CURRENT_LIST_DIR}/contact/contact_fixtures.cpp)
