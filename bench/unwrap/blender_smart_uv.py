# Effective texel share (coverage / L2², docs/bench_unwrap.md) of Blender's Smart UV Project next to
# adaptex's own layout, for issue 8's comparison. Runs inside Blender (Debian 12 `blender`, 3.4):
#
#   adaptex unwrap MESH -o ours.obj            # any format adaptex reads; Blender 3.4 has no OFF importer
#   blender -b --factory-startup --python bench/unwrap/blender_smart_uv.py -- ours.obj [margin]
#
# Prints one JSON line: {"mesh", "faces", "ours": {coverage, l2, share}, "smart_uv": {...}, "margin"}.
# "ours" measures the UVs in the OBJ (a check that this script's L2 matches adaptex's report); then
# Smart UV Project (angle limit 66°, the island margin given, default 0.02: Blender's own default of
# 0 leaves no gutter for the seam padding) replaces them and is measured the same way.
#
# L2 is Sander et al. 2001's stretch of the map texture -> surface, normalized so that a layout that is
# uniform up to scale has L2 = 1: L2² = (Σ_f A3_f (a_f + c_f) / 2 / Σ A3_f) · (Σ A2_f / Σ A3_f), with
# a = |∂p/∂s|², c = |∂p/∂t|² per face, A3 / A2 the surface / UV areas. Coverage = Σ A2_f (capped at 1).
import json
import math
import sys

import bmesh
import bpy


def measure(obj):
    bm = bmesh.new()
    bm.from_mesh(obj.data)
    bmesh.ops.triangulate(bm, faces=bm.faces[:])
    uv_layer = bm.loops.layers.uv.active
    s3 = s2 = acc = 0.0
    for f in bm.faces:
        p = [l.vert.co for l in f.loops]
        q = [l[uv_layer].uv for l in f.loops]
        a2 = 0.5 * ((q[1].x - q[0].x) * (q[2].y - q[0].y) - (q[2].x - q[0].x) * (q[1].y - q[0].y))
        a3 = 0.5 * (p[1] - p[0]).cross(p[2] - p[0]).length
        if a3 <= 0:
            continue
        s3 += a3
        if a2 <= 0:
            continue  # flipped or degenerate UV faces cover nothing
        s2 += a2
        ps = (p[0] * (q[1].y - q[2].y) + p[1] * (q[2].y - q[0].y) + p[2] * (q[0].y - q[1].y)) / (2 * a2)
        pt = (p[0] * (q[2].x - q[1].x) + p[1] * (q[0].x - q[2].x) + p[2] * (q[1].x - q[0].x)) / (2 * a2)
        acc += a3 * (ps.length_squared + pt.length_squared) / 2
    bm.free()
    l2 = math.sqrt(acc / s3 * s2 / s3) if s3 > 0 and s2 > 0 else float("inf")
    coverage = min(1.0, s2)
    return {"coverage": coverage, "l2": l2, "share": coverage / (l2 * l2)}


def main():
    args = sys.argv[sys.argv.index("--") + 1:]
    path = args[0]
    margin = float(args[1]) if len(args) > 1 else 0.02
    bpy.ops.wm.read_factory_settings(use_empty=True)
    bpy.ops.import_scene.obj(filepath=path)
    obj = [o for o in bpy.context.scene.objects if o.type == "MESH"][0]
    ours = measure(obj)
    bpy.context.view_layer.objects.active = obj
    obj.select_set(True)
    bpy.ops.object.mode_set(mode="EDIT")
    bpy.ops.mesh.select_all(action="SELECT")
    bpy.ops.uv.smart_project(angle_limit=math.radians(66.0), island_margin=margin)
    bpy.ops.object.mode_set(mode="OBJECT")
    smart = measure(obj)
    print("SMART_UV_JSON " + json.dumps({"mesh": path, "faces": len(obj.data.polygons), "ours": ours,
                                         "smart_uv": smart, "margin": margin}))


main()
