# Solver part of adaptex_param: stretch metrics, Floater, Yoshizawa (§2.1.3, §2.2, §3.3).
target_sources(adaptex_param PRIVATE
  ${CMAKE_CURRENT_LIST_DIR}/stretch.cpp
  ${CMAKE_CURRENT_LIST_DIR}/floater.cpp
  ${CMAKE_CURRENT_LIST_DIR}/amg.cpp
  ${CMAKE_CURRENT_LIST_DIR}/yoshizawa.cpp
  ${CMAKE_CURRENT_LIST_DIR}/disk_param.cpp)
# UMFPACK (SuiteSparse, Debian libsuitesparse-dev) for the non-symmetric Tutte system; Eigen's SparseLU
# is used when it is missing.
find_path(ADAPTEX_UMFPACK_INCLUDE_DIR umfpack.h PATH_SUFFIXES suitesparse)
find_library(ADAPTEX_UMFPACK_LIBRARY umfpack)
find_library(ADAPTEX_AMD_LIBRARY amd)
set(ADAPTEX_FLOATER_DEFS "")
if(ADAPTEX_UMFPACK_INCLUDE_DIR AND ADAPTEX_UMFPACK_LIBRARY AND ADAPTEX_AMD_LIBRARY)
  target_include_directories(adaptex_param SYSTEM PRIVATE ${ADAPTEX_UMFPACK_INCLUDE_DIR})
  target_link_libraries(adaptex_param PRIVATE ${ADAPTEX_UMFPACK_LIBRARY} ${ADAPTEX_AMD_LIBRARY})
  set(ADAPTEX_FLOATER_DEFS ADAPTEX_HAVE_UMFPACK=1)
endif()
# KLU (SuiteSparse, Debian libsuitesparse-dev): the default direct backend for small and medium Tutte
# systems (cheap refactorization with the pivot order kept, Davis & Palamadai Natarajan 2010).
find_path(ADAPTEX_KLU_INCLUDE_DIR klu.h PATH_SUFFIXES suitesparse)
find_library(ADAPTEX_KLU_LIBRARY klu)
find_library(ADAPTEX_BTF_LIBRARY btf)
find_library(ADAPTEX_COLAMD_LIBRARY colamd)
if(ADAPTEX_KLU_INCLUDE_DIR AND ADAPTEX_KLU_LIBRARY AND ADAPTEX_BTF_LIBRARY AND ADAPTEX_COLAMD_LIBRARY
   AND ADAPTEX_AMD_LIBRARY)
  target_include_directories(adaptex_param SYSTEM PRIVATE ${ADAPTEX_KLU_INCLUDE_DIR})
  target_link_libraries(adaptex_param PRIVATE ${ADAPTEX_KLU_LIBRARY} ${ADAPTEX_BTF_LIBRARY}
    ${ADAPTEX_COLAMD_LIBRARY} ${ADAPTEX_AMD_LIBRARY})
  set(ADAPTEX_FLOATER_DEFS ${ADAPTEX_FLOATER_DEFS} ADAPTEX_HAVE_KLU=1)
endif()
set_source_files_properties(${CMAKE_CURRENT_LIST_DIR}/floater.cpp PROPERTIES
  COMPILE_DEFINITIONS "${ADAPTEX_FLOATER_DEFS}")
