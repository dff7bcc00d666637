# Shared compile settings and helpers for smcbench targets.

# Applied to every smcbench target: warnings (errors in CI), optional sanitizers.
add_library(smcbench_build_flags INTERFACE)
target_compile_options(smcbench_build_flags INTERFACE -Wall -Wextra
  $<$<BOOL:${SMCBENCH_WERROR}>:-Werror>
  $<$<BOOL:${SMCBENCH_NATIVE}>:-march=native>)
if(SMCBENCH_FUZZ)
  # libFuzzer build (tests/fuzz): every library gets coverage instrumentation and ASan+UBSan; the fuzz targets
  # themselves add -fsanitize=fuzzer at link time for libFuzzer's main.
  target_compile_options(smcbench_build_flags INTERFACE -fsanitize=fuzzer-no-link,address,undefined
    -fno-omit-frame-pointer -fno-sanitize-recover=all)
  target_link_options(smcbench_build_flags INTERFACE -fsanitize=address,undefined)
elseif(SMCBENCH_SANITIZE)
  target_compile_options(smcbench_build_flags INTERFACE -fsanitize=address,undefined -fno-omit-frame-pointer
    -fno-sanitize-recover=all)
  target_link_options(smcbench_build_flags INTERFACE -fsanitize=address,undefined)
endif()

# smcbench_library(NAME SOURCES ... DEPS ...) → target smcbench_NAME with alias smcbench::NAME.
function(smcbench_library name)
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPS" ${ARGN})
  add_library(smcbench_${name} STATIC ${ARG_SOURCES})
  add_library(smcbench::${name} ALIAS smcbench_${name})
  target_include_directories(smcbench_${name} PUBLIC ${PROJECT_SOURCE_DIR})
  target_link_libraries(smcbench_${name} PUBLIC ${ARG_DEPS} PRIVATE smcbench_build_flags)
endfunction()

# smcbench_test(NAME SOURCES ... DEPS ... [LABELS ...] [ENVIRONMENT VAR=VALUE ...]) → a GoogleTest binary
# registered with ctest.
function(smcbench_test name)
  if(NOT SMCBENCH_BUILD_TESTS)
    return()
  endif()
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPS;LABELS;ENVIRONMENT" ${ARGN})
  add_executable(${name} ${ARG_SOURCES})
  target_link_libraries(${name} PRIVATE ${ARG_DEPS} GTest::gmock GTest::gtest GTest::gtest_main smcbench_build_flags)
  target_compile_definitions(${name} PRIVATE
    SMCBENCH_SOURCE_DIR="${PROJECT_SOURCE_DIR}"
    SMCBENCH_PEER_DATA_DIR="${PROJECT_SOURCE_DIR}/../shared/peer-data")
  include(GoogleTest)
  set(properties LABELS "${ARG_LABELS}")
  if(ARG_ENVIRONMENT)
    list(APPEND properties ENVIRONMENT "${ARG_ENVIRONMENT}")
  endif()
  gtest_discover_tests(${name} DISCOVERY_TIMEOUT 60 PROPERTIES ${properties})
endfunction()
