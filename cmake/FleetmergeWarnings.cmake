# One place that sets language level, warnings and sanitizers for every fleetmerge target.
function(fleetmerge_target_defaults target)
  target_compile_features(${target} PUBLIC cxx_std_17)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic)
  if(FLEETMERGE_SANITIZE)
    # No recovery: a UBSan finding fails the test instead of printing and going on.
    target_compile_options(${target} PRIVATE -fsanitize=address,undefined
      -fno-sanitize-recover=all -fno-omit-frame-pointer)
    target_link_options(${target} PUBLIC -fsanitize=address,undefined -fno-sanitize-recover=all)
  endif()
  if(FLEETMERGE_FUZZ AND (target STREQUAL "fleetmerge_io" OR target MATCHES "_fuzzer$"))
    target_compile_options(${target} PRIVATE -fsanitize=fuzzer-no-link)
  endif()
endfunction()
