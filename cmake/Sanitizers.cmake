# The hardening options declared in CMakeLists.txt (see README, "CI"):
#   PUNCTUAL_WERROR    warnings are errors.
#   PUNCTUAL_SANITIZE  AddressSanitizer + UndefinedBehaviorSanitizer on everything we compile, for
#                      a build folder of its own (build-asan/) that runs the whole suite.
#   PUNCTUAL_FUZZ      the same sanitizers, plus libFuzzer's coverage (see cmake/Fuzz.cmake).
# The Vulkan loader, lavapipe, the validation layers, Embree and TBB stay uninstrumented Debian
# libraries: ASan intercepts their allocations, which is all it needs as long as our executables
# are instrumented.
if(PUNCTUAL_WERROR)
  list(APPEND PUNCTUAL_WARNINGS -Werror)
endif()

if(PUNCTUAL_SANITIZE OR PUNCTUAL_FUZZ)
  # -fno-sanitize-recover: any UBSan report aborts, so it fails the test that triggered it.
  # GCC leaves float-cast-overflow out of -fsanitize=undefined (clang includes it); a float out of
  # an integer's range (uint32_t(NaN), a huge size) is exactly the bug a renderer makes.
  set(PUNCTUAL_SANITIZER_FLAGS -fsanitize=address,undefined,float-cast-overflow -fno-sanitize-recover=all
      -fno-omit-frame-pointer)
  # -g1: the file and line of every frame in a report, at a fraction of -g's build time.
  # _GLIBCXX_ASSERTIONS: bounds checks in std::vector, std::span, ... (no ABI change), which catch
  # an index past size() but within capacity, where ASan sees valid memory.
  add_compile_options(${PUNCTUAL_SANITIZER_FLAGS} -g1 -D_GLIBCXX_ASSERTIONS)
  if(PUNCTUAL_SANITIZE AND NOT PUNCTUAL_FUZZ)
    # -O1 (after the build type's -O3, so it wins): what the sanitizers' documentation recommends,
    # and it halves this build's compile time (test_shadows.cpp: 17 s at -O3, 8.5 s at -O1), the
    # larger part of CI's sanitizer step. The suite's time is mostly lavapipe's and Embree's, which
    # are not rebuilt. The fuzz build keeps -O3: there, executions per second matter.
    add_compile_options(-O1)
  endif()
  add_link_options(${PUNCTUAL_SANITIZER_FLAGS})
  if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
    # GCC 12 with -fsanitize=address reports -Wmaybe-uninitialized false positives inside
    # libstdc++ (std::regex's std::function members). The other builds keep the warning.
    list(APPEND PUNCTUAL_WARNINGS -Wno-maybe-uninitialized)
  endif()
endif()

if(PUNCTUAL_FUZZ)
  if(NOT CMAKE_CXX_COMPILER_ID STREQUAL "Clang")
    message(FATAL_ERROR "PUNCTUAL_FUZZ needs clang: configure with CC=clang CXX=clang++ (see scripts/fuzz.sh)")
  endif()
  # libFuzzer's coverage instrumentation in every library; the targets link its main (Fuzz.cmake).
  add_compile_options(-fsanitize=fuzzer-no-link)
endif()

# Our sanitizer settings, compiled into every executable of a sanitizer build so that a test, a
# test's child `punctual` process or a developer's shell all run with them (no environment needed).
function(punctual_sanitizer_defaults)
  if(NOT (PUNCTUAL_SANITIZE OR PUNCTUAL_FUZZ))
    return()
  endif()
  foreach(target ${ARGN})
    target_sources(${target} PRIVATE ${CMAKE_SOURCE_DIR}/cmake/sanitizers/sanitizer_defaults.cpp)
    set_source_files_properties(${CMAKE_SOURCE_DIR}/cmake/sanitizers/sanitizer_defaults.cpp PROPERTIES
      COMPILE_DEFINITIONS PUNCTUAL_LSAN_SUPPRESSIONS="${CMAKE_SOURCE_DIR}/cmake/sanitizers/lsan.supp")
  endforeach()
endfunction()
