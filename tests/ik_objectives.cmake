# IK objectives, rod stress limits, reduced-space IK, formulation by slenderness (and their CLI options).
# Under the sanitizers (13x slower) two cases are left out: effort_and_energy_optima_beat_nearby_feasible_points
# alone took 125 of the executable's 220 s there (projections onto the target that need input
# continuation, 8 s in Release), and its code paths (reduced IK, FK, input Jacobian) run in the other
# cases too; infeasible_stress_limit_is_reported (2 s in Release) is the same solve as the unreachable
# stress limit of cli_objective_and_stress_options, which runs it through the sanitized pcr tool.
# Release runs both.
set(ik_objectives_args "")
if(PCR_SANITIZE)
  set(ik_objectives_args
      "--run_test=!effort_and_energy_optima_beat_nearby_feasible_points,infeasible_stress_limit_is_reported")
endif()
pcr_add_test(NAME test_ik_objectives LABELS robots SOURCES ${CMAKE_CURRENT_LIST_DIR}/robots/test_ik_objectives.cpp
             ${CMAKE_CURRENT_LIST_DIR}/robots/test_formulation_choice.cpp
             ${CMAKE_CURRENT_LIST_DIR}/robots/test_ik_constraints.cpp
             ARGS ${ik_objectives_args})
if(TARGET test_ik_objectives)  # not in PCR_SKIP_TESTS
  target_compile_definitions(test_ik_objectives PRIVATE PCR_TOOL="$<TARGET_FILE:pcr>")
  add_dependencies(test_ik_objectives pcr)
endif()
