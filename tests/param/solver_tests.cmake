# Tests of the solver part of adaptex_param (owner: param-solver).
adaptex_add_test(test_param_solver
  SOURCES ${CMAKE_CURRENT_LIST_DIR}/test_disk_param.cpp ${CMAKE_CURRENT_LIST_DIR}/test_stretch.cpp
  LIBS adaptex::param adaptex::core)
