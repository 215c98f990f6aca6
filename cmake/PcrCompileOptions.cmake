# pcr_target_defaults(target [SANITIZE_LINK_ONLY]): warnings (errors with PCR_WERROR) and sanitizers for
# pcr's own targets. SANITIZE_LINK_ONLY: link the sanitizer runtimes but compile without instrumentation
# (the test executables with PCR_SANITIZE_TESTS=OFF: their calls into the instrumented libraries are
# still checked there; ASan + UBSan instrumentation costs 2.5x the compile time of a test source).
function(pcr_target_defaults target)
  cmake_parse_arguments(D "SANITIZE_LINK_ONLY" "" "" ${ARGN})
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic $<$<BOOL:${PCR_WERROR}>:-Werror>)
  if(PCR_SANITIZE)
    if(NOT D_SANITIZE_LINK_ONLY)
      target_compile_options(${target} PRIVATE -fsanitize=address,undefined -fno-omit-frame-pointer
                                               -fno-sanitize-recover=undefined)
    endif()
    target_link_options(${target} PRIVATE -fsanitize=address,undefined)
  endif()
endfunction()
