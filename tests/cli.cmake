# Result writers (JSON, CSV, VTK, outlines) and the pcr tool run as a program.
pcr_add_test(NAME test_io LABELS robots SOURCES ${CMAKE_CURRENT_LIST_DIR}/cli/test_io.cpp)
pcr_add_test(NAME test_cli LABELS robots SOURCES ${CMAKE_CURRENT_LIST_DIR}/cli/test_cli.cpp)
target_compile_definitions(test_cli PRIVATE PCR_TOOL="$<TARGET_FILE:pcr>")
add_dependencies(test_cli pcr)
