# Surgery part of adaptex_param: topological surgery (§3.2), chart packing,
# the unwrap() pipeline.
target_sources(adaptex_param PRIVATE
  ${CMAKE_CURRENT_LIST_DIR}/charts.cpp
  ${CMAKE_CURRENT_LIST_DIR}/cut.cpp
  ${CMAKE_CURRENT_LIST_DIR}/pack.cpp
  ${CMAKE_CURRENT_LIST_DIR}/unfold.cpp
  ${CMAKE_CURRENT_LIST_DIR}/lscm.cpp
  ${CMAKE_CURRENT_LIST_DIR}/slim.cpp
  ${CMAKE_CURRENT_LIST_DIR}/planar.cpp
  ${CMAKE_CURRENT_LIST_DIR}/layout_image.cpp
  ${CMAKE_CURRENT_LIST_DIR}/unwrap.cpp
  ${CMAKE_CURRENT_LIST_DIR}/unwrap_chart.cpp
  ${CMAKE_CURRENT_LIST_DIR}/unwrap_pack.cpp
  ${CMAKE_CURRENT_LIST_DIR}/unwrap_scan.cpp)
