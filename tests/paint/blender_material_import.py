"""Headless Blender 3.4 import of a painted layered material (stroke file version 2).

Run with python3: paints a code-built sphere with `adaptex strokes generate --kind material` and
`adaptex paint`, then runs this same file inside `blender -b --python`, which imports
  * the .glb: Base Color, Metallic, Roughness and Normal (through a tangent-space Normal Map node)
    of the Principled BSDF linked to image textures, base colour sRGB and the others Non-Color,
    Metallic from the Blue and Roughness from the Green output of a Separate Color node fed by the
    packed metallicRoughness image; every image's pixels equal the PNG the CLI wrote for its channel;
  * the .obj/.mtl with Blender 3.4's OBJ importer (wm.obj_import): Base Color, Roughness and Metallic
    linked to NAME.png, NAME_roughness.png and NAME_metallic.png. It ignores `norm` (docs/export.md).
Exits 77 (ctest SKIP) with a message when blender is absent.

usage: blender_material_import.py ADAPTEX_CLI
"""
import os
import shutil
import subprocess
import sys
import tempfile

MARK = "ADAPTEX_MATERIAL_IMPORT_OK"


def run_outside():
    here = os.path.dirname(os.path.abspath(__file__))
    sys.path.insert(0, here)
    from gltf_validate import sphere_obj

    cli = sys.argv[1]
    blender = shutil.which("blender")
    if blender is None:
        print("SKIP: blender is not installed (Debian package blender; scripts/setup.sh)")
        sys.exit(77)
    with tempfile.TemporaryDirectory(prefix="adaptex-material-") as tmp:
        mesh = os.path.join(tmp, "s.obj")
        sphere_obj(mesh)
        strokes, out = os.path.join(tmp, "m.json"), os.path.join(tmp, "mat")
        for args in (["strokes", "generate", mesh, "--kind", "material", "--seed", "3", "-o", strokes],
                     ["paint", mesh, "--strokes", strokes, "--size", "128", "-o", out]):
            subprocess.run([cli, "-q", *args], check=True)
        # A pyenv interpreter running this puts its own bin first on PATH, and Blender's embedded Python
        # then finds that prefix and not Debian's (no numpy): give Blender the PATH without it.
        path = os.pathsep.join(p for p in os.environ.get("PATH", "").split(os.pathsep) if "/.pyenv/" not in p)
        env = dict(os.environ, PATH=path, BLENDER_USER_SCRIPTS=os.path.join(tmp, "scripts"),
                   BLENDER_USER_CONFIG=os.path.join(tmp, "config"))
        r = subprocess.run([blender, "-b", "--factory-startup", "--python-exit-code", "1", "--python",
                            os.path.abspath(__file__), "--", out, "s"], env=env, capture_output=True, text=True)
        print(r.stdout[-6000:], r.stderr[-4000:])
        sys.exit(0 if r.returncode == 0 and MARK in r.stdout else 1)


