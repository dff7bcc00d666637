# Shared compile settings and helpers for smcbench targets.

# Applied to every smcbench target: warnings (errors in CI), optional sanitizers.
set(smcbench_warning_flags -Wall -Wextra -fno-semantic-interposition
  $<$<BOOL:${SMCBENCH_WERROR}>:-Werror>
  $<$<BOOL:${SMCBENCH_NATIVE}>:-march=native>)
set(smcbench_sanitizer_flags)
if(SMCBENCH_SANITIZE OR SMCBENCH_FUZZ)
  set(smcbench_sanitizer_flags -fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=all)
endif()
add_library(smcbench_build_flags INTERFACE)
target_compile_options(smcbench_build_flags INTERFACE ${smcbench_warning_flags} ${smcbench_sanitizer_flags})
if(SMCBENCH_FUZZ)
  # libFuzzer build (tests/fuzz): every library also gets libFuzzer's coverage instrumentation; the fuzz targets
  # themselves add -fsanitize=fuzzer at link time for libFuzzer's main.
  target_compile_options(smcbench_build_flags INTERFACE -fsanitize=fuzzer-no-link)
endif()
if(SMCBENCH_SANITIZE OR SMCBENCH_FUZZ)
  target_link_options(smcbench_build_flags INTERFACE -fsanitize=address,undefined)
endif()

# A test's own files (smcbench_test): the same warnings and sanitizers, without libFuzzer's coverage instrumentation
# (no test file is fuzzed; it was a fifth of a sanitized test file's compile time). The libraries it links keep it.
add_library(smcbench_test_flags INTERFACE)
target_compile_options(smcbench_test_flags INTERFACE ${smcbench_warning_flags} ${smcbench_sanitizer_flags})
if(SMCBENCH_SANITIZE OR SMCBENCH_FUZZ)
  target_link_options(smcbench_test_flags INTERFACE -fsanitize=address,undefined)
endif()

# The static libraries link it PRIVATE, which an installed static library still records ($<LINK_ONLY:...>, for the
# sanitizer link options): it is exported with them as smcbench::build_flags (cmake/SmcbenchInstall.cmake).
set_target_properties(smcbench_build_flags PROPERTIES EXPORT_NAME build_flags)
set_property(GLOBAL APPEND PROPERTY SMCBENCH_INSTALLED_TARGETS smcbench_build_flags)

# Headers are included by their path from the checkout's root ("solvers/core/solver.h"); installed, that root is
# <prefix>/include/smcbench, and <prefix>/include gives <smcbench/smcbench.h> (the umbrella header, include/).
set(SMCBENCH_INCLUDE_DIRS $<BUILD_INTERFACE:${PROJECT_SOURCE_DIR}> $<BUILD_INTERFACE:${PROJECT_SOURCE_DIR}/include>
  $<INSTALL_INTERFACE:include/smcbench> $<INSTALL_INTERFACE:include>)

# smcbench_library(NAME SOURCES ... DEPS ...) → target smcbench_NAME with alias smcbench::NAME, installed and
# exported as smcbench::NAME (cmake/SmcbenchInstall.cmake installs every target this function made).
function(smcbench_library name)
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPS" ${ARGN})
  add_library(smcbench_${name} STATIC ${ARG_SOURCES})
  add_library(smcbench::${name} ALIAS smcbench_${name})
  set_target_properties(smcbench_${name} PROPERTIES EXPORT_NAME ${name})
  target_include_directories(smcbench_${name} PUBLIC ${SMCBENCH_INCLUDE_DIRS})
  target_link_libraries(smcbench_${name} PUBLIC ${ARG_DEPS} PRIVATE smcbench_build_flags)
  set_property(GLOBAL APPEND PROPERTY SMCBENCH_INSTALLED_TARGETS smcbench_${name})
endfunction()

# smcbench_test(NAME SOURCES ... DEPS ... [LABELS ...] [ENVIRONMENT VAR=VALUE ...]) → a GoogleTest binary
# registered with ctest.
function(smcbench_test name)
  if(NOT SMCBENCH_BUILD_TESTS)
    return()
  endif()
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPS;LABELS;ENVIRONMENT" ${ARGN})
  add_executable(${name} ${ARG_SOURCES})
  target_link_libraries(${name} PRIVATE ${ARG_DEPS} GTest::gmock GTest::gtest GTest::gtest_main smcbench_test_flags)
  # A test's own code is calls and checks, so it is built for compile time; the libraries it tests keep the build's
  # flags. Under the sanitizers -O0 (clang compiles a sanitized test file in half the time of -O1, and ASan misses
  # nothing an optimizer would have removed); in a Release build -O1 (g++ compiles a test file in three quarters of
  # the time of -O3; no FMA contraction or reassociation at either level, so the test's own arithmetic is unchanged).
  # At -O1 g++'s -Wmaybe-uninitialized reports '<unknown>' inside Eigen's DenseStorage moves, a false positive; the
  # definite -Wuninitialized stays, and clang's uninitialized-use warnings check the tests in the ASan build.
  if(SMCBENCH_SANITIZE OR SMCBENCH_FUZZ)
    target_compile_options(${name} PRIVATE -O0)
    # One precompiled header of GoogleTest, Eigen, nlohmann::json and the standard library for every test file, built
    # once by the first test target (its flags and definitions are every test's): parsing them was a third of a
    # sanitized test file's compile time. A test target adds definitions only after this function (scenes_test).
    get_property(pch_owner GLOBAL PROPERTY SMCBENCH_TEST_PCH_OWNER)
    if(pch_owner)
      target_precompile_headers(${name} REUSE_FROM ${pch_owner})
    else()
      target_precompile_headers(${name} PRIVATE <gmock/gmock.h> <gtest/gtest.h> <Eigen/Dense> <Eigen/SparseCore>
        <nlohmann/json.hpp> <algorithm> <cmath> <filesystem> <fstream> <map> <memory> <random> <set> <sstream>
        <string> <vector>)
      set_property(GLOBAL PROPERTY SMCBENCH_TEST_PCH_OWNER ${name})
    endif()
  elseif(CMAKE_BUILD_TYPE STREQUAL "Release")
    target_compile_options(${name} PRIVATE -O1 $<$<CXX_COMPILER_ID:GNU>:-Wno-maybe-uninitialized>)
  endif()
  target_compile_definitions(${name} PRIVATE
    SMCBENCH_SOURCE_DIR="${PROJECT_SOURCE_DIR}"
    SMCBENCH_PEER_DATA_DIR="${PROJECT_SOURCE_DIR}/tests/data")  # holds siconos/ (vendored, tests/data/README.md)
  include(GoogleTest)
  set(properties LABELS "${ARG_LABELS}")
  if(ARG_ENVIRONMENT)
    list(APPEND properties ENVIRONMENT "${ARG_ENVIRONMENT}")
  endif()
  gtest_discover_tests(${name} DISCOVERY_TIMEOUT 60 PROPERTIES ${properties})
endfunction()
