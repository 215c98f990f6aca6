pcr_add_test(NAME test_contact_ipopt LABELS rods
             SOURCES ${CMAKE_CURRENT_LIST_DIR}/contact/test_contact_ipopt.cpp
                     ${CMAKE_CURRENT_LIST_DIR}/contact/contact_fixtures.cpp)
