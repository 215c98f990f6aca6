pcr_add_test(NAME test_contact LABELS rods robots
             SOURCES ${CMAKE_CURRENT_LIST_DIR}/contact/test_contact_rods.cpp
                     ${CMAKE_CURRENT_LIST_DIR}/contact/test_contact_references.cpp
                     ${CMAKE_CURRENT_LIST_DIR}/contact/test_contact_models.cpp
                     ${CMAKE_CURRENT_LIST_DIR}/contact/contact_fixtures.cpp)
