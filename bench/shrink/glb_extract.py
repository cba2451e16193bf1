#!/usr/bin/env python3
"""Extract one textured material of a GLB into an OBJ with `vt` + its images (bench helper).

Usage: glb_extract.py IN.glb OUTDIR [--image N]

Writes OUTDIR/mesh.obj (every triangle primitive, of any node, whose material's baseColorTexture uses
image N (default: the first image used as a baseColor), node transforms applied, glTF's v flipped
to OBJ's v = 1 - v; when every UV lies in one tile [k, k+1] other than [0,1], it is shifted into [0,1],
as the glTF REPEAT sampler shows it) and OUTDIR/image_<k>.<ext> for every image of those materials (baseColor,
normal, ...), with a materials.txt naming which map is which. Standard library only.
"""
import json
import struct
import sys
from pathlib import Path

COMP = {5120: ('b', 1), 5121: ('B', 1), 5122: ('h', 2), 5123: ('H', 2), 5125: ('I', 4), 5126: ('f', 4)}
NCOMP = {'SCALAR': 1, 'VEC2': 2, 'VEC3': 3, 'VEC4': 4, 'MAT4': 16}


def load(path):
    b = Path(path).read_bytes()
    if b[:4] != b'glTF':
        sys.exit(f'{path}: not a GLB')
    off, j, binchunk = 12, None, None
    while off < len(b):
        ln, typ = struct.unpack_from('<II', b, off)
        chunk = b[off + 8:off + 8 + ln]
        if typ == 0x4E4F534A:
            j = json.loads(chunk)
        elif typ == 0x004E4942:
            binchunk = chunk
        off += 8 + ln
    return j, binchunk


def accessor(j, bin_, idx):
    a = j['accessors'][idx]
    bv = j['bufferViews'][a['bufferView']]
    fmt, size = COMP[a['componentType']]
    n = NCOMP[a['type']]
    stride = bv.get('byteStride', size * n)
    base = bv.get('byteOffset', 0) + a.get('byteOffset', 0)
    out = []
    for i in range(a['count']):
        out.append(struct.unpack_from('<' + fmt * n, bin_, base + i * stride))
    if a.get('normalized') and fmt != 'f':
        mx = float((1 << (8 * size - (0 if fmt.isupper() else 1))) - 1)
        out = [tuple(max(c / mx, -1.0) for c in t) for t in out]
    return out


def matmul(a, b):  # column-major 4x4
    return [sum(a[k * 4 + r] * b[c * 4 + k] for k in range(4)) for c in range(4) for r in range(4)]


def node_matrix(n):
    if 'matrix' in n:
        return list(n['matrix'])
    t = n.get('translation', [0, 0, 0])
    x, y, z, w = n.get('rotation', [0, 0, 0, 1])
    s = n.get('scale', [1, 1, 1])
    r = [1 - 2 * (y * y + z * z), 2 * (x * y + z * w), 2 * (x * z - y * w),
         2 * (x * y - z * w), 1 - 2 * (x * x + z * z), 2 * (y * z + x * w),
         2 * (x * z + y * w), 2 * (y * z - x * w), 1 - 2 * (x * x + y * y)]
    return [r[0] * s[0], r[1] * s[0], r[2] * s[0], 0, r[3] * s[1], r[4] * s[1], r[5] * s[1], 0,
            r[6] * s[2], r[7] * s[2], r[8] * s[2], 0, t[0], t[1], t[2], 1]


def main():
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    j, bin_ = load(sys.argv[1])
    out = Path(sys.argv[2])
    out.mkdir(parents=True, exist_ok=True)
    want = int(sys.argv[sys.argv.index('--image') + 1]) if '--image' in sys.argv else None
    tex_img = lambda t: j['textures'][t['index']]['source']
    mats = j.get('materials', [])
    base_img = {}
    for mi, m in enumerate(mats):
        t = m.get('pbrMetallicRoughness', {}).get('baseColorTexture')
        if t:
            base_img[mi] = tex_img(t)
    if want is None:
        want = min(base_img.values())
    chosen = [mi for mi, im in base_img.items() if im == want]
    roles = {}
    for mi in chosen:
        m = mats[mi]
        pbr = m.get('pbrMetallicRoughness', {})
        for key, t in [('baseColor', pbr.get('baseColorTexture')), ('metallicRoughness', pbr.get('metallicRoughnessTexture')),
                       ('normal', m.get('normalTexture')), ('occlusion', m.get('occlusionTexture')),
                       ('emissive', m.get('emissiveTexture'))]:
            if t:
                if t.get('texCoord', 0) != 0:
                    print(f'warning: {key} of material {mi} uses TEXCOORD_{t["texCoord"]}', file=sys.stderr)
                roles.setdefault(tex_img(t), set()).add(key)
    lines_v, uvs, lines_f = [], [], []
    nv = 0

    def visit(ni, parent):
        nonlocal nv
        n = j['nodes'][ni]
        M = matmul(parent, node_matrix(n))
        if 'mesh' in n:
            for p in j['meshes'][n['mesh']]['primitives']:
                if p.get('material') not in chosen or p.get('mode', 4) != 4 or 'TEXCOORD_0' not in p['attributes']:
                    continue
                P = accessor(j, bin_, p['attributes']['POSITION'])
                T = accessor(j, bin_, p['attributes']['TEXCOORD_0'])
                idx = [i[0] for i in accessor(j, bin_, p['indices'])] if 'indices' in p else list(range(len(P)))
                for x, y, z in P:
                    lines_v.append('v %.9g %.9g %.9g' % tuple(M[r] * x + M[4 + r] * y + M[8 + r] * z + M[12 + r] for r in range(3)))
                uvs.extend((u, 1.0 - v) for u, v in T)
                for k in range(0, len(idx) - 2, 3):
                    a, b, c = (nv + idx[k + q] + 1 for q in range(3))
                    lines_f.append(f'f {a}/{a} {b}/{b} {c}/{c}')
                nv += len(P)
        for c in n.get('children', []):
            visit(c, M)

    ident = [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1]
    scene = j['scenes'][j.get('scene', 0)]
    for ni in scene['nodes']:
        visit(ni, ident)
    shift = []
    for axis in range(2):
        lo, hi = min(t[axis] for t in uvs), max(t[axis] for t in uvs)
        k = int(lo // 1)
        shift.append(k if hi <= k + 1 + 1e-6 else 0)
    if shift != [0, 0]:
        print(f'{sys.argv[1]}: UVs lie in tile {shift}; shifted into [0,1]', file=sys.stderr)
    lines_vt = ['vt %.9g %.9g' % (u - shift[0], v - shift[1]) for u, v in uvs]
    (out / 'mesh.obj').write_text('\n'.join(lines_v + lines_vt + lines_f) + '\n')
    desc = []
    for im, keys in sorted(roles.items()):
        img = j['images'][im]
        ext = {'image/png': 'png', 'image/jpeg': 'jpg'}.get(img.get('mimeType'), 'bin')
        bv = j['bufferViews'][img['bufferView']]
        data = bin_[bv.get('byteOffset', 0):bv.get('byteOffset', 0) + bv['byteLength']]
        (out / f'image_{im}.{ext}').write_bytes(data)
        desc.append(f'image_{im}.{ext} {",".join(sorted(keys))}')
    (out / 'materials.txt').write_text('\n'.join(desc) + '\n')
    print(f'{out}/mesh.obj: {len(lines_f)} faces, {nv} vertices; ' + '; '.join(desc))


if __name__ == '__main__':
    main()
