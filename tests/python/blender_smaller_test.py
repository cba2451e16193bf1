"""Headless Blender test of "make N× smaller" (Adapt layout to paint) on meshes built here, run by
run_blender.py inside `blender -b --python`.

argv after "--": ADDON_ZIP BACKEND(MODULE|CLI) MODULE_DIR CLI WORKDIR
Checks that the operator reads the UV map the image is painted on (a UV Map node's, else the
render-active one), never merely the active one; shows both PSNRs; keeps the original assigned with a
warning when the result is not better than plain downsizing; and that a failed job (a non-manifold
mesh to unwrap, a NaN in the painted UV map) leaves the mesh exactly as it was, with a message that
names no command-line flag, for both operators ('Triangulate first' included)."""
import os
import sys

import numpy

if "bool" not in vars(numpy):
    numpy.bool = bool  # Debian's Blender 3.4 glTF add-on uses np.bool (removed in numpy 1.24); tests only

import bpy  # noqa: E402
import numpy as np  # noqa: E402

addon_zip, which, module_dir, cli, work = sys.argv[sys.argv.index("--") + 1:]
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from shapes import grid  # noqa: E402


def check(cond, what):
    if not cond:
        raise AssertionError(what)


bpy.ops.wm.read_factory_settings(use_empty=True)
bpy.ops.preferences.addon_install(filepath=addon_zip)
bpy.ops.preferences.addon_enable(module="adaptex_blender")
from adaptex_blender import meshdata  # noqa: E402

prefs = bpy.context.preferences.addons["adaptex_blender"].preferences
prefs.backend, prefs.module_path, prefs.cli_path = which, module_dir, cli


