"""Blender mesh / image data <-> the arrays of the adaptex Python module (docs/python.md), and the
quality figures the add-on reports. Only numpy and bpy; no adaptex import here.

Arrays: V #V x 3 float64, F #F x 3 int32 (the mesh's loop triangles), UV #W x 2 float64 (one row
per distinct (vertex, uv) pair: a "wedge"), FT #F x 3 int32, textures H x W x 4 uint8 with row 0 at
v = 0 (Blender's own pixel order).
"""
import struct
import zlib

import numpy as np


def triangles(mesh):
    """(V, F, loops): vertex positions, loop triangles as vertex indices, and as loop indices."""
    mesh.calc_loop_triangles()
    V = np.empty(3 * len(mesh.vertices), dtype=np.float64)
    mesh.vertices.foreach_get("co", V)
    nt = len(mesh.loop_triangles)
    F = np.empty(3 * nt, dtype=np.int32)
    mesh.loop_triangles.foreach_get("vertices", F)
    loops = np.empty(3 * nt, dtype=np.int32)
    mesh.loop_triangles.foreach_get("loops", loops)
    return V.reshape(-1, 3), F.reshape(-1, 3), loops.reshape(-1, 3)


def triangulated_copy(mesh):
    """A new mesh datablock: \p mesh with every polygon triangulated (UV maps, materials and the
    vertex order kept); \p mesh is not touched. Remove it with bpy.data.meshes.remove."""
    import bmesh
    import bpy
    bm = bmesh.new()
    try:
        bm.from_mesh(mesh)
        bmesh.ops.triangulate(bm, faces=bm.faces[:])
        copy = bpy.data.meshes.new(mesh.name + "_triangulated")
        bm.to_mesh(copy)
    finally:
        bm.free()
    return copy


def replace_geometry(mesh, source):
    """\p mesh gets the geometry and the layers (UV maps, ...) of \p source (a triangulated_copy)."""
    import bmesh
    bm = bmesh.new()
    try:
        bm.from_mesh(source)
        bm.to_mesh(mesh)
    finally:
        bm.free()
    mesh.update()


def wedges(mesh, uv_layer, loops):
    """(UV, FT) of a UV map: loops with the same vertex and the same uv share a wedge (so charts
    are the groups of triangles connected through shared wedges, as in an OBJ file)."""
    n = len(mesh.loops)
    uv = np.empty(2 * n, dtype=np.float64)
    uv_layer.data.foreach_get("uv", uv)
    uv = uv.reshape(-1, 2)
    vert = np.empty(n, dtype=np.int64)
    mesh.loops.foreach_get("vertex_index", vert)
    keys = np.column_stack([vert.astype(np.float64), uv])
    _, first, wedge_of_loop = np.unique(keys, axis=0, return_index=True, return_inverse=True)
    return uv[first], wedge_of_loop.reshape(-1)[loops].astype(np.int32)


def loop_uvs(mesh, loops, UV, FT):
    """Per-loop uv of the layout (UV, FT) on the loop triangles \\p loops, and the number of loops
    given two different uvs (a polygon cut by a seam: triangulate the mesh for an exact layout)."""
    out = np.full((len(mesh.loops), 2), np.nan)
    corner_uv = UV[FT].reshape(-1, 2)
    flat = loops.reshape(-1)
    out[flat] = corner_uv
    conflicts = int(np.count_nonzero(np.any(out[flat] != corner_uv, axis=1)))
    return np.nan_to_num(out), conflicts


def add_uv_map(mesh, name, per_loop_uv):
    """A new UV map \\p name (a unique name if taken) with \\p per_loop_uv, made active."""
    layer = mesh.uv_layers.new(name=name, do_init=False)
    layer.data.foreach_set("uv", per_loop_uv.astype(np.float32).reshape(-1))
    mesh.uv_layers.active = layer
    return layer


def image_pixels(image):
    """The image as H x W x 4 uint8 (row 0 = bottom)."""
    w, h = image.size
    px = np.empty(w * h * 4, dtype=np.float32)
    image.pixels.foreach_get(px)
    return np.clip(np.round(px * 255.0), 0, 255).astype(np.uint8).reshape(h, w, 4)


def new_image(bpy, name, texture):
    """A new Blender image (8-bit, alpha) holding \\p texture (H x W x 4 uint8), packed in the file."""
    h, w = texture.shape[:2]
    img = bpy.data.images.new(name, width=w, height=h, alpha=True)
    img.pixels.foreach_set((texture.astype(np.float32) / 255.0).reshape(-1))
    img.pack()
    return img


