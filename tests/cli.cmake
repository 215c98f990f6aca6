# Result writers (JSON, CSV, VTK, outlines), the workspace sampler and the pcr tool run as a program.
pcr_add_test(NAME test_io LABELS robots SOURCES ${CMAKE_CURRENT_LIST_DIR}/cli/test_io.cpp
             ${CMAKE_CURRENT_LIST_DIR}/cli/test_io_obstacles.cpp)
pcr_add_test(NAME test_workspace LABELS robots SOURCES ${CMAKE_CURRENT_LIST_DIR}/cli/test_workspace.cpp)
# Under the sanitizers the out-of-memory case is left out: it runs the tool in a 600 MB address space
# (ulimit -v), and AddressSanitizer reserves terabytes of shadow address space at start-up, so the
# sanitized tool aborts before main. Release runs it.
set(cli_args "")
if(PCR_SANITIZE)
  set(cli_args "--run_test=!running_out_of_memory_ends_with_exit_code_4_and_a_message")
endif()
pcr_add_test(NAME test_cli LABELS robots SOURCES ${CMAKE_CURRENT_LIST_DIR}/cli/test_cli.cpp ARGS ${cli_args})
pcr_add_test(NAME test_cli_tools LABELS robots SOURCES ${CMAKE_CURRENT_LIST_DIR}/cli/test_cli_tools.cpp
             ${CMAKE_CURRENT_LIST_DIR}/cli/test_cli_targets.cpp)
foreach(cli_test test_cli test_cli_tools)
  target_compile_definitions(${cli_test} PRIVATE PCR_TOOL="$<TARGET_FILE:pcr>")
  add_dependencies(${cli_test} pcr)
endforeach()
