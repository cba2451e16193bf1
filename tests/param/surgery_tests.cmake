# Tests of the §3.2 surgery, packing and unwrap().
adaptex_add_test(test_param_cut SOURCES test_cut.cpp LIBS adaptex::adaptex)
adaptex_add_test(test_param_unwrap SOURCES test_unwrap.cpp LIBS adaptex::adaptex TBB::tbb)
adaptex_add_test(test_param_unwrap_cli SOURCES test_unwrap_cli.cpp
  LIBS adaptex::adaptex nlohmann_json::nlohmann_json)
adaptex_add_test(test_param_unwrap_shared SOURCES test_unwrap_shared.cpp LIBS adaptex::adaptex)
adaptex_add_test(test_param_charts SOURCES test_charts.cpp LIBS adaptex::adaptex)
adaptex_add_test(test_param_unfold SOURCES test_unfold.cpp LIBS adaptex::adaptex)
adaptex_add_test(test_param_slim SOURCES test_slim.cpp LIBS adaptex::adaptex)
adaptex_add_test(test_param_pack SOURCES test_pack.cpp test_pack_shapes.cpp LIBS adaptex::adaptex TBB::tbb)
adaptex_add_test(test_param_unwrap_scan SOURCES test_unwrap_scan.cpp LIBS adaptex::adaptex)
adaptex_add_test(test_param_unwrap_memory SOURCES test_unwrap_memory.cpp LIBS adaptex::adaptex)
adaptex_add_test(test_param_planar SOURCES test_planar.cpp LIBS adaptex::adaptex)
