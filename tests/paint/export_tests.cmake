# Decal and export tests (owned by the paint-export helper).
adaptex_add_test(test_decal SOURCES test_decal.cpp LIBS adaptex::adaptex)
adaptex_add_test(test_export SOURCES test_export.cpp LIBS adaptex::adaptex TinyGLTF::TinyGLTF)
adaptex_add_test(test_paint_cli SOURCES test_paint_cli.cpp LIBS adaptex::adaptex nlohmann_json::nlohmann_json)
