# Imported targets for every external dependency (no global flag variables).
find_package(GSL REQUIRED)                # GSL::gsl, GSL::gslcblas
find_package(LAPACK REQUIRED)             # LAPACK::LAPACK
find_package(PkgConfig REQUIRED)
pkg_check_modules(FFTW3 REQUIRED IMPORTED_TARGET fftw3)      # PkgConfig::FFTW3
pkg_check_modules(LAPACKE REQUIRED IMPORTED_TARGET lapacke)  # PkgConfig::LAPACKE
pkg_check_modules(LIBZIP REQUIRED IMPORTED_TARGET libzip)    # PkgConfig::LIBZIP (AFM archives)
pkg_check_modules(FREEXL REQUIRED IMPORTED_TARGET freexl)    # PkgConfig::FREEXL (NanoSuite .xls)
find_package(Threads REQUIRED)           # Threads::Threads (the FFTW planner lock)
find_package(OpenMP COMPONENTS CXX)       # OpenMP::OpenMP_CXX (optional)

# The Fortran interface file fftw3.f03 ships with libfftw3-dev in the include dir.
find_path(FFTW3_FORTRAN_INCLUDE_DIR fftw3.f03 HINTS ${FFTW3_INCLUDE_DIRS} PATHS /usr/include REQUIRED)

# The gfortran runtime, named for consumers of the static libraries and in coatcontact.pc.
set(COATCONTACT_FORTRAN_RUNTIME "")
foreach(cc_lib IN LISTS CMAKE_Fortran_IMPLICIT_LINK_LIBRARIES)
  if(cc_lib MATCHES "^(gfortran|quadmath)$")
    list(APPEND COATCONTACT_FORTRAN_RUNTIME ${cc_lib})
  endif()
endforeach()
list(REMOVE_DUPLICATES COATCONTACT_FORTRAN_RUNTIME)
