# Paths through folds: pseudo-arclength continuation of FK along input paths, folds, snap-through and
# bifurcations (path_through_folds.hpp), checked against independent methods (discrete energy model of
# tests/stability, displacement control by IK).
pcr_add_test(NAME test_paths_through_folds LABELS robots
             SOURCES ${CMAKE_CURRENT_LIST_DIR}/paths/test_paths_through_folds.cpp
                     ${CMAKE_CURRENT_LIST_DIR}/stability/robot_discrete.cpp
                     ${CMAKE_CURRENT_LIST_DIR}/stability/discrete_rods.cpp)