def read_png(bpy, path, remove_folder=True):
    """H x W x 4 uint8 of a PNG written by the CLI (loaded through Blender, then dropped); its
    temporary folder (the PNG's grandparent) is removed."""
    import os
    import shutil
    img = bpy.data.images.load(path)
    try:
        return image_pixels(img)
    finally:
        bpy.data.images.remove(img)
        if remove_folder:
            shutil.rmtree(os.path.dirname(os.path.dirname(path)), ignore_errors=True)


def write_png(path, texture):
    """Writes H x W x 4 uint8 (row 0 = bottom) as an RGBA PNG (top row first), for the CLI."""
    h, w = texture.shape[:2]
    rows = np.ascontiguousarray(texture[::-1]).reshape(h, w * 4)
    raw = b"".join(b"\x00" + rows[j].tobytes() for j in range(h))

    def chunk(tag, data):
        return struct.pack(">I", len(data)) + tag + data + struct.pack(">I", zlib.crc32(tag + data) & 0xFFFFFFFF)

    with open(path, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 6, 0, 0, 0)) +
                chunk(b"IDAT", zlib.compress(raw, 6)) + chunk(b"IEND", b""))


def area_resize(texture, width, height):
    """Plain downsizing: every output texel is the area-weighted mean of the input texels it covers
    (a box filter; exact block means for integer factors), rounded to 8 bits."""
    def weights(n_in, n_out):
        edges_in = np.arange(n_in + 1) / n_in
        edges_out = np.arange(n_out + 1) / n_out
        lo = np.maximum(edges_out[:-1, None], edges_in[None, :-1])
        hi = np.minimum(edges_out[1:, None], edges_in[None, 1:])
        w = np.clip(hi - lo, 0.0, None)
        return w / w.sum(axis=1, keepdims=True)

    h, w = texture.shape[:2]
    wy, wx = weights(h, height), weights(w, width)
    out = np.einsum("xw,ywc->yxc", wx, np.einsum("yh,hwc->ywc", wy, texture.astype(np.float64)))
    return np.clip(np.round(out), 0, 255).astype(np.uint8)


def surface_samples(V, F, count, seed=1):
    """\\p count points uniform by area: (face index, barycentrics #count x 3)."""
    rng = np.random.default_rng(seed)
    area = 0.5 * np.linalg.norm(np.cross(V[F[:, 1]] - V[F[:, 0]], V[F[:, 2]] - V[F[:, 0]]), axis=1)
    face = rng.choice(len(F), size=count, p=area / area.sum())
    r1, r2 = rng.random(count), rng.random(count)
    s = np.sqrt(r1)
    bary = np.column_stack([1.0 - s, s * (1.0 - r2), s * r2])
    return face, bary


def sample_bilinear(texture, uv):
    """RGB in [0,1] at \\p uv (#K x 2): bilinear, clamp-to-edge, texel centres at (i + 0.5) / W
    (the reconstruction of docs/strokes.md)."""
    h, w = texture.shape[:2]
    x = uv[:, 0] * w - 0.5
    y = uv[:, 1] * h - 0.5
    x0, y0 = np.floor(x), np.floor(y)
    fx, fy = (x - x0)[:, None], (y - y0)[:, None]
    i0, j0 = np.clip(x0.astype(int), 0, w - 1), np.clip(y0.astype(int), 0, h - 1)
    i1, j1 = np.clip(x0.astype(int) + 1, 0, w - 1), np.clip(y0.astype(int) + 1, 0, h - 1)
    t = texture[..., :3].astype(np.float64) / 255.0
    return ((t[j0, i0] * (1 - fx) + t[j0, i1] * fx) * (1 - fy) + (t[j1, i0] * (1 - fx) + t[j1, i1] * fx) * fy)


def psnr_against(reference, layouts, V, F, samples=200000, seed=1):
    """PSNR (dB) of each (UV, FT, texture) of \\p layouts against \\p reference (UV, FT, texture) on
    the same surface: mean squared RGB difference of the two reconstructions over points uniform
    by area; 10 log10(1 / MSE), 200 when they are equal."""
    face, bary = surface_samples(V, F, samples, seed)

    def colours(UV, FT, tex):
        return sample_bilinear(tex, np.einsum("kc,kcd->kd", bary, UV[FT[face]]))

    ref = colours(*reference)
    out = []
    for layout in layouts:
        mse = float(np.mean((colours(*layout) - ref) ** 2))
        out.append(200.0 if mse < 1e-20 else 10.0 * np.log10(1.0 / mse))
    return out
