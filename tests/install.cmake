# find_package(pcr) from the install tree: a downstream project builds and runs (label install).
add_test(NAME test_install_downstream
         COMMAND ${CMAKE_COMMAND} -DBUILD_DIR=${PROJECT_BINARY_DIR} -DWORK=${CMAKE_CURRENT_BINARY_DIR}/downstream
                 -DDOWNSTREAM=${CMAKE_CURRENT_LIST_DIR}/install/downstream
                 -DMODEL=${PROJECT_SOURCE_DIR}/models/cantilever.urdf -P ${CMAKE_CURRENT_LIST_DIR}/install/run_downstream.cmake)
set_tests_properties(test_install_downstream PROPERTIES LABELS install TIMEOUT 600)
