# `cmake --install <build> --prefix P`: the static libraries with their headers, the smcbench command, the scenes, and
# a relocatable CMake package (find_package(smcbench CONFIG) → smcbench::<library>, smcbench::smcbench). Tests and
# benchmarks are not installed. Included at the end of the top-level CMakeLists.txt, once every target exists.
# Layout (GNUInstallDirs): bin/smcbench, lib/libsmcbench_*.a, include/smcbench/{smcbench.h,version.h,solvers/,
# problems/,bench/,tools/} (the public headers only), share/smcbench/{scenes,siconos}/, lib/cmake/smcbench/.
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

set(SMCBENCH_INSTALL_CMAKEDIR ${CMAKE_INSTALL_LIBDIR}/cmake/smcbench CACHE STRING
  "Where the CMake package of smcbench is installed, relative to the prefix")

# The umbrella target: the library API (every backend, the conformance checks, problems, scenes, steppers, the
# problem library, a benchmark run and its replay engine). smcbench::cli (the commands) is separate: only a program
# that runs the command line needs it.
add_library(smcbench_all INTERFACE)
add_library(smcbench::smcbench ALIAS smcbench_all)
set_target_properties(smcbench_all PROPERTIES EXPORT_NAME smcbench)
target_link_libraries(smcbench_all INTERFACE smcbench::solvers smcbench::avi smcbench::conformance smcbench::reference
  smcbench::problems smcbench::library smcbench::references smcbench::capture smcbench::scenes smcbench::stepper
  smcbench::suites smcbench::replay smcbench::bench_run smcbench::version)
target_include_directories(smcbench_all INTERFACE ${SMCBENCH_INCLUDE_DIRS})

get_property(installed_targets GLOBAL PROPERTY SMCBENCH_INSTALLED_TARGETS)
install(TARGETS ${installed_targets} smcbench_all EXPORT smcbenchTargets
  ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR} COMPONENT development)
install(TARGETS smcbench RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR} COMPONENT runtime)

# Only the public headers (cmake/SmcbenchPublicHeaders.cmake, one list) are installed, under include/smcbench with
# their paths from the checkout's root (so "solvers/core/solver.h" never collides with another package's headers in
# <prefix>/include); include/smcbench/ of the checkout gives <smcbench/smcbench.h>. Every other header is internal.
include(SmcbenchPublicHeaders)
foreach(header IN LISTS SMCBENCH_PUBLIC_HEADERS)
  get_filename_component(folder ${header} DIRECTORY)
  if(folder MATCHES "^include(/|$)")
    string(REGEX REPLACE "^include/?" "" destination "${folder}")
    set(destination ${CMAKE_INSTALL_INCLUDEDIR}/${destination})
  else()
    set(destination ${CMAKE_INSTALL_INCLUDEDIR}/smcbench/${folder})
  endif()
  install(FILES ${PROJECT_SOURCE_DIR}/${header} DESTINATION ${destination} COMPONENT development)
endforeach()
if(SMCBENCH_BUILD_TESTS)
  # A public header includes only public headers (so the installed tree is closed); the second test shows the
  # check fails, naming both headers, when one does not (polish.h includes the internal active_set.h).
  add_test(NAME public_headers COMMAND ${CMAKE_COMMAND} -DSOURCE_DIR=${PROJECT_SOURCE_DIR}
    -P ${PROJECT_SOURCE_DIR}/cmake/CheckPublicHeaders.cmake)
  add_test(NAME public_headers_names_an_internal_include COMMAND ${CMAKE_COMMAND} -DSOURCE_DIR=${PROJECT_SOURCE_DIR}
    -DHEADERS=solvers/core/polish.h -P ${PROJECT_SOURCE_DIR}/cmake/CheckPublicHeaders.cmake)
  set_tests_properties(public_headers_names_an_internal_include PROPERTIES PASS_REGULAR_EXPRESSION
    "solvers/core/polish.h includes \"solvers/core/active_set.h\", which is internal")
endif()

# The data folders: the scene files and the vendored Siconos collection (unchanged, with its README, LICENSE and
# SOURCE_COMMIT). The installed smcbench and Python module find them beside themselves, wherever the prefix is moved
# (DataDirectory, problems/io/data_dirs.h), so no default path depends on the working directory.
file(GLOB scene_files ${PROJECT_SOURCE_DIR}/problems/scenes/*.json)
install(FILES ${scene_files} DESTINATION ${CMAKE_INSTALL_DATADIR}/smcbench/scenes COMPONENT runtime)
install(DIRECTORY ${PROJECT_SOURCE_DIR}/tests/data/siconos/ DESTINATION ${CMAKE_INSTALL_DATADIR}/smcbench/siconos
  COMPONENT runtime)
install(FILES ${PROJECT_SOURCE_DIR}/LICENSE ${PROJECT_SOURCE_DIR}/CITATION.cff
  DESTINATION ${CMAKE_INSTALL_DATADIR}/doc/smcbench COMPONENT runtime)

# The package: targets, version, and the find modules of dependencies that ship no CMake config of their own.
install(EXPORT smcbenchTargets NAMESPACE smcbench:: DESTINATION ${SMCBENCH_INSTALL_CMAKEDIR} COMPONENT development)
get_property(SMCBENCH_PACKAGE_WITH_SICONOS GLOBAL PROPERTY SMCBENCH_HAVE_SICONOS)
get_property(SMCBENCH_PACKAGE_WITH_BULLET GLOBAL PROPERTY SMCBENCH_HAVE_BULLET)
get_property(SMCBENCH_PACKAGE_WITH_DART GLOBAL PROPERTY SMCBENCH_HAVE_DART)
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/smcbenchConfig.cmake.in
  ${PROJECT_BINARY_DIR}/package/smcbenchConfig.cmake
  INSTALL_DESTINATION ${SMCBENCH_INSTALL_CMAKEDIR}
  PATH_VARS CMAKE_INSTALL_DATADIR)
# 0.x: a minor release may change the API, so a consumer asking for 0.1 accepts 0.1.* only.
write_basic_package_version_file(${PROJECT_BINARY_DIR}/package/smcbenchConfigVersion.cmake
  VERSION ${PROJECT_VERSION} COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/package/smcbenchConfig.cmake
  ${PROJECT_BINARY_DIR}/package/smcbenchConfigVersion.cmake
  ${PROJECT_SOURCE_DIR}/cmake/FindSuiteSparseLibs.cmake ${PROJECT_SOURCE_DIR}/cmake/FindSiconosNumerics.cmake
  DESTINATION ${SMCBENCH_INSTALL_CMAKEDIR} COMPONENT development)

# Everything `cmake --install` copies, as one target: tools/install-check.sh builds it instead of `all` (which
# would also build every test and benchmark).
add_custom_target(smcbench_installables)
add_dependencies(smcbench_installables ${installed_targets} smcbench)
if(TARGET _smcbench)
  add_dependencies(smcbench_installables _smcbench)  # the Python module (python/CMakeLists.txt installs it)
endif()
