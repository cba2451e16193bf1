"""Side-by-side renders of textured OBJs at equal size (docs/assets.md), by Blender itself (Cycles on
the CPU, headless; no window needed):

    blender -b --factory-startup --python bench/shrink/render_assets.py -- OUT.png SPEC [SPEC ...]
        [--size 512] [--view AZIMUTH,ELEVATION,ZOOM[,DX,DY]]

SPEC is LABEL=OBJ,TEXTURE. Every panel shows the texture's colour unlit (an emission shader: what
the texture holds, with no lighting to hide or invent detail), looked up as the measure does
(bilinear, "Linear" interpolation, clamp to edge), from the same camera. AZIMUTH/ELEVATION in degrees
(0,0 looks along -y at the model's front, +z up... after the OBJ importer's axis conversion), ZOOM > 1
frames a smaller part, DX/DY shift the framed centre in units of the model's radius. The panels are
joined left to right in the order given (the labels are printed, not drawn)."""
import math
import os
import sys
import tempfile

import bpy
from mathutils import Vector

args = sys.argv[sys.argv.index("--") + 1:]
out_png, specs, size, view = None, [], 512, (0.0, 0.0, 1.0, 0.0, 0.0)
i = 0
while i < len(args):
    if args[i] == "--size":
        size = int(args[i + 1]); i += 2
    elif args[i] == "--view":
        v = [float(x) for x in args[i + 1].split(",")]
        view = tuple(v + [0.0] * (5 - len(v))); i += 2
    elif out_png is None:
        out_png = args[i]; i += 1
    else:
        label, rest = args[i].split("=", 1)
        obj, tex = rest.split(",", 1)
        specs.append((label, obj, tex)); i += 1


def import_obj(path):
    before = set(bpy.data.objects)
    if hasattr(bpy.ops.wm, "obj_import"):
        bpy.ops.wm.obj_import(filepath=path)
    else:
        bpy.ops.import_scene.obj(filepath=path, split_mode="OFF")
    objs = [o for o in bpy.data.objects if o not in before and o.type == "MESH"]
    return objs[0]


def unlit_material(tex_path):
    mat = bpy.data.materials.new(os.path.basename(tex_path))
    mat.use_nodes = True
    nt = mat.node_tree
    for n in list(nt.nodes):
        nt.nodes.remove(n)
    tex = nt.nodes.new("ShaderNodeTexImage")
    tex.image = bpy.data.images.load(tex_path)
    tex.interpolation = "Linear"
    tex.extension = "EXTEND"
    em = nt.nodes.new("ShaderNodeEmission")
    out = nt.nodes.new("ShaderNodeOutputMaterial")
    nt.links.new(tex.outputs["Color"], em.inputs["Color"])
    nt.links.new(em.outputs["Emission"], out.inputs["Surface"])
    return mat


def render_one(obj_path, tex_path, png):
    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    scene.render.engine = "CYCLES"
    scene.cycles.device = "CPU"
    scene.cycles.samples = 16
    scene.cycles.use_denoising = False
    scene.render.resolution_x = scene.render.resolution_y = size
    scene.render.film_transparent = False
    scene.view_settings.view_transform = "Standard"  # the texture's sRGB values, not Filmic's curve
    world = bpy.data.worlds.new("w")
    world.color = (1, 1, 1)
    scene.world = world
    ob = import_obj(obj_path)
    ob.data.materials.clear()
    ob.data.materials.append(unlit_material(tex_path))
    pts = [ob.matrix_world @ v.co for v in ob.data.vertices]
    lo = Vector([min(p[k] for p in pts) for k in range(3)])
    hi = Vector([max(p[k] for p in pts) for k in range(3)])
    centre, radius = (lo + hi) / 2, (hi - lo).length / 2
    az, el, zoom, dx, dy = view
    d = Vector((math.sin(math.radians(az)) * math.cos(math.radians(el)),
                -math.cos(math.radians(az)) * math.cos(math.radians(el)), math.sin(math.radians(el))))
    right = Vector((0, 0, 1)).cross(-d).normalized() if abs(d.z) < 0.999 else Vector((1, 0, 0))
    up = (-d).cross(right).normalized()
    target = centre + right * (dx * radius) + up * (dy * radius)
    cam_data = bpy.data.cameras.new("cam")
    cam_data.type = "ORTHO"
    cam_data.ortho_scale = 2.1 * radius / zoom
    cam = bpy.data.objects.new("cam", cam_data)
    scene.collection.objects.link(cam)
    cam.location = target + d * (4 * radius)
    cam.rotation_euler = (-d).to_track_quat("-Z", "Y").to_euler()
    cam_data.clip_end = 10 * radius
    scene.camera = cam
    scene.render.filepath = png
    bpy.ops.render.render(write_still=True)


tmp = tempfile.mkdtemp(prefix="adaptex-render-")
panels = []
for k, (label, obj, tex) in enumerate(specs):
    png = os.path.join(tmp, f"{k}.png")
    render_one(os.path.abspath(obj), os.path.abspath(tex), png)
    panels.append((label, png))

# Join the panels left to right (Blender's image API: no other dependency).
bpy.ops.wm.read_factory_settings(use_empty=True)
W, H = size * len(panels), size
joined = [1.0] * (W * H * 4)
for k, (label, png) in enumerate(panels):
    img = bpy.data.images.load(png)
    px = list(img.pixels)
    for y in range(size):
        row = y * W + k * size
        joined[row * 4:(row + size) * 4] = px[y * size * 4:(y + 1) * size * 4]
out = bpy.data.images.new("joined", W, H)
out.pixels = joined
out.filepath_raw = out_png
out.file_format = "PNG"
out.save()
print("wrote", out_png, "panels:", ", ".join(label for label, _ in panels))
