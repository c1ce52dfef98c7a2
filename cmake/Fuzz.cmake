# PUNCTUAL_FUZZ: the libFuzzer targets of tests/fuzz, in a build folder of their own configured
# with clang (scripts/fuzz.sh: CC=clang CXX=clang++ cmake -DPUNCTUAL_FUZZ=ON -B build-fuzz).
# Only the CPU libraries are built: punctual_scene (the glTF loader) and punctual_options (the
# option parser). Everything is compiled with ASan, UBSan and libFuzzer's coverage
# instrumentation (cmake/Sanitizers.cmake); the targets link libFuzzer's main.
#
# Included before the libraries are declared: the fuzz build compiles tinygltf and stb_image from
# the Debian headers (the same version the packages' libtinygltf.so and libstb.so are built from)
# into punctual_gltf_libraries, so that the fuzzer sees their coverage and ASan checks their
# memory accesses; an uninstrumented parser would be a black box to both.
add_library(punctual_gltf_libraries STATIC ${CMAKE_SOURCE_DIR}/tests/fuzz/instrumented_libraries.cpp)
target_include_directories(punctual_gltf_libraries PUBLIC ${STB_INCLUDE_DIRS})
target_link_libraries(punctual_gltf_libraries PUBLIC nlohmann_json::nlohmann_json)

# After the libraries: one executable per target.
function(punctual_add_fuzz_targets)
  foreach(target gltf gltf_json options)
    add_executable(punctual_fuzz_${target} ${CMAKE_SOURCE_DIR}/tests/fuzz/fuzz_${target}.cpp)
    target_compile_options(punctual_fuzz_${target} PRIVATE ${PUNCTUAL_WARNINGS})
    target_link_libraries(punctual_fuzz_${target} PRIVATE punctual_options)
    target_link_options(punctual_fuzz_${target} PRIVATE -fsanitize=fuzzer)
    punctual_sanitizer_defaults(punctual_fuzz_${target})
  endforeach()
  # Prints the option fuzzer's dictionary words that come from the tables (every option and
  # variant name), which scripts/fuzz.sh adds to tests/fuzz/options.dict's hand-picked values.
  add_executable(punctual_options_dictionary ${CMAKE_SOURCE_DIR}/tests/fuzz/options_dictionary.cpp)
  target_compile_options(punctual_options_dictionary PRIVATE ${PUNCTUAL_WARNINGS})
  target_link_libraries(punctual_options_dictionary PRIVATE punctual_options)
  punctual_sanitizer_defaults(punctual_options_dictionary)
endfunction()
