# Finds Siconos Numerics (Debian 12: libsiconos-numerics-dev, 4.4): headers under <prefix>/include/siconos/numerics,
# library libsiconos_numerics. Siconos' own CMake package needs its kernel components, which this package lacks,
# so it is not used.
#
# Defines SiconosNumerics_FOUND, SiconosNumerics_VERSION (from the Debian changelog when readable, else unknown)
# and the imported target SiconosNumerics::SiconosNumerics. Its include directories are both <prefix>/include/siconos
# (SiconosConfig.h) and <prefix>/include/siconos/numerics (the headers include each other by bare name).
find_path(SiconosNumerics_INCLUDE_DIR NAMES SiconosNumerics.h PATH_SUFFIXES siconos/numerics)
find_path(SiconosNumerics_CONFIG_DIR NAMES SiconosConfig.h PATH_SUFFIXES siconos)
find_library(SiconosNumerics_LIBRARY NAMES siconos_numerics)

if(SiconosNumerics_INCLUDE_DIR AND NOT SiconosNumerics_VERSION)
  # The headers carry no version macro; the Debian package records its version in dpkg's database.
  find_program(SiconosNumerics_DPKG_QUERY dpkg-query)
  mark_as_advanced(SiconosNumerics_DPKG_QUERY)
  if(SiconosNumerics_DPKG_QUERY)
    execute_process(COMMAND ${SiconosNumerics_DPKG_QUERY} -W -f=\${Version} libsiconos-numerics-dev
                    OUTPUT_VARIABLE _siconos_version ERROR_QUIET RESULT_VARIABLE _siconos_rc)
    if(_siconos_rc EQUAL 0 AND _siconos_version MATCHES "^([0-9]+\\.[0-9]+(\\.[0-9]+)?)")
      set(SiconosNumerics_VERSION "${CMAKE_MATCH_1}")
    endif()
  endif()
endif()

include(FindPackageHandleStandardArgs)
find_package_handle_standard_args(SiconosNumerics
  REQUIRED_VARS SiconosNumerics_LIBRARY SiconosNumerics_INCLUDE_DIR SiconosNumerics_CONFIG_DIR
  VERSION_VAR SiconosNumerics_VERSION)

if(SiconosNumerics_FOUND AND NOT TARGET SiconosNumerics::SiconosNumerics)
  add_library(SiconosNumerics::SiconosNumerics UNKNOWN IMPORTED)
  # SYSTEM: Siconos' headers are not ours to keep warning-free under -Wall -Wextra -Werror.
  set_target_properties(SiconosNumerics::SiconosNumerics PROPERTIES
    IMPORTED_LOCATION "${SiconosNumerics_LIBRARY}"
    INTERFACE_SYSTEM_INCLUDE_DIRECTORIES "${SiconosNumerics_INCLUDE_DIR};${SiconosNumerics_CONFIG_DIR}"
    INTERFACE_INCLUDE_DIRECTORIES "${SiconosNumerics_INCLUDE_DIR};${SiconosNumerics_CONFIG_DIR}")
endif()
mark_as_advanced(SiconosNumerics_INCLUDE_DIR SiconosNumerics_CONFIG_DIR SiconosNumerics_LIBRARY)
