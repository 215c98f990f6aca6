# Result writers (JSON, CSV, VTK, outlines), the workspace sampler and the pcr tool run as a program.
pcr_add_test(NAME test_io LABELS robots SOURCES ${CMAKE_CURRENT_LIST_DIR}/cli/test_io.cpp)
pcr_add_test(NAME test_workspace LABELS robots SOURCES ${CMAKE_CURRENT_LIST_DIR}/cli/test_workspace.cpp)
pcr_add_test(NAME test_cli LABELS robots SOURCES ${CMAKE_CURRENT_LIST_DIR}/cli/test_cli.cpp)
pcr_add_test(NAME test_cli_tools LABELS robots SOURCES ${CMAKE_CURRENT_LIST_DIR}/cli/test_cli_tools.cpp)
foreach(cli_test test_cli test_cli_tools)
  target_compile_definitions(${cli_test} PRIVATE PCR_TOOL="$<TARGET_FILE:pcr>")
  add_dependencies(${cli_test} pcr)
endforeach()
