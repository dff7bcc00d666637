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
# libFuzzer build (tests/fuzz): libFuzzer's coverage instrumentation, for the code a fuzz target can reach, the
# libraries under solvers/ and problems/ (smcbench_library) and the fuzz targets (which add -fsanitize=fuzzer at link
# time for libFuzzer's main). The layers above (bench/, tools/) point down, so no fuzz target links them: they are
# built without it (it was a fifth of a sanitized file's compile time).
set(smcbench_fuzz_coverage_flags)
if(SMCBENCH_FUZZ)
  set(smcbench_fuzz_coverage_flags -fsanitize=fuzzer-no-link)
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

# A test's own code is calls and checks, so it is built for compile time; the libraries it tests keep the build's
# flags. Under the sanitizers -O0 (clang compiles a sanitized test file in half the time of -O1, and ASan misses
# nothing an optimizer would have removed); in a Release build -O1 (g++ compiles a test file in three quarters of the
# time of -O3; no FMA contraction or reassociation at either level, so the test's own arithmetic is unchanged). At -O1
# g++'s -Wmaybe-uninitialized reports '<unknown>' inside Eigen's DenseStorage moves, a false positive; the definite
# -Wuninitialized stays, and clang's uninitialized-use warnings check the tests in the ASan build.
add_library(smcbench_test_compile_flags INTERFACE)
if(SMCBENCH_SANITIZE OR SMCBENCH_FUZZ)
  target_compile_options(smcbench_test_compile_flags INTERFACE -O0)
elseif(CMAKE_BUILD_TYPE STREQUAL "Release")
  target_compile_options(smcbench_test_compile_flags INTERFACE -O1 $<$<CXX_COMPILER_ID:GNU>:-Wno-maybe-uninitialized>)
endif()

# The static libraries link it PRIVATE, which an installed static library still records ($<LINK_ONLY:...>, for the
# sanitizer link options): it is exported with them as smcbench::build_flags (cmake/SmcbenchInstall.cmake).
set_target_properties(smcbench_build_flags PROPERTIES EXPORT_NAME build_flags)
set_property(GLOBAL APPEND PROPERTY SMCBENCH_INSTALLED_TARGETS smcbench_build_flags)

# Headers are included by their path from the checkout's root ("solvers/core/solver.h"); installed, that root is
# <prefix>/include/smcbench, and <prefix>/include gives <smcbench/smcbench.h> (the umbrella header, include/).
set(SMCBENCH_INCLUDE_DIRS $<BUILD_INTERFACE:${PROJECT_SOURCE_DIR}> $<BUILD_INTERFACE:${PROJECT_SOURCE_DIR}/include>
  $<INSTALL_INTERFACE:include/smcbench> $<INSTALL_INTERFACE:include>)

# Precompiled headers (option SMCBENCH_PRECOMPILED_HEADERS): each file parsed Eigen, nlohmann::json and the standard
# library again (g++: 1.5 s for Eigen/Dense, 2 s for json.hpp); with them a file takes 0.82 of its compile time
# under clang with the sanitizers, 0.88-0.91 under g++ -O3 (whose header costs about a second to load). Each kind of
# file gets one header, precompiled once by a small owner target with that kind's flags (smcbench_library_pch for
# the libraries, smcbench_test_pch for the tests) and reused by every target of the kind. OFF builds without them,
# which also checks that every file includes what it uses.
set(smcbench_common_pch_headers <Eigen/Dense> <Eigen/SparseCore> <nlohmann/json.hpp> <algorithm> <cmath> <cstdint>
  <filesystem> <fstream> <functional> <limits> <map> <memory> <optional> <random> <set> <sstream> <stdexcept>
  <string> <utility> <vector>)

# smcbench_precompiled_header_owner(OWNER OBJECT|EXECUTABLE HEADERS ... LINK ... [OPTIONS ...]) → a target of one
# empty program that precompiles HEADERS with the flags LINK and OPTIONS give. The targets that reuse it must compile
# with the same flags, -fPIC or -fPIE and the coverage instrumentation included (g++ and clang refuse a precompiled
# header made with other ones): an object library for the libraries' -fPIC, an executable for the tests' -fPIE.
function(smcbench_precompiled_header_owner owner type)
  cmake_parse_arguments(ARG "" "" "HEADERS;LINK;OPTIONS" ${ARGN})
  if(NOT SMCBENCH_PRECOMPILED_HEADERS)
    return()
  endif()
  set(source ${PROJECT_BINARY_DIR}/pch/${owner}.cc)
  file(CONFIGURE OUTPUT ${source} CONTENT "// The owner of a precompiled header (cmake/SmcbenchHelpers.cmake).
int main() { return 0; }
")  # written when it changes only, so a new configure does not rebuild it
  if(type STREQUAL "EXECUTABLE")
    add_executable(${owner} ${source})
  else()
    add_library(${owner} OBJECT ${source})
  endif()
  target_link_libraries(${owner} PRIVATE ${ARG_LINK})
  target_compile_options(${owner} PRIVATE ${ARG_OPTIONS})
  target_precompile_headers(${owner} PRIVATE ${ARG_HEADERS})
endfunction()

# smcbench_reuse_precompiled_headers(TARGET OWNER): TARGET's files start from OWNER's precompiled header. A file
# compiled with other options (set_source_files_properties(... COMPILE_OPTIONS ...)) must set
# SKIP_PRECOMPILE_HEADERS ON.
function(smcbench_reuse_precompiled_headers target owner)
  if(SMCBENCH_PRECOMPILED_HEADERS)
    target_precompile_headers(${target} REUSE_FROM ${owner})
  endif()
endfunction()

# smcbench_library(NAME SOURCES ... DEPS ...) → target smcbench_NAME with alias smcbench::NAME, installed and
# exported as smcbench::NAME (cmake/SmcbenchInstall.cmake installs every target this function made).
function(smcbench_library name)
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPS" ${ARGN})
  add_library(smcbench_${name} STATIC ${ARG_SOURCES})
  add_library(smcbench::${name} ALIAS smcbench_${name})
  set_target_properties(smcbench_${name} PROPERTIES EXPORT_NAME ${name})
  target_include_directories(smcbench_${name} PUBLIC ${SMCBENCH_INCLUDE_DIRS})
  target_link_libraries(smcbench_${name} PUBLIC ${ARG_DEPS} PRIVATE smcbench_build_flags)
  file(RELATIVE_PATH folder ${PROJECT_SOURCE_DIR} ${CMAKE_CURRENT_SOURCE_DIR})
  if(SMCBENCH_FUZZ AND folder MATCHES "^(solvers|problems)(/|$)")  # what a fuzz target can reach
    target_compile_options(smcbench_${name} PRIVATE ${smcbench_fuzz_coverage_flags})
    smcbench_reuse_precompiled_headers(smcbench_${name} smcbench_fuzzed_library_pch)
  else()
    smcbench_reuse_precompiled_headers(smcbench_${name} smcbench_library_pch)
  endif()
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
  target_link_libraries(${name} PRIVATE smcbench_test_compile_flags)
  # GoogleTest, Eigen, nlohmann::json and the standard library, parsed once for every test file (a third of a
  # sanitized test file's compile time).
  smcbench_reuse_precompiled_headers(${name} smcbench_test_pch)
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
