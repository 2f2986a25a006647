# Finds CHOLMOD and the SuiteSparse libraries it needs (Debian: libsuitesparse-dev).
# Debian 12 ships SuiteSparse 5.x without CMake config files, so we locate the libraries directly.
# Defines the imported target SuiteSparse::CHOLMOD. CHOLMOD calls BLAS/LAPACK through
# libblas.so.3 / liblapack.so.3, which Debian's alternatives point at OpenBLAS when
# libopenblas-dev is installed (the README's install command does that). rbla calls a few BLAS
# and LAPACK routines itself (the dense separator block of detail::SplitCholesky), so both are
# linked directly too.
find_path(SuiteSparseCholmod_INCLUDE_DIR cholmod.h PATH_SUFFIXES suitesparse)
foreach(lib cholmod amd camd colamd ccolamd suitesparseconfig lapack blas)
  find_library(SuiteSparseCholmod_${lib}_LIBRARY NAMES ${lib})
  list(APPEND SuiteSparseCholmod_LIBRARIES ${SuiteSparseCholmod_${lib}_LIBRARY})
  list(APPEND _rbla_ss_required SuiteSparseCholmod_${lib}_LIBRARY)
endforeach()
include(FindPackageHandleStandardArgs)
find_package_handle_standard_args(SuiteSparseCholmod REQUIRED_VARS SuiteSparseCholmod_INCLUDE_DIR ${_rbla_ss_required})
if(SuiteSparseCholmod_FOUND AND NOT TARGET SuiteSparse::CHOLMOD)
  add_library(SuiteSparse::CHOLMOD INTERFACE IMPORTED)
  set_target_properties(SuiteSparse::CHOLMOD PROPERTIES
    INTERFACE_INCLUDE_DIRECTORIES "${SuiteSparseCholmod_INCLUDE_DIR}"
    INTERFACE_LINK_LIBRARIES "${SuiteSparseCholmod_LIBRARIES}")
endif()
