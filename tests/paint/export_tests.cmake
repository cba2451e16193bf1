# Decal and export tests (owned by the paint-export helper).
adaptex_add_test(test_decal SOURCES test_decal.cpp LIBS adaptex::adaptex)
adaptex_add_test(test_export SOURCES test_export.cpp LIBS adaptex::adaptex TinyGLTF::TinyGLTF)
adaptex_add_test(test_paint_cli SOURCES test_paint_cli.cpp LIBS adaptex::adaptex nlohmann_json::nlohmann_json)
# A layered material (stroke file version 2) painted into PBR textures and exported.
adaptex_add_test(test_material_paint SOURCES test_material_paint.cpp LIBS adaptex::adaptex TinyGLTF::TinyGLTF
                 nlohmann_json::nlohmann_json)
# The Khronos glTF Validator on the exported .glb files (skips without node / the npm package).
add_test(NAME gltf_validator COMMAND ${Python3_EXECUTABLE} ${CMAKE_CURRENT_LIST_DIR}/gltf_validate.py
         $<TARGET_FILE:adaptex_cli>)
set_tests_properties(gltf_validator PROPERTIES SKIP_RETURN_CODE 77 TIMEOUT 300)
# Headless Blender imports the material's .glb and .obj with the right Principled BSDF inputs linked
# (skips without blender).
add_test(NAME blender_material_import
         COMMAND ${Python3_EXECUTABLE} ${CMAKE_CURRENT_LIST_DIR}/blender_material_import.py $<TARGET_FILE:adaptex_cli>)
set_tests_properties(blender_material_import PROPERTIES SKIP_RETURN_CODE 77 LABELS no_sanitize TIMEOUT 600)
# MikkTSpace tangents: the .glb's TANGENT and the frame of the normal map derived from height.
adaptex_add_test(test_tangent_frame SOURCES test_tangent_frame.cpp LIBS adaptex::adaptex TinyGLTF::TinyGLTF)
