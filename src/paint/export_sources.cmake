# Decals and export (owned by the paint-export helper).
target_sources(adaptex_paint PRIVATE
  decal.cpp
  export.cpp)
