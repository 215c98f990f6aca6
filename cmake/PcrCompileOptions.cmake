# pcr_target_defaults(target [SANITIZERS_LINKED_ONLY]): warnings (errors with PCR_WERROR) and sanitizers
# for pcr's own targets. SANITIZERS_LINKED_ONLY (the test executables): linked with the sanitizer
# runtimes, their own code not instrumented - the libraries they call are; instrumenting the Boost.Test
# code too tripled its compile time (test_kinematics.cpp: 48 s against 16 s) and checked only the tests.
function(pcr_target_defaults target)
  cmake_parse_arguments(D "SANITIZERS_LINKED_ONLY" "" "" ${ARGN})
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic $<$<BOOL:${PCR_WERROR}>:-Werror>)
  if(PCR_SANITIZE)
    # Eigen allocates its heap arrays by malloc where glibc aligns them, by its own aligned malloc under
    # AddressSanitizer (Eigen/src/Core/util/Memory.h): instrumented and plain code must agree on one.
    target_compile_definitions(${target} PRIVATE EIGEN_MALLOC_ALREADY_ALIGNED=0)
    if(NOT D_SANITIZERS_LINKED_ONLY)
      target_compile_options(${target} PRIVATE -fsanitize=address,undefined -fno-omit-frame-pointer
                                               -fno-sanitize-recover=undefined)
    endif()
    target_link_options(${target} PRIVATE -fsanitize=address,undefined)
  endif()
endfunction()

# Precompiled headers: nearly every translation unit includes Eigen/Dense (through pcr/core/types.hpp)
# and the same few standard headers; parsing them is about 2 s of every compile. One header set per
# library and executable target; the test executables share one (pcr_test_pch in tests/CMakeLists.txt).
# Boost.Test is not in it: a test's BOOST_TEST_MODULE must come before its unit_test.hpp.
option(PCR_PRECOMPILE_HEADERS "Precompile the Eigen and standard headers every source includes" ON)
set(PCR_PCH_HEADERS <algorithm> <cmath> <functional> <memory> <sstream> <string> <vector> <Eigen/Dense>
                    <Eigen/SparseCore>)
# pcr_precompile_headers(target [extra headers...])
function(pcr_precompile_headers target)
  if(PCR_PRECOMPILE_HEADERS)
    target_precompile_headers(${target} PRIVATE ${PCR_PCH_HEADERS} ${ARGN})
  endif()
endfunction()
# pcr_reuse_precompiled_headers(target from): target compiles with from's precompiled headers (the same
# compile options).
function(pcr_reuse_precompiled_headers target from)
  if(PCR_PRECOMPILE_HEADERS)
    target_precompile_headers(${target} REUSE_FROM ${from})
  endif()
endfunction()
