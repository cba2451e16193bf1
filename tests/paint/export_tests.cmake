# Decal and export tests (owned by the paint-export helper).
adaptex_add_test(test_decal SOURCES test_decal.cpp LIBS adaptex::adaptex)
