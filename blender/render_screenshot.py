"""The pictures of docs/blender.md, made by Blender itself.

    blender -b --factory-startup --python blender/render_screenshot.py -- OUT.png BUILD_DIR
renders (Cycles on the CPU, headless) a painted sphere (512 x 512), the same painting plainly
downsized to 128 x 128, and the layout adapted to the paint by the add-on's "Adapt layout to paint"
at 128 x 128;

    xvfb-run -s "-screen 0 1600x900x24" blender --factory-startup --python blender/render_screenshot.py -- OUT.png BUILD_DIR ui
opens Blender's window, runs "Adapt layout to paint" from the UI (in the background, with the
progress bar) and saves a screenshot of the window once it has finished.

BUILD_DIR holds python/adaptex (the module) and apps/cli/adaptex (the CLI, for the strokes)."""
import json
import os
import subprocess
import sys
import tempfile

import bpy
import numpy as np
from mathutils import Vector

args = sys.argv[sys.argv.index("--") + 1:]
out_png, build, mode = args[0], args[1], (args[2] if len(args) > 2 else "render")
here = os.path.dirname(os.path.abspath(__file__))
sys.path[:0] = [here, os.path.join(build, "python")]
import adaptex  # noqa: E402
import adaptex_blender  # noqa: E402
from adaptex_blender import backend, meshdata  # noqa: E402


def material(image_name, uv_map):
    mat = bpy.data.materials.new(image_name)
    mat.use_nodes = True
    nt = mat.node_tree
    tex = nt.nodes.new("ShaderNodeTexImage")
    tex.image = bpy.data.images[image_name]
    uvn = nt.nodes.new("ShaderNodeUVMap")
    uvn.uv_map = uv_map
    nt.links.new(uvn.outputs["UV"], tex.inputs["Vector"])
    nt.links.new(tex.outputs["Color"], nt.nodes["Principled BSDF"].inputs["Base Color"])
    return mat


def painted_sphere():
    """A sphere unwrapped by the add-on and painted (512 x 512, generated lines) by the module; its
    painted side turned towards -y. Returns (object, painted texture)."""
    bpy.ops.mesh.primitive_uv_sphere_add(segments=64, ring_count=32)
    obj = bpy.context.active_object
    bpy.ops.object.shade_smooth()
    bpy.ops.adaptex.unwrap(triangulate=True)
    me = obj.data
    V, F, loops = meshdata.triangles(me)
    UV, FT = meshdata.wedges(me, me.uv_layers["adaptex"], loops)
    tmp = tempfile.mkdtemp(prefix="adaptex-shot-")
    backend.write_obj(os.path.join(tmp, "ball.obj"), V, F)
    subprocess.run([os.path.join(build, "apps", "cli", "adaptex"), "-q", "strokes", "generate",
                    os.path.join(tmp, "ball.obj"), "--kind", "lines", "--seed", "2", "-o", os.path.join(tmp, "s.json")],
                   check=True, capture_output=True)
    painted = adaptex.paint(V, F, UV, FT, os.path.join(tmp, "s.json"), size=512)
    meshdata.new_image(bpy, "painted", painted)
    me.materials.append(material("painted", "adaptex"))
    strokes = json.load(open(os.path.join(tmp, "s.json")))
    centre = Vector(np.mean([d for s in strokes["strokes"] for d in s["dabs"]], axis=0).tolist())
    obj.rotation_euler = centre.normalized().rotation_difference(Vector((0.0, -1.0, 0.35)).normalized()).to_euler()
    return obj, painted


