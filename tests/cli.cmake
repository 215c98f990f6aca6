# Result writers (JSON, CSV, VTK, outlines) and the pcr tool run as a program.
pcr_add_test(NAME test_io LABELS robots SOURCES ${CMAKE_CURRENT_LIST_DIR}/cli/test_io.cpp)
# Under the sanitizers the out-of-memory case is left out: it runs the tool in a 600 MB address space
# (ulimit -v), and AddressSanitizer reserves terabytes of shadow address space at start-up, so the
# sanitized tool aborts before main. Release runs it.
set(cli_args "")
if(PCR_SANITIZE)
  set(cli_args "--run_test=!running_out_of_memory_ends_with_exit_code_4_and_a_message")
endif()
pcr_add_test(NAME test_cli LABELS robots SOURCES ${CMAKE_CURRENT_LIST_DIR}/cli/test_cli.cpp ARGS ${cli_args})
target_compile_definitions(test_cli PRIVATE PCR_TOOL="$<TARGET_FILE:pcr>")
add_dependencies(test_cli pcr)
