# Runs the code blocks of README.md as written (cmake -P script run by CTest, label install):
#  1. the blocks between "<!-- readme-block: NAME -->" and "<!-- readme-block-end -->" are extracted;
#  2. in WORK/root, where build/release is BUILD_DIR and models/ the source models, with
#     HOME = WORK/home: tour.sh runs with bash (the pcr tool on shipped models), example.cpp and
#     CMakeLists.txt go to example/, and install.sh runs with bash (cmake --install into
#     $HOME/opt/pcr, then the example is configured against that prefix, built, and run on an
#     installed model); example.py goes to example/ too and python.sh runs it with the installed
#     Python package;
#  3. the installed layout is checked, and the installed pcr tool solves an installed model;
#  4. the C++ blocks of docs/api.md and of docs/paths_through_folds.md, in page order, are built as one
#     program per page against the install and run where the installed models are.
# Arguments: -DBUILD_DIR -DSOURCE_DIR -DWORK.
file(REMOVE_RECURSE "${WORK}")
set(root "${WORK}/root")
set(home "${WORK}/home")
file(MAKE_DIRECTORY "${root}/build" "${root}/example" "${home}")
file(CREATE_LINK "${BUILD_DIR}" "${root}/build/release" SYMBOLIC)
file(CREATE_LINK "${SOURCE_DIR}/models" "${root}/models" SYMBOLIC)

file(READ "${SOURCE_DIR}/README.md" readme)
# The body of the fenced block that follows the marker of `name` (its fence lines left out).
function(readme_block name out)
  set(begin_marker "<!-- readme-block: ${name} -->\n")
  string(FIND "${readme}" "${begin_marker}" begin)
  if(begin EQUAL -1)
    message(FATAL_ERROR "README.md has no block '${name}'")
  endif()
  string(LENGTH "${begin_marker}" marker_length)
  math(EXPR begin "${begin} + ${marker_length}")
  string(SUBSTRING "${readme}" ${begin} -1 rest)
  string(FIND "${rest}" "```\n<!-- readme-block-end -->" end)
  string(FIND "${rest}" "\n" fence_end)  # the opening fence line, e.g. ```cpp
  if(end EQUAL -1 OR fence_end EQUAL -1 OR fence_end GREATER end)
    message(FATAL_ERROR "README.md: block '${name}' is not a fenced block closed before its end marker")
  endif()
  math(EXPR body_begin "${fence_end} + 1")
  math(EXPR body_length "${end} - ${body_begin}")
  string(SUBSTRING "${rest}" ${body_begin} ${body_length} body)
  set(${out} "${body}" PARENT_SCOPE)
endfunction()

foreach(name tour.sh install.sh python.sh)
  readme_block(${name} body)
  file(WRITE "${WORK}/${name}" "${body}")
endforeach()
foreach(name example.cpp CMakeLists.txt example.py)
  readme_block(${name} body)
  file(WRITE "${root}/example/${name}" "${body}")
endforeach()

function(run)
  execute_process(COMMAND ${ARGN} WORKING_DIRECTORY "${root}" RESULT_VARIABLE result OUTPUT_VARIABLE out
                  ERROR_VARIABLE err)
  if(NOT result EQUAL 0)
    message(FATAL_ERROR "failed (${result}): ${ARGN}\n${out}\n${err}")
  endif()
  message(STATUS "${ARGN}:\n${out}")
endfunction()
run(${CMAKE_COMMAND} -E env HOME=${home} bash -euo pipefail "${WORK}/tour.sh")
run(${CMAKE_COMMAND} -E env HOME=${home} bash -euo pipefail "${WORK}/install.sh")
run(${CMAKE_COMMAND} -E env HOME=${home} bash -euo pipefail "${WORK}/python.sh")

# What the README says the install holds.
set(prefix "${home}/opt/pcr")
file(GLOB models RELATIVE "${SOURCE_DIR}/models" "${SOURCE_DIR}/models/*.urdf")
file(GLOB docs RELATIVE "${SOURCE_DIR}" "${SOURCE_DIR}/docs/*.md" "${SOURCE_DIR}/docs/images/*")
set(expected bin/pcr include/pcr/core/types.hpp include/pcr/rods/rod_model.hpp
             include/pcr/robots/kinematics.hpp share/doc/pcr/README.md)
foreach(model ${models})
  list(APPEND expected share/pcr/models/${model})
endforeach()
foreach(doc ${docs})
  list(APPEND expected share/doc/pcr/${doc})
endforeach()
foreach(file ${expected})
  if(NOT EXISTS "${prefix}/${file}")
    message(FATAL_ERROR "not installed: ${prefix}/${file}")
  endif()
endforeach()
file(GLOB_RECURSE package "${prefix}/*/pcrConfig.cmake")
file(GLOB_RECURSE libraries "${prefix}/*/libpcr_robots.a")
if(NOT package OR NOT libraries)
  message(FATAL_ERROR "no pcrConfig.cmake or libpcr_robots.a under ${prefix}")
endif()
run("${prefix}/bin/pcr" fk "${prefix}/share/pcr/models/planar_three_rod.urdf" --json)

# The C++ blocks of a docs page as one program: each block nested in the scope of the blocks before it
# (later blocks use their variables, e.g. api.md's model, fk, target, rod; a name declared again shadows
# the earlier one), their #include lines hoisted. It must build against the install and run without an
# exception where the installed models are.
function(run_doc_cpp_blocks page)
  file(READ "${SOURCE_DIR}/docs/${page}.md" text)
  set(includes "#include <cmath>\n#include <iostream>\n#include <memory>\n")
  set(body "")
  set(closing "")
  string(FIND "${text}" "```cpp\n" begin)
  while(NOT begin EQUAL -1)
    math(EXPR begin "${begin} + 7")
    string(SUBSTRING "${text}" ${begin} -1 text)
    string(FIND "${text}" "```" end)
    string(SUBSTRING "${text}" 0 ${end} block)
    math(EXPR end "${end} + 3")
    string(SUBSTRING "${text}" ${end} -1 text)
    string(REGEX MATCHALL "#include [^\n]*\n" block_includes "${block}")
    string(REGEX REPLACE "#include [^\n]*\n" "" block "${block}")
    string(APPEND includes ${block_includes})
    string(APPEND body "{\n${block}")
    string(APPEND closing "}\n")
    string(FIND "${text}" "```cpp\n" begin)
  endwhile()
  if(body STREQUAL "")
    message(FATAL_ERROR "docs/${page}.md has no C++ block")
  endif()
  set(dir "${root}/doc_${page}")
  file(WRITE "${dir}/main.cpp" "${includes}\nint main() {\n${body}${closing}  return 0;\n}\n")
  file(WRITE "${dir}/CMakeLists.txt" "cmake_minimum_required(VERSION 3.16)
project(pcr_doc_${page} LANGUAGES CXX)
set(CMAKE_CXX_STANDARD 17)
find_package(pcr 0.1 REQUIRED)
add_executable(doc_${page} main.cpp)
target_link_libraries(doc_${page} PRIVATE pcr::robots)
")
  run(${CMAKE_COMMAND} -S "${dir}" -B "${dir}/build" -DCMAKE_PREFIX_PATH=${prefix})
  run(${CMAKE_COMMAND} --build "${dir}/build")
  run(${CMAKE_COMMAND} -E chdir "${prefix}/share/pcr" "${dir}/build/doc_${page}")
endfunction()
run_doc_cpp_blocks(api)
run_doc_cpp_blocks(paths_through_folds)
