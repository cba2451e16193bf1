"""Headless Blender test of the add-on (run by run_blender.py inside `blender -b --python`).

argv after "--": ADDON_ZIP BACKEND(MODULE|CLI|INSTALLED) MODULE_DIR CLI WORKDIR
Installs the zipped add-on, paints a mesh with the adaptex CLI, runs "Unwrap with adaptex" and
"Adapt layout to paint" (4x smaller) and checks the new UV maps (no flips, in [0,1]^2), the new
image, the originals, that the adapted image beats plain downsizing to the same size (PSNR against
the original, and against the exact strokes with `adaptex eval`), and that a job cancels."""
import os
import subprocess
import sys
import time

import numpy

if "bool" not in vars(numpy):
    numpy.bool = bool  # Debian's Blender 3.4 glTF add-on uses np.bool (removed in numpy 1.24); tests only

import bpy  # noqa: E402
import numpy as np  # noqa: E402

addon_zip, which, module_dir, cli, work = sys.argv[sys.argv.index("--") + 1:]


def check(cond, what):
    if not cond:
        raise AssertionError(what)


def signed_areas(UV, FT):
    a, b, c = UV[FT[:, 0]], UV[FT[:, 1]], UV[FT[:, 2]]
    return 0.5 * ((b[:, 0] - a[:, 0]) * (c[:, 1] - a[:, 1]) - (b[:, 1] - a[:, 1]) * (c[:, 0] - a[:, 0]))


def check_layout(me, layer, loops):
    uv = np.empty(2 * len(me.loops))
    layer.data.foreach_get("uv", uv)
    uv = uv.reshape(-1, 2)
    tri = uv[loops]  # #T x 3 x 2
    area = 0.5 * ((tri[:, 1, 0] - tri[:, 0, 0]) * (tri[:, 2, 1] - tri[:, 0, 1]) -
                  (tri[:, 1, 1] - tri[:, 0, 1]) * (tri[:, 2, 0] - tri[:, 0, 0]))
    check((area > 0).all(), f"{layer.name}: {int((area <= 0).sum())} flipped or degenerate UV triangles")
    check(uv.min() >= -1e-6 and uv.max() <= 1 + 1e-6, f"{layer.name}: UVs outside [0,1]^2: {uv.min()} {uv.max()}")


def run_cli(*args):
    r = subprocess.run([cli, "-q", *map(str, args)], capture_output=True, text=True)
    check(r.returncode == 0, r.stderr)
    return r.stdout


# ---- install and enable the add-on from its zip ------------------------------------------------
bpy.ops.wm.read_factory_settings(use_empty=True)
bpy.ops.preferences.addon_install(filepath=addon_zip)
bpy.ops.preferences.addon_enable(module="adaptex_blender")
import adaptex_blender  # noqa: E402
from adaptex_blender import backend, meshdata  # noqa: E402

prefs = bpy.context.preferences.addons["adaptex_blender"].preferences
if which == "INSTALLED":  # the zip `cmake --install` made, no preferences: it finds the installed module
    check(os.path.dirname(backend.find_cli()) == os.path.dirname(cli), backend.find_cli())
    which = "MODULE"
else:
    prefs.backend, prefs.module_path, prefs.cli_path = which, module_dir, cli
# The panels follow Blender's naming, and the 3D View's shows in Object and Texture Paint mode only.
check(hasattr(bpy.types, "ADAPTEX_PT_view3d") and hasattr(bpy.types, "ADAPTEX_PT_uv_editor"), "panels")
check(not any(n.endswith("_PT_adaptex") for n in dir(bpy.types)), "an old panel name is still registered")
for mode, shown in (("OBJECT", True), ("PAINT_TEXTURE", True), ("EDIT_MESH", False), ("SCULPT", False)):
    check(bool(adaptex_blender.ADAPTEX_PT_view3d.poll(type("Context", (), {"mode": mode}))) == shown, mode)
chosen = adaptex_blender.choose_backend(bpy.context)
check(chosen.name == {"MODULE": "Python module", "CLI": "adaptex CLI"}[which], chosen.name)

# ---- a painted mesh: a sphere painted with the CLI on its own layout at 512 x 512 --------------
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from shapes import uv_sphere  # noqa: E402

V, F = uv_sphere(64, 32)
backend.write_obj(os.path.join(work, "ball.obj"), V, F)
run_cli("strokes", "generate", os.path.join(work, "ball.obj"), "--kind", "lines", "--seed", 2,
        "-o", os.path.join(work, "s.json"))
run_cli("paint", os.path.join(work, "ball.obj"), "--strokes", os.path.join(work, "s.json"), "--size", 512,
        "--adapt", "none", "-o", os.path.join(work, "p"))
UV0, FT0 = backend.read_obj_layout(os.path.join(work, "p", "ball.obj"), F)

me = bpy.data.meshes.new("ball")
me.from_pydata(V.tolist(), [], F.tolist())
painted_layer = me.uv_layers.new(name="painted")
painted_layer.data.foreach_set("uv", UV0[FT0].reshape(-1).astype(np.float32))  # loops are the face corners
obj = bpy.data.objects.new("ball", me)
bpy.context.scene.collection.objects.link(obj)
bpy.context.view_layer.objects.active = obj
obj.select_set(True)
painted = bpy.data.images.load(os.path.join(work, "p", "ball.png"))
painted.name = "painted"
painted.pack()
mat = bpy.data.materials.new("paint")
mat.use_nodes = True
node = mat.node_tree.nodes.new("ShaderNodeTexImage")
node.image = painted
mat.node_tree.links.new(node.outputs["Color"], mat.node_tree.nodes["Principled BSDF"].inputs["Base Color"])
me.materials.append(mat)
original_pixels = meshdata.image_pixels(painted)
Vb, Fb, loops = meshdata.triangles(me)  # what the operators read: Blender keeps float32 positions
check(np.array_equal(Fb, F) and np.allclose(Vb, V, atol=1e-6), "Blender changed the mesh")
V = Vb

