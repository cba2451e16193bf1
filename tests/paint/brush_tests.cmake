# Tests of the brush part of the paint area (strokes, texel map, painter, padding, signal, eval,
# generate, their CLI commands).
adaptex_add_test(test_paint_strokes SOURCES ${CMAKE_CURRENT_LIST_DIR}/test_strokes.cpp LIBS adaptex::paint)
adaptex_add_test(test_paint_generate SOURCES ${CMAKE_CURRENT_LIST_DIR}/test_generate.cpp LIBS adaptex::paint)
adaptex_add_test(test_paint_texel_saving SOURCES ${CMAKE_CURRENT_LIST_DIR}/test_texel_saving.cpp LIBS adaptex::paint)
adaptex_add_test(test_paint_brush SOURCES ${CMAKE_CURRENT_LIST_DIR}/test_painter.cpp LIBS adaptex::paint)
adaptex_add_test(test_paint_brush_cli SOURCES ${CMAKE_CURRENT_LIST_DIR}/test_brush_cli.cpp
                 LIBS adaptex::paint adaptex::io nlohmann_json::nlohmann_json)
adaptex_add_test(test_paint_material_strokes SOURCES ${CMAKE_CURRENT_LIST_DIR}/test_material_strokes.cpp LIBS adaptex::paint)
adaptex_add_test(test_paint_material_eval SOURCES ${CMAKE_CURRENT_LIST_DIR}/test_material_eval.cpp LIBS adaptex::paint)