def detail_texture(n=256):
    """Flat grey with sharp stripes in one corner: adapting the layout beats downsizing (+4 dB at 64²)."""
    t = np.full((n, n, 4), 200, np.uint8)
    t[..., 3] = 255
    a, b = int(0.6 * n), int(0.95 * n)
    for k in range(a, b):
        if (k // 3) % 2 == 0:
            t[a:b, k, :3] = (30, 60, 160)
    t[a:b:7, a:b, :3] = (250, 40, 40)
    return t


def textured_grid(name, texture, linked_uv_node):
    """A 16 x 16 grid with two UV maps: 'painted' (the layout of \\p texture) and 'decoy' (another
    layout), 'decoy' active. With \\p linked_uv_node the image node reads 'painted' through a UV Map
    node and 'decoy' is also the render map; without, 'painted' is the render map."""
    V, F = grid(16)
    me = bpy.data.meshes.new(name)
    me.from_pydata(V.tolist(), [], F.tolist())
    painted = me.uv_layers.new(name="painted")
    painted.data.foreach_set("uv", V[F][:, :, :2].reshape(-1).astype(np.float32))
    decoy = me.uv_layers.new(name="decoy")
    decoy.data.foreach_set("uv", (0.25 + 0.5 * V[F][:, :, 1::-1]).reshape(-1).astype(np.float32))
    me.uv_layers.active = decoy
    (decoy if linked_uv_node else painted).active_render = True
    obj = bpy.data.objects.new(name, me)
    bpy.context.scene.collection.objects.link(obj)
    img = meshdata.new_image(bpy, name + "_paint", texture)
    mat = bpy.data.materials.new(name)
    mat.use_nodes = True
    node = mat.node_tree.nodes.new("ShaderNodeTexImage")
    node.image = img
    mat.node_tree.links.new(node.outputs["Color"], mat.node_tree.nodes["Principled BSDF"].inputs["Base Color"])
    uvnode = None
    if linked_uv_node:
        uvnode = mat.node_tree.nodes.new("ShaderNodeUVMap")
        uvnode.uv_map = "painted"
        mat.node_tree.links.new(uvnode.outputs["UV"], node.inputs["Vector"])
    me.materials.append(mat)
    for o in bpy.context.view_layer.objects:
        o.select_set(False)
    bpy.context.view_layer.objects.active = obj
    obj.select_set(True)
    return obj, node, uvnode


def state(obj):
    """Everything about the object a failed job must leave alone."""
    me = obj.data
    uv = {}
    for layer in me.uv_layers:
        a = np.empty(2 * len(me.loops))
        layer.data.foreach_get("uv", a)
        uv[layer.name] = a.tobytes()
    co = np.empty(3 * len(me.vertices))
    me.vertices.foreach_get("co", co)
    images = [(n.name, n.image.name if n.image else None) for s in obj.material_slots if s.material
              for n in s.material.node_tree.nodes if n.type == "TEX_IMAGE"]
    return (len(me.polygons), [len(p.vertices) for p in me.polygons], co.tobytes(), uv,
            me.uv_layers.active.name if me.uv_layers.active else None,
            [layer.name for layer in me.uv_layers if layer.active_render], images, sorted(bpy.data.meshes.keys()))


# ---- the painted UV map through a UV Map node, while another map is active and render-active ------
obj, node, uvnode = textured_grid("linked", detail_texture(), linked_uv_node=True)
original = node.image
check(bpy.ops.adaptex.adapt_layout(scale="4") == {"FINISHED"}, "adapt operator failed")
res = bpy.context.scene["adaptex_last"].to_dict()
print("linked:", res)
check(res["uv_source"] == "painted" and res["uv_map"] == "painted_adaptex", res)
check(res["psnr"] > res["psnr_plain"] + 1.0, f"adapted {res['psnr']:.2f} vs plain {res['psnr_plain']:.2f} dB")
check(res["assigned"] and node.image.name == res["image"] and node.image != original, "result not assigned")
check(uvnode.uv_map == "painted_adaptex", f"the UV Map node reads {uvnode.uv_map}")
check(node.extension == "EXTEND", "the new image is not clamped at its border")
check(obj.data.uv_layers["decoy"].active_render, "the render UV map of the other textures changed")

# ---- no UV Map node: the render-active map ('painted'), not the active one ('decoy') --------------
obj, node, _ = textured_grid("unlinked", detail_texture(), linked_uv_node=False)
check(bpy.ops.adaptex.adapt_layout(scale="4") == {"FINISHED"}, "adapt operator failed")
res = bpy.context.scene["adaptex_last"].to_dict()
print("unlinked:", res)
check(res["uv_source"] == "painted" and res["assigned"], res)
links = node.inputs["Vector"].links
check(len(links) == 1 and links[0].from_node.type == "UVMAP" and links[0].from_node.uv_map == res["uv_map"],
      "the image node does not read the new UV map")
check(obj.data.uv_layers["painted"].active_render, "the render UV map changed")

# ---- not better than plain downsizing (a flat image): the original stays, with a warning ----------
flat = np.full((128, 128, 4), 90, np.uint8)
flat[..., 3] = 255
obj, node, uvnode = textured_grid("flat", flat, linked_uv_node=True)
original, active = node.image, obj.data.uv_layers.active.name
check(bpy.ops.adaptex.adapt_layout(scale="4") == {"FINISHED"}, "adapt operator failed")
res = bpy.context.scene["adaptex_last"].to_dict()
print("flat:", res)
check(res["psnr"] <= res["psnr_plain"] and not res["assigned"], res)
check(node.image == original and uvnode.uv_map == "painted", "the original is no longer assigned")
check(obj.data.uv_layers.active.name == active, "the active UV map changed")
check(res["image"] in bpy.data.images and res["uv_map"] in obj.data.uv_layers, "the result was not kept")

# ---- a failed job leaves the mesh as it was, and names no command-line flag ----------------------
def nonmanifold(name, quads):
    """Three faces on one edge (a fin): every adaptex reader rejects it."""
    if quads:
        V = [(0, 0, 0), (0, 0, 1), (1, 0, 0), (1, 0, 1), (-1, 0, 0), (-1, 0, 1), (0, 1, 0), (0, 1, 1)]
        P = [(0, 2, 3, 1), (1, 5, 4, 0), (0, 6, 7, 1)]
    else:
        V = [(0, 0, 0), (0, 0, 1), (1, 0, 0.5), (-1, 0, 0.5), (0, 1, 0.5)]
        P = [(0, 2, 1), (1, 3, 0), (0, 4, 1)]
    me = bpy.data.meshes.new(name)
    me.from_pydata(V, [], P)
    layer = me.uv_layers.new(name="painted")
    layer.data.foreach_set("uv", np.random.default_rng(1).random(2 * len(me.loops)).astype(np.float32))
    o = bpy.data.objects.new(name, me)
    bpy.context.scene.collection.objects.link(o)
    img = meshdata.new_image(bpy, name + "_paint", detail_texture(64))
    mat = bpy.data.materials.new(name)
    mat.use_nodes = True
    mat.node_tree.nodes.new("ShaderNodeTexImage").image = img
    me.materials.append(mat)
    bpy.context.view_layer.objects.active = o
    return o


def expect_failure(op, kwargs, obj, needle):
    before = state(obj)
    try:
        op(**kwargs)
        check(False, f"{op.idname()} did not fail")
    except RuntimeError as e:
        msg = str(e)
        print(f"{op.idname()} {kwargs}: {msg.strip()}")
        check("--" not in msg, f"the message names a command-line flag: {msg}")
        check(needle in msg, msg)
    check(state(obj) == before, f"{op.idname()} {kwargs}: the failed job changed the mesh")


for op, kwargs, quads in [(bpy.ops.adaptex.unwrap, {"triangulate": True}, True), (bpy.ops.adaptex.unwrap, {}, False)]:
    expect_failure(op, kwargs, nonmanifold(f"fin_{quads}", quads), "manifold")
# A painted UV map with a NaN: every backend refuses it.
obj, node, _ = textured_grid("nan", detail_texture(), linked_uv_node=False)
uv = np.empty(2 * len(obj.data.loops), dtype=np.float32)
obj.data.uv_layers["painted"].data.foreach_get("uv", uv)
uv[7] = np.nan
obj.data.uv_layers["painted"].data.foreach_set("uv", uv)
expect_failure(bpy.ops.adaptex.adapt_layout, {"scale": "2"}, obj, "finite")

print("ADAPTEX_BLENDER_OK", which)
