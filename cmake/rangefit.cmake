# Shared build settings. Every library and test goes through these functions, so warnings,
# the language level and sanitizers are set in one place (no global include_directories).

option(RANGEFIT_SANITIZE "Build with AddressSanitizer and UndefinedBehaviorSanitizer" OFF)
option(RANGEFIT_FUZZ "Build the libFuzzer harnesses of test/fuzz (clang; implies ASan + UBSan)" OFF)
# CI fuzzes with both; "undefined" alone runs the allocation-heavy TOML harness ~1.5x as many
# inputs per CPU second, for long searches (memory errors are then caught only when they crash).
set(RANGEFIT_FUZZ_SANITIZERS "address,undefined" CACHE STRING
    "Sanitizers of a RANGEFIT_FUZZ build besides fuzzer-no-link")

function(rangefit_compile_options target)
  target_compile_features(${target} PUBLIC cxx_std_20)
  # -Wno-psabi: GCC notes that passing 32-byte vectors (detect/lanes.hpp) by value would change
  # the ABI without AVX; those functions are always inlined, so no ABI is involved.
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wshadow -Wconversion
                                           -Wno-sign-conversion -Wno-psabi -Werror)
  # In a unity build a .cpp's class (e.g. a pimpl's Impl) holding a type from the file's anonymous
  # namespace is no longer in the main file, and GCC warns as if it were in a shared header. The
  # batch is still one translation unit, so nothing can disagree; the headers have no anonymous
  # namespaces.
  if(CMAKE_UNITY_BUILD AND CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
    target_compile_options(${target} PRIVATE -Wno-subobject-linkage)
  endif()
  if(RANGEFIT_SANITIZE)
    target_compile_options(${target} PRIVATE -fsanitize=address,undefined -fno-omit-frame-pointer
                                             -fno-sanitize-recover=all)
    target_link_options(${target} PUBLIC -fsanitize=address,undefined)
  endif()
  if(RANGEFIT_FUZZ)
    # -Wno-error: clang warns about things GCC does not; -Werror is the GCC build's gate.
    target_compile_options(${target} PRIVATE -fsanitize=fuzzer-no-link,${RANGEFIT_FUZZ_SANITIZERS}
                                             -fno-omit-frame-pointer -fno-sanitize-recover=all
                                             -Wno-error)
    target_link_options(${target} PUBLIC -fsanitize=${RANGEFIT_FUZZ_SANITIZERS})
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

# rangefit_registry(OUT_VAR FOLDER NAMESPACE TYPE HEADER FUNCTION): a folder of kinds, each file
# registering itself. FOLDER/<stem>.cpp defines `const TYPE <stem>` in namespace
# rangefit::daemon::NAMESPACE (declared extern first); a generated source lists every file's entry,
# in name order, as `std::span<const TYPE* const> FUNCTION()` (declared in HEADER). OUT_VAR gets
# the folder's files and the generated one. Adding a kind is adding a file: nothing else names it.
function(rangefit_registry out_var folder namespace type header function)
  file(GLOB files CONFIGURE_DEPENDS ${folder}/*.cpp)
  list(SORT files)
  set(decls "")
  set(entries "")
  foreach(f IN LISTS files)
    get_filename_component(stem ${f} NAME_WE)
    string(APPEND decls "extern const ${type} ${stem};\n")
    string(APPEND entries "&${namespace}::${stem}, ")
  endforeach()
  string(REGEX REPLACE ", $" "" entries "${entries}")
  set(generated ${CMAKE_CURRENT_BINARY_DIR}/${namespace}_registry.cpp)
  file(RELATIVE_PATH from ${PROJECT_SOURCE_DIR} ${folder})
  file(CONFIGURE OUTPUT ${generated} @ONLY CONTENT
"// Generated by rangefit_registry() (cmake/rangefit.cmake) from the files of
// ${from}/: one entry per file, in name order. Not to be edited.
#include \"${header}\"

namespace rangefit::daemon {
namespace ${namespace} {
${decls}}  // namespace ${namespace}

std::span<const ${type}* const> ${function}() {
  static const ${type}* const kAll[] = {${entries}};
  return kAll;
}

}  // namespace rangefit::daemon
")
  set(${out_var} ${files} ${generated} PARENT_SCOPE)
endfunction()
