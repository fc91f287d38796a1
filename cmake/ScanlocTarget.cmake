# One place that sets the language level, warnings and sanitizers on every target of ours.
function(scanloc_configure_target target)
  target_compile_features(${target} PUBLIC cxx_std_17)
  set_target_properties(${target} PROPERTIES CXX_EXTENSIONS OFF)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wshadow -Wno-unused-parameter)
  if(SCANLOC_SANITIZE)
    target_compile_options(${target} PRIVATE -fsanitize=address,undefined -fno-omit-frame-pointer)
    target_link_options(${target} PRIVATE -fsanitize=address,undefined)
  endif()
  if(SCANLOC_FUZZ)
    # Coverage for libFuzzer and both sanitizers; an undefined behaviour aborts, so that the fuzzer
    # records it. The fuzz targets link libFuzzer itself (fuzz/CMakeLists.txt).
    target_compile_options(${target} PRIVATE -fsanitize=fuzzer-no-link,address,undefined
                                             -fno-sanitize-recover=undefined -fno-omit-frame-pointer)
    target_link_options(${target} PRIVATE -fsanitize=address,undefined)
  endif()
endfunction()

# A program around the library (the app, a test): configured as the library is, but under the
# sanitizers compiled without the optimiser. Its passes over the sanitizers' checks took most of the
# sanitized build's time (CLI11 and GoogleTest code), and the code worth running fast is the
# library's; the checks themselves stay.
function(scanloc_configure_driver target)
  scanloc_configure_target(${target})
  if(SCANLOC_SANITIZE)
    target_compile_options(${target} PRIVATE -O0)
  endif()
endfunction()