def render_comparison():
    bpy.ops.wm.read_factory_settings(use_empty=True)
    adaptex_blender.register()
    obj, painted = painted_sphere()
    bpy.ops.adaptex.adapt_layout(image="painted", scale="4", assign=False)
    res = bpy.context.scene["adaptex_last"].to_dict()
    meshdata.new_image(bpy, "plain_128", meshdata.area_resize(painted, 128, 128))
    spheres = [("painted", "adaptex", "painted 512 x 512"),
               ("plain_128", "adaptex", f"plain downsizing 128 x 128\n{res['psnr_plain']:.1f} dB"),
               (res["image"], res["uv_map"], f"adapted 128 x 128\n{res['psnr']:.1f} dB")]
    for k, (image, uv_map, label) in enumerate(spheres):
        o = obj if k == 0 else obj.copy()
        if k:
            bpy.context.scene.collection.objects.link(o)
            o.data = obj.data.copy()
            o.data.materials.clear()
            o.data.materials.append(material(image, uv_map))
        o.location = (2.4 * (k - 1), 0, 0)
        curve = bpy.data.curves.new(f"label{k}", "FONT")
        curve.body, curve.size, curve.align_x = label, 0.22, "CENTER"
        text = bpy.data.objects.new(f"label{k}", curve)
        text.location, text.rotation_euler = (2.4 * (k - 1), -1.3, -1.45), (np.pi / 2, 0, 0)
        bpy.context.scene.collection.objects.link(text)
    cam = bpy.data.objects.new("cam", bpy.data.cameras.new("cam"))
    cam.location, cam.rotation_euler = (0, -12, -0.25), (np.pi / 2, 0, 0)
    bpy.context.scene.collection.objects.link(cam)
    sun = bpy.data.objects.new("sun", bpy.data.lights.new("sun", "SUN"))
    sun.rotation_euler, sun.data.energy = (0.7, 0.2, -0.4), 3
    bpy.context.scene.collection.objects.link(sun)
    world = bpy.data.worlds.new("w")
    world.use_nodes = True
    world.node_tree.nodes["Background"].inputs["Strength"].default_value = 0.6
    scene = bpy.context.scene
    scene.world, scene.camera = world, cam
    scene.render.engine = "CYCLES"
    scene.cycles.device, scene.cycles.samples, scene.cycles.use_denoising = "CPU", 64, False
    scene.render.resolution_x, scene.render.resolution_y = 1200, 520
    scene.render.filepath = out_png
    bpy.ops.render.render(write_still=True)
    print("RENDERED", out_png, res)


def ui_screenshot():
    """Runs the operator from the UI (modal, background job) and saves a screenshot when it is done."""
    bpy.ops.wm.read_homefile()  # closes the splash screen
    bpy.app.timers.register(ui_scene, first_interval=1.0)


def ui_scene():
    for o in list(bpy.data.objects):
        bpy.data.objects.remove(o)
    adaptex_blender.register()
    obj, _ = painted_sphere()
    obj.select_set(True)
    bpy.ops.object.mode_set(mode="TEXTURE_PAINT")
    window = bpy.context.window_manager.windows[0]
    area = next(a for a in window.screen.areas if a.type == "VIEW_3D")
    space = area.spaces[0]
    space.shading.type = "MATERIAL"
    space.show_region_ui = True
    space.overlay.show_floor = space.overlay.show_axis_x = space.overlay.show_axis_y = False
    space.region_3d.view_location = (0.0, 0.0, 0.0)
    space.region_3d.view_distance = 4.5
    space.region_3d.view_rotation = Vector((0.0, -1.0, 0.35)).to_track_quat("Z", "Y")  # towards the paint
    region = next(r for r in area.regions if r.type == "WINDOW")
    with bpy.context.temp_override(window=window, area=area, region=region):
        bpy.ops.adaptex.adapt_layout("INVOKE_DEFAULT", scale="4")
    state = {"ticks": 0}

    def wait():
        state["ticks"] += 1
        if "adaptex_last" not in bpy.context.scene and state["ticks"] < 600:
            return 0.1
        if state["ticks"] < 10000:  # time for the material's shaders and a few redraws
            state["ticks"] = 10000
            return 8.0
        with bpy.context.temp_override(window=window, area=area):
            bpy.ops.screen.screenshot(filepath=out_png)
        print("SCREENSHOT", out_png, bpy.context.scene.get("adaptex_last", {}).to_dict()
              if "adaptex_last" in bpy.context.scene else "operator did not finish")
        bpy.ops.wm.quit_blender()
        return None

    bpy.app.timers.register(wait, first_interval=0.5)


if mode == "ui":
    bpy.app.timers.register(lambda: ui_screenshot(), first_interval=1.0)
else:
    render_comparison()
