# IK objectives, rod stress limits, reduced-space IK, formulation by slenderness (and their CLI options).
pcr_add_test(NAME test_ik_objectives LABELS robots SOURCES ${CMAKE_CURRENT_LIST_DIR}/robots/test_ik_objectives.cpp)
target_compile_definitions(test_ik_objectives PRIVATE PCR_TOOL="$<TARGET_FILE:pcr>")
add_dependencies(test_ik_objectives pcr)
