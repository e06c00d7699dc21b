# Shared build settings. Every library and test goes through these functions, so warnings,
# the language level and sanitizers are set in one place (no global include_directories).

option(RANGEFIT_SANITIZE "Build with AddressSanitizer and UndefinedBehaviorSanitizer" OFF)
option(RANGEFIT_FUZZ "Build the libFuzzer harnesses of test/fuzz (clang; implies ASan + UBSan)" OFF)

function(rangefit_compile_options target)
  target_compile_features(${target} PUBLIC cxx_std_20)
  # -Wno-psabi: GCC notes that passing 32-byte vectors (detect/lanes.hpp) by value would change
  # the ABI without AVX; those functions are always inlined, so no ABI is involved.
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wshadow -Wconversion
                                           -Wno-sign-conversion -Wno-psabi -Werror)
  if(RANGEFIT_SANITIZE)
    target_compile_options(${target} PRIVATE -fsanitize=address,undefined -fno-omit-frame-pointer
                                             -fno-sanitize-recover=all)
    target_link_options(${target} PUBLIC -fsanitize=address,undefined)
  endif()
  if(RANGEFIT_FUZZ)
    # -Wno-error: clang warns about things GCC does not; -Werror is the GCC build's gate.
    target_compile_options(${target} PRIVATE -fsanitize=fuzzer-no-link,address,undefined
                                             -fno-omit-frame-pointer -fno-sanitize-recover=all
                                             -Wno-error)
    target_link_options(${target} PUBLIC -fsanitize=address,undefined)
  endif()
endfunction()

# rangefit_add_library(NAME folder SOURCES ... [PUBLIC_DEPS ...] [PRIVATE_DEPS ...])
# Creates rangefit_<folder> with the alias rangefit::<folder>. Headers are included as
# "<folder>/<file>.hpp" from the repository root.
function(rangefit_add_library folder)
  cmake_parse_arguments(ARG "" "" "SOURCES;PUBLIC_DEPS;PRIVATE_DEPS" ${ARGN})
  set(target rangefit_${folder})
  if(ARG_SOURCES)
    add_library(${target} STATIC ${ARG_SOURCES})
    target_include_directories(${target} PUBLIC ${PROJECT_SOURCE_DIR})
    target_link_libraries(${target} PUBLIC ${ARG_PUBLIC_DEPS} PRIVATE ${ARG_PRIVATE_DEPS})
    rangefit_compile_options(${target})
  else()
    add_library(${target} INTERFACE)
    target_include_directories(${target} INTERFACE ${PROJECT_SOURCE_DIR})
    target_link_libraries(${target} INTERFACE ${ARG_PUBLIC_DEPS})
    target_compile_features(${target} INTERFACE cxx_std_20)
  endif()
  add_library(rangefit::${folder} ALIAS ${target})
endfunction()

# rangefit_add_test(NAME SOURCES ... DEPS ...): one GoogleTest executable, tests discovered by ctest.
function(rangefit_add_test name)
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPS" ${ARGN})
  add_executable(${name} ${ARG_SOURCES})
  target_link_libraries(${name} PRIVATE ${ARG_DEPS} GTest::gtest GTest::gmock GTest::gtest_main)
  target_compile_definitions(${name} PRIVATE RANGEFIT_SOURCE_DIR="${PROJECT_SOURCE_DIR}")
  rangefit_compile_options(${name})
  gtest_discover_tests(${name} DISCOVERY_TIMEOUT 60 PROPERTIES TIMEOUT 300)
endfunction()

# rangefit_add_benchmark(NAME SOURCES ... DEPS ...): one Google Benchmark executable (not a ctest).
function(rangefit_add_benchmark name)
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPS" ${ARGN})
  add_executable(${name} ${ARG_SOURCES})
  target_link_libraries(${name} PRIVATE ${ARG_DEPS} benchmark::benchmark)
  target_compile_definitions(${name} PRIVATE RANGEFIT_SOURCE_DIR="${PROJECT_SOURCE_DIR}")
  rangefit_compile_options(${name})
endfunction()
