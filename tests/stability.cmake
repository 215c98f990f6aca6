pcr_add_test(NAME test_stability_verdict LABELS rods robots
             SOURCES ${CMAKE_CURRENT_LIST_DIR}/stability/test_rod_verdict.cpp
                     ${CMAKE_CURRENT_LIST_DIR}/stability/test_robot_verdict.cpp
                     ${CMAKE_CURRENT_LIST_DIR}/stability/test_passive_joint_verdict.cpp
                     ${CMAKE_CURRENT_LIST_DIR}/stability/test_energy_fallback.cpp
                     ${CMAKE_CURRENT_LIST_DIR}/stability/test_energy_fallback_contact.cpp
                     ${CMAKE_CURRENT_LIST_DIR}/stability/test_contact_verdict.cpp
                     $<TARGET_OBJECTS:pcr_test_discrete>)
# The energy-minimisation FK strategy (robots/src/kinematics/energy_fallback.hpp, internal) is tested
# directly: its internal headers (the target is absent when PCR_SKIP_TESTS leaves it out).
if(TARGET test_stability_verdict)
  target_include_directories(test_stability_verdict PRIVATE ${PROJECT_SOURCE_DIR}/robots/src)
endif()
