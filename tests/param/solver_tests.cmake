# Tests of the solver part of adaptex_param: stretch metrics, Floater, Yoshizawa.
adaptex_add_test(test_param_solver
  SOURCES ${CMAKE_CURRENT_LIST_DIR}/test_disk_param.cpp ${CMAKE_CURRENT_LIST_DIR}/test_stretch.cpp
  LIBS adaptex::param adaptex::core)
adaptex_add_test(test_param_solver_shared
  SOURCES ${CMAKE_CURRENT_LIST_DIR}/test_disk_param_shared.cpp
  LIBS adaptex::io adaptex::param adaptex::core)
# Solver fallbacks, degenerate elements, tiny components.
adaptex_add_test(test_param_solver_robust
  SOURCES ${CMAKE_CURRENT_LIST_DIR}/test_solver_robust.cpp
  LIBS adaptex::param adaptex::core)
