# Decals and export (owned by the paint-export helper).
target_sources(adaptex_paint PRIVATE
  decal.cpp
  ray_scene.cpp  # the Embree scene of a mesh: decal visibility, the studio's picking
  export.cpp
  tangent_frame.cpp)  # vertex normals, MikkTSpace tangents: the .glb's TANGENT and the normal map's frame
