# Under the sanitizers the two long reference cases (a cantilever wrapped on a cylinder, a heavy cantilever
# on a plane: 37 of the 45 s there) are left out; the other cases run the same contact rows, semismooth
# solver and Jacobians on smaller problems. Release runs all.
set(contact_args "")
if(PCR_SANITIZE)
  set(contact_args "--run_test=!cantilever_wrapped_on_a_cylinder:!heavy_cantilever_on_a_plane")
endif()
pcr_add_test(NAME test_contact LABELS rods robots ARGS ${contact_args}
             SOURCES ${CMAKE_CURRENT_LIST_DIR}/contact/test_contact_rods.cpp
                     ${CMAKE_CURRENT_LIST_DIR}/contact/test_contact_references.cpp
                     ${CMAKE_CURRENT_LIST_DIR}/contact/test_contact_models.cpp
                     ${CMAKE_CURRENT_LIST_DIR}/contact/contact_fixtures.cpp)
# The complementarity function (rods/src/contact/edge_contact.hpp, internal) is tested directly.
if(TARGET test_contact)
  target_include_directories(test_contact PRIVATE ${PROJECT_SOURCE_DIR}/rods/src)
endif()
