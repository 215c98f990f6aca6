# The README's code blocks, run as written: the tour with the pcr tool, then cmake --install into a
# prefix and the C++ example built against it and run on an installed model; then the C++ blocks of
# docs/api.md and docs/paths_through_folds.md built as one program per page against the install and run
# (label install).
add_test(NAME test_install_readme
         COMMAND ${CMAKE_COMMAND} -DBUILD_DIR=${PROJECT_BINARY_DIR} -DSOURCE_DIR=${PROJECT_SOURCE_DIR}
                 -DWORK=${CMAKE_CURRENT_BINARY_DIR}/install_readme -P ${CMAKE_CURRENT_LIST_DIR}/install/run_readme_blocks.cmake)
set_tests_properties(test_install_readme PROPERTIES LABELS install TIMEOUT 600)
