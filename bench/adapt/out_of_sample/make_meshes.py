# Blender 3.4 script: four meshes that the quality study has never seen, made from Blender's own
# primitives (seeded, so the files are the same on every run). Used by out_of_sample.sh:
#   blender -b --factory-startup --python make_meshes.py -- OUTDIR
# suzanne      Suzanne, subdivided twice (15.7k triangles, 4 boundary loops, separate eyes)
# ico_holes    icosphere (5 subdivisions) with 40 random faces deleted (38 loops, pinched vertices)
# torus_decim  torus 96x32 decimated to 30 % (1.8k triangles, slivers, genus 1)
# wavy_sheet   120x60 grid with a wave modifier (a disk, nearly developable)
import random
import sys

import bmesh
import bpy

out = sys.argv[sys.argv.index("--") + 1]
random.seed(7)


def clear():
    bpy.ops.object.select_all(action="SELECT")
    bpy.ops.object.delete()


def apply(obj, kind, **settings):
    mod = obj.modifiers.new("m", kind)
    for key, value in settings.items():
        setattr(mod, key, value)
    bpy.ops.object.modifier_apply(modifier="m")


def export(name):
    bpy.ops.object.select_all(action="SELECT")
    bpy.ops.export_scene.obj(filepath=f"{out}/{name}.obj", use_selection=True, use_materials=False,
                             use_uvs=False, use_normals=False, use_triangles=True)


clear()
bpy.ops.mesh.primitive_monkey_add()
apply(bpy.context.object, "SUBSURF", levels=2)
export("suzanne")

clear()
bpy.ops.mesh.primitive_ico_sphere_add(subdivisions=5)
obj = bpy.context.object
bm = bmesh.new()
bm.from_mesh(obj.data)
faces = list(bm.faces)
random.shuffle(faces)
bmesh.ops.delete(bm, geom=faces[:40], context="FACES")
bm.to_mesh(obj.data)
export("ico_holes")

clear()
bpy.ops.mesh.primitive_torus_add(major_segments=96, minor_segments=32)
apply(bpy.context.object, "DECIMATE", ratio=0.3)
export("torus_decim")

clear()
bpy.ops.mesh.primitive_grid_add(x_subdivisions=120, y_subdivisions=60, size=2)
apply(bpy.context.object, "WAVE")
export("wavy_sheet")
