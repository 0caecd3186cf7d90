# Install rules and the package files: `cmake --install build --prefix P` gives P/lib (the two
# libraries, CMake package, coatcontact.pc), P/include/coatcontact, P/bin/coatcontact and
# P/share/coatcontact/gnuplot. Consumers use find_package(coatcontact) or pkg-config.
include(CMakePackageConfigHelpers)

set(COATCONTACT_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/coatcontact)

if(BUILD_SHARED_LIBS)
  # The installed program and library find their libraries next to / relative to themselves.
  if(APPLE)
    set(cc_origin @loader_path)
  else()
    set(cc_origin $ORIGIN)
  endif()
  file(RELATIVE_PATH cc_bin_to_lib ${CMAKE_INSTALL_FULL_BINDIR} ${CMAKE_INSTALL_FULL_LIBDIR})
  set_target_properties(coatcontact PROPERTIES INSTALL_RPATH "${cc_origin}/${cc_bin_to_lib}")
  set_target_properties(coatcontact_library PROPERTIES INSTALL_RPATH "${cc_origin}")
endif()

install(TARGETS coatcontact_library coatcontact_fortran
  EXPORT coatcontactTargets
  ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
  LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
  RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(TARGETS coatcontact RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})

# Public headers: every floor's include/coatcontact/ (COATCONTACT_PUBLIC_HEADER_DIRS, cpp/) into
# the one installed include/coatcontact/. The CLI's headers (cpp/support, never listed), the data
# file reader's and the GSL helpers (sources only) stay private. detail/format.hpp is installed:
# kernel.hpp formats its messages with it.
get_property(cc_public_header_dirs GLOBAL PROPERTY COATCONTACT_PUBLIC_HEADER_DIRS)
install(DIRECTORY ${cc_public_header_dirs}
  DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/coatcontact
  FILES_MATCHING PATTERN "*.h" PATTERN "*.hpp"
  PATTERN "data_file.hpp" EXCLUDE
  PATTERN "gsl_handler_off.hpp" EXCLUDE
  PATTERN "brent.hpp" EXCLUDE)
install(DIRECTORY ${PROJECT_SOURCE_DIR}/fortran/include/coatcontact/
  DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/coatcontact
  FILES_MATCHING PATTERN "*.h")

install(DIRECTORY ${PROJECT_SOURCE_DIR}/gnuplot/
  DESTINATION ${CMAKE_INSTALL_DATADIR}/coatcontact/gnuplot)

# The license (BSD-3-Clause) and the citation travel with every installed copy.
install(FILES ${PROJECT_SOURCE_DIR}/LICENSE ${PROJECT_SOURCE_DIR}/CITATION.cff
  DESTINATION ${CMAKE_INSTALL_DOCDIR})

# CMake package: targets, config (finds what static libraries need), version.
install(EXPORT coatcontactTargets
  NAMESPACE coatcontact::
  DESTINATION ${COATCONTACT_CMAKE_DIR})
if(BUILD_SHARED_LIBS)
  set(COATCONTACT_STATIC OFF)
else()
  set(COATCONTACT_STATIC ON)
endif()
if(OpenMP_CXX_FOUND)
  set(COATCONTACT_OPENMP ON)
else()
  set(COATCONTACT_OPENMP OFF)
endif()
configure_package_config_file(
  ${PROJECT_SOURCE_DIR}/cmake/coatcontactConfig.cmake.in
  ${PROJECT_BINARY_DIR}/coatcontactConfig.cmake
  INSTALL_DESTINATION ${COATCONTACT_CMAKE_DIR})
# 0.x: a new minor version may change the API.
write_basic_package_version_file(
  ${PROJECT_BINARY_DIR}/coatcontactConfigVersion.cmake
  VERSION ${PROJECT_VERSION}
  COMPATIBILITY SameMinorVersion)
install(FILES
  ${PROJECT_BINARY_DIR}/coatcontactConfig.cmake
  ${PROJECT_BINARY_DIR}/coatcontactConfigVersion.cmake
  DESTINATION ${COATCONTACT_CMAKE_DIR})

# pkg-config: paths relative to the .pc file, so `cmake --install --prefix P` stays valid.
file(RELATIVE_PATH cc_pc_to_prefix ${CMAKE_INSTALL_FULL_LIBDIR}/pkgconfig ${CMAKE_INSTALL_PREFIX})
string(REGEX REPLACE "/$" "" cc_pc_to_prefix "${cc_pc_to_prefix}")
set(COATCONTACT_PC_PREFIX "\${pcfiledir}/${cc_pc_to_prefix}")
foreach(cc_dir LIBDIR INCLUDEDIR)
  if(IS_ABSOLUTE "${CMAKE_INSTALL_${cc_dir}}")
    set(COATCONTACT_PC_${cc_dir} "${CMAKE_INSTALL_${cc_dir}}")
  else()
    set(COATCONTACT_PC_${cc_dir} "\${prefix}/${CMAKE_INSTALL_${cc_dir}}")
  endif()
endforeach()
# Libs: the gfortran runtime. Libs.private (static linking): the C++ runtime and OpenMP.
list(TRANSFORM COATCONTACT_FORTRAN_RUNTIME PREPEND -l OUTPUT_VARIABLE cc_pc_libs)
string(JOIN " " COATCONTACT_PC_LIBS ${cc_pc_libs})
set(cc_pc_libs_private "")
foreach(cc_lib IN LISTS CMAKE_CXX_IMPLICIT_LINK_LIBRARIES)
  if(cc_lib MATCHES "^(stdc\\+\\+|c\\+\\+|m)$")
    list(APPEND cc_pc_libs_private -l${cc_lib})
  endif()
endforeach()
if(OpenMP_CXX_FOUND)
  list(TRANSFORM OpenMP_CXX_LIB_NAMES PREPEND -l OUTPUT_VARIABLE cc_omp_libs)
  list(APPEND cc_pc_libs_private ${cc_omp_libs})
endif()
list(REMOVE_DUPLICATES cc_pc_libs_private)
string(JOIN " " COATCONTACT_PC_LIBS_PRIVATE ${cc_pc_libs_private})
configure_file(${PROJECT_SOURCE_DIR}/cmake/coatcontact.pc.in
  ${PROJECT_BINARY_DIR}/coatcontact.pc @ONLY)
install(FILES ${PROJECT_BINARY_DIR}/coatcontact.pc
  DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig)