def run_inside():
    import numpy
    if "bool" not in vars(numpy):
        numpy.bool = bool  # Debian's Blender 3.4 glTF add-on uses np.bool (removed in numpy 1.24); tests only
    import bpy
    import numpy as np

    out, name = sys.argv[sys.argv.index("--") + 1:]

    def check(cond, what):
        if not cond:
            raise AssertionError(what)

    def pixels(img):
        """RGBA in [0, 1], rows from the bottom (Blender's order), as stored (no colour conversion)."""
        a = np.empty(4 * img.size[0] * img.size[1], dtype=np.float32)
        img.pixels.foreach_get(a)
        return a.reshape(img.size[1], img.size[0], 4)

    def png(file):
        img = bpy.data.images.load(os.path.join(out, file), check_existing=False)
        img.colorspace_settings.name = "Non-Color"
        return pixels(img)

    def principled(mat):
        nodes = [n for n in mat.node_tree.nodes if n.bl_idname == "ShaderNodeBsdfPrincipled"]
        check(len(nodes) == 1, f"{mat.name}: {len(nodes)} Principled BSDF nodes")
        return nodes[0]

    def source(socket):
        check(socket.is_linked, f"Principled input {socket.name} is not linked")
        link = socket.links[0]
        return link.from_node, link.from_socket

    def image_of(node, what):
        check(node.bl_idname == "ShaderNodeTexImage" and node.image is not None,
              f"{what} comes from {node.bl_idname}, not an image texture")
        return node.image

    def same(a, b, what):
        check(a.shape == b.shape, f"{what}: image sizes {a.shape} vs {b.shape}")
        diff = float(np.abs(a - b).max())
        check(diff < 0.5 / 255, f"{what}: pixels differ from the CLI's PNG by up to {diff * 255:.1f}/255")

    roughness, metallic = png(name + "_roughness.png")[..., 0], png(name + "_metallic.png")[..., 0]
    # Both channels carry paint, and differently: a swapped G/B would be seen.
    check(np.ptp(roughness) > 0.2 and np.ptp(metallic) > 0.2, "the material paints no roughness/metallic detail")
    check(np.abs(roughness - metallic).max() > 0.2, "roughness and metallic are the same picture")

    # ---- glTF ---------------------------------------------------------------------------------
    bpy.ops.wm.read_factory_settings(use_empty=True)
    bpy.ops.import_scene.gltf(filepath=os.path.join(out, name + ".glb"))
    mats = [m for m in bpy.data.materials if m.users and m.node_tree]
    check(len(mats) == 1, f"{len(mats)} materials imported from the .glb")
    bsdf = principled(mats[0])
    node, sock = source(bsdf.inputs["Base Color"])
    base = image_of(node, "Base Color")
    check(sock.name == "Color", f"Base Color from the {sock.name} output")
    check(base.colorspace_settings.name == "sRGB", f"base colour image in {base.colorspace_settings.name}")
    same(pixels(base), png(name + ".png"), "base colour")

    sep_m, out_m = source(bsdf.inputs["Metallic"])
    sep_r, out_r = source(bsdf.inputs["Roughness"])
    check(sep_m == sep_r and sep_m.bl_idname in ("ShaderNodeSeparateColor", "ShaderNodeSeparateRGB"),
          f"Metallic from {sep_m.bl_idname}, Roughness from {sep_r.bl_idname}: not one Separate Color node")
    check(out_m.name in ("Blue", "B") and out_r.name in ("Green", "G"),
          f"Metallic from {out_m.name}, Roughness from {out_r.name} (glTF: metallic B, roughness G)")
    packed = image_of(source(sep_m.inputs[0])[0], "the Separate Color input")
    check(packed.colorspace_settings.name == "Non-Color", f"metallicRoughness in {packed.colorspace_settings.name}")
    mr = pixels(packed)
    same(mr[..., 1], roughness, "the packed image's G channel (roughness)")
    same(mr[..., 2], metallic, "the packed image's B channel (metallic)")

    nmap, _ = source(bsdf.inputs["Normal"])
    check(nmap.bl_idname == "ShaderNodeNormalMap", f"Normal from {nmap.bl_idname}, not a Normal Map node")
    check(nmap.space == "TANGENT", f"Normal Map node in {nmap.space} space")
    normal = image_of(source(nmap.inputs["Color"])[0], "the Normal Map's Color")
    check(normal.colorspace_settings.name == "Non-Color", f"normal map in {normal.colorspace_settings.name}")
    same(pixels(normal), png(name + "_normal.png"), "normal map")

    # ---- OBJ / MTL ----------------------------------------------------------------------------
    bpy.ops.wm.read_factory_settings(use_empty=True)
    bpy.ops.wm.obj_import(filepath=os.path.join(out, name + ".obj"))
    mats = [m for m in bpy.data.materials if m.users and m.node_tree]
    check(len(mats) == 1, f"{len(mats)} materials imported from the .obj")
    bsdf = principled(mats[0])
    for socket, file in (("Base Color", name + ".png"), ("Roughness", name + "_roughness.png"),
                         ("Metallic", name + "_metallic.png")):
        img = image_of(source(bsdf.inputs[socket])[0], socket)
        check(os.path.basename(img.filepath) == file, f"OBJ: {socket} from {img.filepath}, not {file}")
    print(MARK)


if __name__ == "__main__":
    try:
        import bpy  # noqa: F401
    except ImportError:
        run_outside()
    else:
        run_inside()
