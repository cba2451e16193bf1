// Merges the Draco-compressed triangles of GLB tiles (a 3D Tiles tileset's content, e.g. the
// Matterport scans of docs/bench_unwrap.md) into one OBJ, welding bit-identical positions. Needs
// node and npm's draco3d (npm install draco3d). Usage: node glbdraco2obj.js OUT.obj TILE.glb...
const fs = require('fs');
const draco3d = require('draco3d');
let current = '';
(async () => {
  const [out, ...files] = process.argv.slice(2);
  if (!out || files.length === 0) throw new Error('usage: node glbdraco2obj.js OUT.obj TILE.glb...');
  const dm = await draco3d.createDecoderModule({});
  const weld = new Map(); const pos = []; const faces = [];
  for (const f of files) {
    current = f;
    const b = fs.readFileSync(f);
    if (b.length < 20 || b.toString('latin1', 0, 4) !== 'glTF') throw new Error('not a binary glTF (GLB) file');
    const jl = b.readUInt32LE(12);
    if (20 + jl > b.length) throw new Error('JSON chunk runs past the end of the file');
    const j = JSON.parse(b.slice(20, 20 + jl).toString());
    const binStart = 20 + jl + 8;
    for (const n of (j.nodes || [])) if (n.matrix || n.translation || n.rotation || n.scale) throw new Error('node transform in ' + f);
    for (const m of j.meshes) for (const p of m.primitives) {
      const ext = p.extensions && p.extensions.KHR_draco_mesh_compression;
      if (!ext) throw new Error('a primitive without KHR_draco_mesh_compression');
      const bv = j.bufferViews[ext.bufferView];
      const data = new Int8Array(b.buffer, b.byteOffset + binStart + (bv.byteOffset || 0), bv.byteLength);
      const dec = new dm.Decoder(); const buf = new dm.DecoderBuffer(); buf.Init(data, data.length);
      const mesh = new dm.Mesh(); const st = dec.DecodeBufferToMesh(buf, mesh);
      if (!st.ok()) throw new Error(st.error_msg());
      const att = dec.GetAttributeByUniqueId(mesh, ext.attributes.POSITION);
      const arr = new dm.DracoFloat32Array(); dec.GetAttributeFloatForAllPoints(mesh, att, arr);
      const np = mesh.num_points(); const map = new Int32Array(np);
      for (let i = 0; i < np; ++i) {
        const x = arr.GetValue(3 * i), y = arr.GetValue(3 * i + 1), z = arr.GetValue(3 * i + 2);
        const k = x + ',' + y + ',' + z;
        let id = weld.get(k);
        if (id === undefined) { id = pos.length / 3; weld.set(k, id); pos.push(x, y, z); }
        map[i] = id;
      }
      const ia = new dm.DracoInt32Array();
      for (let fi = 0; fi < mesh.num_faces(); ++fi) {
        dec.GetFaceFromMesh(mesh, fi, ia);
        faces.push(map[ia.GetValue(0)], map[ia.GetValue(1)], map[ia.GetValue(2)]);
      }
      dm.destroy(ia); dm.destroy(arr); dm.destroy(mesh); dm.destroy(buf); dm.destroy(dec);
    }
  }
  const lines = [];
  for (let i = 0; i < pos.length; i += 3) lines.push(`v ${pos[i]} ${pos[i + 1]} ${pos[i + 2]}`);
  for (let i = 0; i < faces.length; i += 3) lines.push(`f ${faces[i] + 1} ${faces[i + 1] + 1} ${faces[i + 2] + 1}`);
  current = out;
  fs.writeFileSync(out + '.part', lines.join('\n') + '\n');
  fs.renameSync(out + '.part', out);  // no partial OUT if writing fails
  console.log(out, pos.length / 3, 'vertices', faces.length / 3, 'faces');
})().catch((e) => {
  console.error('glbdraco2obj: ' + (current ? current + ': ' : '') + e.message);
  process.exit(2);
});