# ---- Unwrap with adaptex ------------------------------------------------------------------------
t = time.perf_counter()
check(bpy.ops.adaptex.unwrap() == {"FINISHED"}, "unwrap operator failed")
check("adaptex" in me.uv_layers and me.uv_layers.active.name == "adaptex", list(me.uv_layers.keys()))
check_layout(me, me.uv_layers["adaptex"], loops)
print(f"unwrap operator: {time.perf_counter() - t:.2f} s")

# ---- Adapt layout to paint, 4x smaller ----------------------------------------------------------
me.uv_layers.active = me.uv_layers["painted"]
t = time.perf_counter()
check(bpy.ops.adaptex.adapt_layout(scale="4") == {"FINISHED"}, "adapt operator failed")
print(f"adapt operator: {time.perf_counter() - t:.2f} s")
res = bpy.context.scene["adaptex_last"].to_dict()
print("adapt result:", res)
new_img = bpy.data.images[res["image"]]
check(tuple(new_img.size) == (128, 128) and res["size"] == 128, tuple(new_img.size))
check(res["uv_map"] == "painted_adaptex" and me.uv_layers.active.name == "painted_adaptex", res["uv_map"])
check_layout(me, me.uv_layers["painted_adaptex"], loops)
check(node.image == new_img, "the material's image node shows the new image")
# The originals are kept, unchanged.
check("painted" in bpy.data.images and np.array_equal(meshdata.image_pixels(painted), original_pixels),
      "original image changed")
old = np.empty(2 * len(me.loops))
me.uv_layers["painted"].data.foreach_get("uv", old)
check(np.allclose(old.reshape(-1, 2), UV0[FT0].reshape(-1, 2), atol=1e-6), "original UV map changed")
new_pixels = meshdata.image_pixels(new_img)
check(len(np.unique(new_pixels.reshape(-1, 4), axis=0)) > 10, "the new image is not a painting")
# At equal size the adapted image beats plain downsizing (PSNR against the original painting) ...
check(res["gain"] > 0.5, f"adapted {res['psnr']:.2f} dB vs plain downsizing {res['psnr_plain']:.2f} dB")
# ... and against the exact strokes (adaptex eval of both 128 x 128 results).
UVa, FTa = meshdata.wedges(me, me.uv_layers["painted_adaptex"], loops)
backend.write_obj(os.path.join(work, "adapted.obj"), V, F, UVa, FTa)
meshdata.write_png(os.path.join(work, "adapted.png"), new_pixels)
backend.write_obj(os.path.join(work, "plain.obj"), V, F, UV0, FT0)
meshdata.write_png(os.path.join(work, "plain.png"), meshdata.area_resize(original_pixels, 128, 128))
import json  # noqa: E402
e_adapt = json.loads(run_cli("eval", os.path.join(work, "adapted.obj"), os.path.join(work, "adapted.png"),
                             os.path.join(work, "s.json"), "--samples", 200000))["psnr"]
e_plain = json.loads(run_cli("eval", os.path.join(work, "plain.obj"), os.path.join(work, "plain.png"),
                             os.path.join(work, "s.json"), "--samples", 200000))["psnr"]
print(f"against the strokes: adapted {e_adapt:.2f} dB, plain downsizing {e_plain:.2f} dB")
check(e_adapt > e_plain + 0.5, (e_adapt, e_plain))
UVp, FTp = meshdata.wedges(me, me.uv_layers["painted"], loops)  # what the operator read (float32 UVs)
if which == "MODULE":  # the CLI backend gives the same UVs and texture bytes as the module
    UVm, FTm, texm = chosen.reparam(V, F, UVp, FTp, original_pixels, 128, lambda p, f: True)
    UVc, FTc, png = backend.CliBackend(cli).reparam(V, F, UVp, FTp, original_pixels, 128, lambda p, f: True)
    check(UVm.tobytes() == UVc.tobytes() and np.array_equal(FTm, FTc), "module and CLI layouts differ")
    check(texm.tobytes() == meshdata.read_png(bpy, png).tobytes(), "module and CLI textures differ")
    check(np.array_equal(texm, new_pixels), "the operator's image is not the module's texture")

# ---- a quad mesh: "Triangulate first" gives an exact layout; no painted image is an error ---------
bpy.ops.mesh.primitive_uv_sphere_add(segments=24, ring_count=12, location=(4, 0, 0))
quads = bpy.context.active_object
check(bpy.ops.adaptex.unwrap(triangulate=True) == {"FINISHED"}, "unwrap of a quad mesh failed")
check(all(len(p.vertices) == 3 for p in quads.data.polygons), "not triangulated")
check_layout(quads.data, quads.data.uv_layers["adaptex"], meshdata.triangles(quads.data)[2])
try:
    bpy.ops.adaptex.adapt_layout()
    check(False, "adapt without a painted image did not fail")
except RuntimeError as e:
    check("no painted image" in str(e), str(e))
bpy.context.view_layer.objects.active = obj

# ---- a background job cancels -------------------------------------------------------------------
job = backend.Job(lambda report: chosen.reparam(V, F, UVp, FTp, original_pixels, 128, report))
job.cancel()
job.start()
while not job.done:
    time.sleep(0.01)
check(isinstance(job.error, backend.Cancelled), repr(job.error))
job = backend.Job(lambda report: chosen.unwrap(V, F, report))
job.start()
while not job.done:
    time.sleep(0.01)
check(job.error is None and job.result[0].shape[1] == 2, repr(job.error))
print("ADAPTEX_BLENDER_OK", which)
