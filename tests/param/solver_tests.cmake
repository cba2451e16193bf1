# Tests of the solver part of adaptex_param (owner: param-solver): stretch metrics, Floater, Yoshizawa.
adaptex_add_test(test_param_solver
  SOURCES ${CMAKE_CURRENT_LIST_DIR}/test_disk_param.cpp ${CMAKE_CURRENT_LIST_DIR}/test_stretch.cpp
  LIBS adaptex::param adaptex::core)
adaptex_add_test(test_param_solver_shared
  SOURCES ${CMAKE_CURRENT_LIST_DIR}/test_disk_param_shared.cpp
  LIBS adaptex::io adaptex::param adaptex::core)
# Issue 8: solver fallbacks, degenerate elements, tiny components (owner: param-solver).
adaptex_add_test(test_param_solver_robust
  SOURCES ${CMAKE_CURRENT_LIST_DIR}/test_solver_robust.cpp
  LIBS adaptex::param adaptex::core)
