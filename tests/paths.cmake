# Paths through folds: pseudo-arclength continuation of FK along input paths, folds, snap-through and
# bifurcations (path_through_folds.hpp), checked against independent methods (discrete energy model of
# tests/stability, displacement control by IK).
# Under the sanitizers only the rod cases run (the continuation, fold and bifurcation code; the robot
# cases take 7 of the 9 s in Release and run the same code on larger systems); Release runs all.
set(paths_args "")
if(PCR_SANITIZE)
  set(paths_args "--run_test=fed_column_bifurcations_at_the_euler_lengths,arch_fold_located_and_counted")
endif()
pcr_add_test(NAME test_paths_through_folds LABELS robots ARGS ${paths_args}
             SOURCES ${CMAKE_CURRENT_LIST_DIR}/paths/test_paths_through_folds.cpp
                     ${CMAKE_CURRENT_LIST_DIR}/paths/test_snaps_past_folds.cpp
                     $<TARGET_OBJECTS:pcr_test_discrete>)
# The damped motion of the snap (robots/src/kinematics/pseudo_transient_snap.hpp, internal) is tested
# directly: its internal header (the target is absent when PCR_SKIP_TESTS leaves it out).
if(TARGET test_paths_through_folds)
  target_include_directories(test_paths_through_folds PRIVATE ${PROJECT_SOURCE_DIR}/robots/src)
endif()
