# Sources of the paint area owned by the brush work: stroke file, texel map, painter, signal,
# seam padding, evaluation, stroke generation.
target_sources(adaptex_paint PRIVATE
  ${CMAKE_CURRENT_LIST_DIR}/strokes.cpp
  ${CMAKE_CURRENT_LIST_DIR}/texel_map.cpp
  ${CMAKE_CURRENT_LIST_DIR}/texel_grid.cpp
  ${CMAKE_CURRENT_LIST_DIR}/padding.cpp
  ${CMAKE_CURRENT_LIST_DIR}/painter.cpp
  ${CMAKE_CURRENT_LIST_DIR}/signal.cpp
  ${CMAKE_CURRENT_LIST_DIR}/eval.cpp
  ${CMAKE_CURRENT_LIST_DIR}/generate.cpp
  ${CMAKE_CURRENT_LIST_DIR}/texel_saving.cpp
  ${CMAKE_CURRENT_LIST_DIR}/asset_eval.cpp       # surface PSNR of shrunk assets, box downsizing
  ${CMAKE_CURRENT_LIST_DIR}/point_transfer.cpp   # sample points carried to a refined mesh
  ${CMAKE_CURRENT_LIST_DIR}/surface_lattice.cpp    # the surface caches' per-face sample lattice
  ${CMAKE_CURRENT_LIST_DIR}/surface_cache.cpp)
# The stroke file version 2 (layered materials) and its exact evaluation at surface points.
target_sources(adaptex_paint PRIVATE
  ${CMAKE_CURRENT_LIST_DIR}/material_strokes.cpp
  ${CMAKE_CURRENT_LIST_DIR}/material_signal.cpp
  ${CMAKE_CURRENT_LIST_DIR}/material_generate.cpp
  ${CMAKE_CURRENT_LIST_DIR}/material_paint.cpp
  ${CMAKE_CURRENT_LIST_DIR}/material_eval.cpp
  ${CMAKE_CURRENT_LIST_DIR}/material_point_cache.cpp    # incremental per-layer state at fixed points
  ${CMAKE_CURRENT_LIST_DIR}/material_surface_cache.cpp)  # ... at the surface lattice's samples
