# pcr_target_defaults(target): warnings (errors with PCR_WERROR) and sanitizers for pcr's own targets.
function(pcr_target_defaults target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic $<$<BOOL:${PCR_WERROR}>:-Werror>)
  if(PCR_SANITIZE)
    target_compile_options(${target} PRIVATE -fsanitize=address,undefined -fno-omit-frame-pointer
                                             -fno-sanitize-recover=undefined)
    target_link_options(${target} PRIVATE -fsanitize=address,undefined)
  endif()
endfunction()
