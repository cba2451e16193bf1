// Hostile input files (issue 11): each kind found by fuzzing gets, through the CLI, exit code 2 and one
// line on stderr naming the file and the problem, no output, in bounded time and memory: the CLI
// runs under a 2 GB address-space limit and a 30 s timeout (the limit is left out in sanitizer builds,
// whose shadow memory needs more address space). The files are built here, byte by byte.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <cstdint>

#include "adaptex/core/limits.h"
#include "adaptex/core/shapes.h"
#include "adaptex/io/mesh_io.h"
#include "image_test_files.h"
#include "io_test_files.h"
#include "test_support.h"

namespace adaptex {
namespace {

using test::glb;
using test::png_header;
using test::psd_header;
using test::put;
using test::TempDir;

#if defined(__SANITIZE_ADDRESS__)
constexpr bool kSanitized = true;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
constexpr bool kSanitized = true;
#else
constexpr bool kSanitized = false;
#endif
#else
constexpr bool kSanitized = false;
#endif

std::string q(const std::filesystem::path& p) {
  std::string s(1, '\'');
  s += p.string();
  s += '\'';
  return s;
}

/// Runs the CLI with \p args under `ulimit -v 2 GB` and `timeout 30`.
test::CliResult run_bounded(const std::string& args) {
  return test::run_cli(args, std::string(kSanitized ? "" : "ulimit -v 2097152; ") + "timeout 30 ");
}

/// `adaptex ARGS` must exit 2 with one line naming \p file and containing \p what, and print nothing.
void expect_rejected(const std::string& args, const std::filesystem::path& file, const std::string& what) {
  const auto r = run_bounded(args);
  EXPECT_EQ(r.exit_code, 2) << args << "\n" << r.err;
  EXPECT_EQ(r.err.rfind("adaptex: error: ", 0), 0u) << r.err;
  EXPECT_NE(r.err.find(file.filename().string()), std::string::npos) << r.err;
  EXPECT_NE(r.err.find(what), std::string::npos) << "expected '" << what << "' in: " << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_TRUE(r.out.empty()) << r.out;
}

void expect_info_rejects(const std::filesystem::path& file, const std::string& what) {
  expect_rejected("info " + q(file), file, what);
}

TEST(HostileFiles, OffColourIndexAndNegativeCounts) {
  TempDir dir;
  // 52 bytes: a COFF vertex whose single colour value is a colour-map index far out of range.
  test::write_text(dir.path / "color.off", "COFF\n3 1 0\n0 0 0 99999999\n1 0 0 1\n0 1 0 2\n3 0 1 2\n");
  expect_info_rejects(dir.path / "color.off", "vertex 0: colour index 99999999 is out of range");
  test::write_text(dir.path / "fcolor.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2 -7\n");
  expect_info_rejects(dir.path / "fcolor.off", "face 0: colour index -7 is out of range");
  test::write_text(dir.path / "neg.off", "OFF\n-3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
  expect_info_rejects(dir.path / "neg.off", "negative count in the header");
  test::write_text(dir.path / "negface.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n-3 0 1 2\n");
  expect_info_rejects(dir.path / "negface.off", "face 0 is missing or unreadable");
  test::write_text(dir.path / "negidx.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 -1 2\n");
  expect_info_rejects(dir.path / "negidx.off", "face 0 refers to a vertex index out of range");
  // Header counts far beyond what the bytes left can hold: rejected before allocating.
  test::write_text(dir.path / "huge.off", "OFF\n2000000000 2000000000 0\n0 0 0\n");
  expect_info_rejects(dir.path / "huge.off", "the OFF header claims 2000000000 vertices and 2000000000 faces");
  test::write_text(dir.path / "hugeface.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n2147483647 0 1 2\n");
  expect_info_rejects(dir.path / "hugeface.off", "face 0 claims 2147483647 corners");
  // STOFF: texture coordinates are skipped, the colour before them is checked.
  test::write_text(dir.path / "st.off", "STCOFF\n3 1 0\n0 0 0 300 0 0\n1 0 0 1 0 0\n0 1 0 1 0 0\n3 0 1 2\n");
  expect_info_rejects(dir.path / "st.off", "vertex 0: colour index 300 is out of range");
}

TEST(HostileFiles, PlyPropertyBeforeElementAndHugeOrNegativeLists) {
  TempDir dir;
  // 49 bytes: a property before any element.
  test::write_text(dir.path / "prop.ply", "ply\nformat ascii 1.0\nproperty float x\nend_header\n");
  expect_info_rejects(dir.path / "prop.ply", "line 3: a property is declared before any element");
  const std::string header = "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\n"
                             "property float y\nproperty float z\nelement face 1\n"
                             "property list uint int vertex_indices\nend_header\n";
  std::string body;
  for (float c : {0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 0.f, 1.f, 0.f}) put(body, c);
  put(body, std::uint32_t{1} << 31);  // the face list claims 2^31 entries
  for (int i : {0, 1, 2}) put(body, i);
  test::write_text(dir.path / "list.ply", header + body);
  expect_info_rejects(dir.path / "list.ply", "the list claims 2147483648 entries");
  test::write_text(dir.path / "negative.ply",
                   "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                   "element face 1\nproperty list int int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n-5 0 1 2\n");
  expect_info_rejects(dir.path / "negative.ply", "the list claims -5 entries");
  test::write_text(dir.path / "count.ply",
                   "ply\nformat ascii 1.0\nelement vertex 4000000000\nproperty float x\nproperty float y\n"
                   "property float z\nend_header\n0 0 0\n");
  expect_info_rejects(dir.path / "count.ply", "the PLY header claims 4000000000 'vertex' items");
}

TEST(HostileFiles, GltfForgedChunkLengthAndNotGltf) {
  TempDir dir;
  const std::string json = R"({"asset":{"version":"2.0"},"buffers":[{"byteLength":36}]})";
  const std::string bin(36, '\0');
  test::write_text(dir.path / "forged.glb", glb(json, bin, 0xFFFFFFF0u));
  expect_info_rejects(dir.path / "forged.glb", "GLB chunk 1 claims 4294967280 bytes");
  // A PLY (or anything that is not glTF) named .glb never reaches assimp's other importers.
  test::write_ply_ascii(dir.path / "ply.glb", shapes::icosphere(0));
  expect_info_rejects(dir.path / "ply.glb", "neither a binary glTF");
  test::write_text(dir.path / "v1.gltf", R"({"asset":{"version":"1.0"}})");
  expect_info_rejects(dir.path / "v1.gltf", "not glTF 2.0");
  test::write_text(dir.path / "big.glb",
                   glb(R"({"asset":{"version":"2.0"},"buffers":[{"byteLength":4000000000}]})", bin));
  expect_info_rejects(dir.path / "big.glb", "buffer 0 claims 4000000000 bytes but only 36 exist");
  test::write_text(dir.path / "acc.glb", glb(R"({"asset":{"version":"2.0"},"buffers":[{"byteLength":36}],
      "bufferViews":[{"buffer":0,"byteLength":36}],
      "accessors":[{"bufferView":0,"componentType":5126,"type":"VEC3","count":1000000}]})", bin));
  expect_info_rejects(dir.path / "acc.glb", "accessor 0 (1000000 items) lies outside its buffer view");
  // Found by fuzz_gltf: a primitive without POSITION made assimp dereference a null pointer.
  test::write_text(dir.path / "nopos.glb", glb(R"({"asset":{"version":"2.0"},"meshes":[{"primitives":[{"ittributes":{}}]}]})", bin));
  expect_info_rejects(dir.path / "nopos.glb", "mesh 0: a primitive has no POSITION attribute");
  // Found by fuzz_gltf (session 6): a line-loop primitive whose indices are a float VEC3 accessor made
  // assimp read address 0 (SEGV). The fuzzer's 576-byte file, JSON and BIN chunk as found.
  std::string loop_bin;
  for (std::uint32_t w : {0x3f800000u, 0x20000u, 0x1u, 0x30001u, 0x65030000u, 0x10072u, 0xfffe0000u, 0x3f80ffffu, 0u,
                          0u, 0u, 0u, 0u, 0xf9u, 0x30001u, 0x65030000u, 0x10072u, 0x30002u})
    put(loop_bin, w);
  // One four-vertex scene: POSITION is accessor 0 (bufferView 0), the indices accessor \p indices
  // (0: POSITION itself, 1: \p index_count unsigned shorts on bufferView \p index_view), primitive \p mode.
  auto four_vertex_glb = [&](int indices, int index_view, int mode, const std::string& chunk,
                             const char* count_key = "count", int index_count = 12) {
    return glb(R"({"asset":{"version":"2.!"},"scene":0,"scenes":[{"nodes":[0]}],)"
               R"("nodes":[{"mesh":0,"translation":[1,0,0]}],"meshes":[{"primitives":[{"attributes":{"POSITION":0},)"
               R"("indices":)" + std::to_string(indices) + R"(,"mode":)" + std::to_string(mode) +
               R"(}]}],"buffers":[{"byteLength":72}],"bufferViews":[{"buffer":0,"byteLength":48},)"
               R"({"buffer":0,"byteOffset":48,"byteLength":24}],"accessors":[{"bufferView":0,"componentType":5126,)"
               R"("type":"VEC3",")" + count_key + R"(":4,"min":[0,0,0],"max":[1,1,1]},{"bufferView":)" + std::to_string(index_view) +
               R"(,"componentType":5123,"type":"SCALAR","count":)" + std::to_string(index_count) + "}]}", chunk);
  };
  test::write_text(dir.path / "loop.glb", four_vertex_glb(0, 0, 2, loop_bin));
  expect_info_rejects(dir.path / "loop.glb", "mesh 0: indices must be a SCALAR accessor");
  // Found by fuzz_gltf (session 11): the same line loop with a valid unsigned-short index accessor
  // that reads the positions' bytes, so its index values (16256, ...) name missing vertices: SEGV
  // in assimp. Index values are now checked against the POSITION count.
  test::write_text(dir.path / "loop2.glb", four_vertex_glb(1, 0, 2, loop_bin));
  expect_info_rejects(dir.path / "loop2.glb", "mesh 0 indices: index 16256 but the primitive has 4 vertices");
  // Valid indices still read: a tetrahedron, 4 vertices, 12 unsigned-short indices after them.
  std::string tet_bin;
  for (std::uint32_t w : {0u, 0u, 0u, 0x3f800000u, 0u, 0u, 0u, 0x3f800000u, 0u, 0u, 0u, 0x3f800000u,  // positions
                          0x20000u, 0x1u, 0x30001u, 0x30000u, 0x10002u, 0x30002u})  // 0 2 1 / 0 1 3 / 0 3 2 / 1 2 3
    put(tet_bin, w);
  test::write_text(dir.path / "tet.glb", four_vertex_glb(1, 1, 4, tet_bin));
  const auto ok = run_bounded("info " + q(dir.path / "tet.glb"));
  EXPECT_EQ(ok.exit_code, 0) << ok.err;
  EXPECT_NE(ok.out.find("faces:       4"), std::string::npos) << ok.out;
  // Found by fuzz_gltf right after that fix: POSITION without a count ("cuont"), so no vertex at all;
  // the first index check read the missing member and threw an uncaught JSON error.
  // Found by fuzz_gltf (session 11): a triangle strip (mode 5) with a single index: assimp asked
  // for count − 2 = 2^64 − 1 faces. Strips and fans need 3 vertices, triangles a multiple of 3.
  std::string one_bin = tet_bin;
  test::write_text(dir.path / "strip1.glb", four_vertex_glb(1, 1, 5, one_bin, "count", 1));
  expect_info_rejects(dir.path / "strip1.glb", "mesh 0: 1 vertices do not make whole primitives of mode 5");
  test::write_text(dir.path / "tri11.glb", four_vertex_glb(1, 1, 4, one_bin, "count", 11));
  expect_info_rejects(dir.path / "tri11.glb", "mesh 0: 11 vertices do not make whole primitives of mode 4");
  test::write_text(dir.path / "nocount.glb", four_vertex_glb(1, 1, 4, tet_bin, "cuont"));
  expect_info_rejects(dir.path / "nocount.glb", "mesh 0 indices: index 0 but the primitive has 0 vertices");
  // The index check reads index data from every kind of buffer: the BIN chunk (above), a base64
  // data: URI and a file beside the glTF. One triangle, 3 positions then 3 unsigned-short indices
  // (0 1 2, or 0 1 3 naming a vertex that does not exist) and 2 bytes of padding: 44 bytes.
  auto indexed_gltf = [](const std::string& uri) {
    return R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],)"
           R"("meshes":[{"primitives":[{"attributes":{"POSITION":0},"indices":1}]}],)"
           R"("buffers":[{"uri":")" + uri + R"(","byteLength":44}],"bufferViews":[{"buffer":0,"byteLength":36},)"
           R"({"buffer":0,"byteOffset":36,"byteLength":6}],"accessors":[{"bufferView":0,"componentType":5126,)"
           R"("type":"VEC3","count":3,"min":[0,0,0],"max":[1,1,0]},{"bufferView":1,"componentType":5123,)"
           R"("type":"SCALAR","count":3}]})";
  };
  const std::string b64 = "data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAAAAAB";
  test::write_text(dir.path / "uri_ok.gltf", indexed_gltf(b64 + "AAIAAAA="));
  test::write_text(dir.path / "uri_bad.gltf", indexed_gltf(b64 + "AAMAAAA="));
  std::string tri_bin;
  for (std::uint32_t w : {0u, 0u, 0u, 0x3f800000u, 0u, 0u, 0u, 0x3f800000u, 0u}) put(tri_bin, w);
  std::string bad_bin = tri_bin;
  for (std::uint32_t w : {0x10000u, 0x2u}) put(tri_bin, w);  // indices 0 1 | 2, padding
  for (std::uint32_t w : {0x10000u, 0x3u}) put(bad_bin, w);  // indices 0 1 | 3, padding
  test::write_text(dir.path / "tri_ok.bin", tri_bin);
  test::write_text(dir.path / "tri_bad.bin", bad_bin);
  test::write_text(dir.path / "file_ok.gltf", indexed_gltf("tri_ok.bin"));
  test::write_text(dir.path / "file_bad.gltf", indexed_gltf("tri_bad.bin"));
  for (const char* f : {"uri_ok.gltf", "file_ok.gltf"}) {
    const auto r = run_bounded("info " + q(dir.path / f));
    EXPECT_EQ(r.exit_code, 0) << f << ": " << r.err;
    EXPECT_NE(r.out.find("faces:       1"), std::string::npos) << f << ": " << r.out;
  }
  for (const char* f : {"uri_bad.gltf", "file_bad.gltf"})
    expect_info_rejects(dir.path / f, "mesh 0 indices: index 3 but the primitive has 3 vertices");
  test::write_text(dir.path / "cycle.gltf", R"({"asset":{"version":"2.0"},"nodes":[{"children":[1]},{"children":[0]}]})");
  expect_info_rejects(dir.path / "cycle.gltf", "the node hierarchy has a cycle");
  // An external buffer that is a device.
  test::write_text(dir.path / "zero.gltf",
                   R"({"asset":{"version":"2.0"},"buffers":[{"uri":"../../../../../../../../dev/zero","byteLength":99999999}]})");
  expect_info_rejects(dir.path / "zero.gltf", "is not a regular file");
  // An external buffer over the input file cap (a sparse file: no disk space used).
  test::write_text(dir.path / "huge.bin", "");
  std::filesystem::resize_file(dir.path / "huge.bin", adaptex::kMaxInputFileBytes + 1);
  test::write_text(dir.path / "huge.gltf",
                   R"({"asset":{"version":"2.0"},"buffers":[{"uri":"huge.bin","byteLength":12}]})");
  expect_info_rejects(dir.path / "huge.gltf", "larger than the input file limit");
}

TEST(HostileFiles, GltfImageMimeTypeWithoutSlash) {
  // Found by fuzz_gltf: an embedded image whose mimeType has no '/' ("image$png") made assimp's glTF
  // importer strcmp() the address after strchr()'s null (SEGV). The fuzzer's JSON as found; the BIN
  // chunk is zeros (8 vertices at the origin, 12 indices 0, and the image's 74 bytes).
  TempDir dir;
  const std::string json =
      R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],)"
      R"("meshes":[{"primitives":[{"attributes":{"POSITION":0,"TEXCOORD_0":1},"indices":2,"material":0}]}],)"
      R"("buffers":[{"byteLength":260}],"bufferViews":[{"buffer":0,"byteOffset":0,"byteLength":96},)"
      R"({"buffer":0,"byteOffset":96,"byteLength":64},{"buffer":0,"byteOffset":160,"byteLength":24},)"
      R"({"buffer":0,"byteOffset":184,"byteLength":74}],"accessors":[{"bufferView":0,"componentType":5126,)"
      R"("count":8,"type":"VEC3"},{"bufferView":1,"componentType":5126,"count":8,"type":"VEC2"},)"
      R"({"bufferView":2,"componentType":5123,"count":12,"type":"SCALAR"}],)"
      R"("images":[{"bufferView":3,"mimeType":"MIME"}],"samplers":[{"wrapS":10497,"wrapT":10497}],)"
      R"("textures":[{"source":0,"sampler":0}],"materials":[{"name":"m","pbrMetallicRoughness":)"
      R"({"baseColorTexture":{"index":0}},"normalTexture":{"index":0,"scale":0.5}}]})";
  auto with_mime = [&](const std::string& mime) {
    std::string j = json;
    j.replace(j.find("MIME"), 4, mime);
    return glb(j, std::string(260, '\0'));
  };
  test::write_text(dir.path / "mime.glb", with_mime("image$png"));
  expect_info_rejects(dir.path / "mime.glb", "image 0: mimeType \"image$png\" is not a MIME type");
  test::write_text(dir.path / "mime2.glb", with_mime("png"));
  expect_info_rejects(dir.path / "mime2.glb", "image 0: mimeType \"png\" is not a MIME type");
  // A well-formed MIME type passes the check (the zero image bytes are no PNG; the geometry reads).
  test::write_text(dir.path / "mime_ok.glb", with_mime("image/png"));
  const auto ok = run_bounded("info " + q(dir.path / "mime_ok.glb"));
  EXPECT_EQ(ok.err.find("is not a MIME type"), std::string::npos) << ok.err;
}

TEST(HostileFiles, OnlyRegularFilesAreRead) {
  TempDir dir;
  std::filesystem::create_symlink("/dev/zero", dir.path / "zero.off");
  expect_info_rejects(dir.path / "zero.off", "not a regular file");
  const auto fifo = dir.path / "pipe.off";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  expect_info_rejects(fifo, "not a regular file");
  // An OBJ whose material file is /dev/zero: material files are never opened, the mesh is read.
  test::write_text(dir.path / "m.obj",
                   "mtllib ../../../../../../../../../dev/zero\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl x\nf 1 2 3\n");
  const auto r = run_bounded("info " + q(dir.path / "m.obj"));
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("faces:       1"), std::string::npos) << r.out;
}

TEST(HostileFiles, ImagesArePngWithinThePixelCap) {
  TempDir dir;
  const TriMesh mesh = shapes::plane(2);
  Parameterization param;  // UV = the plane's x, y: one chart
  for (int v = 0; v < mesh.num_vertices(); ++v) {
    param.uv.emplace_back(mesh.positions[v].x(), mesh.positions[v].y());
    param.wedge_vertex.push_back(v);
  }
  param.uv_faces = mesh.faces;
  param.face_chart.assign(mesh.faces.size(), 0);
  param.num_charts = 1;
  write_obj(dir.path / "m.obj", mesh, &param);
  test::write_text(dir.path / "psd.png", psd_header());
  test::write_text(dir.path / "huge.png", png_header(11'000'000, 25));
  const auto out = dir.path / "out";
  expect_rejected("reparam " + q(dir.path / "m.obj") + " " + q(dir.path / "psd.png") + " -o " + q(out),
                  dir.path / "psd.png", "not a PNG file");
  EXPECT_FALSE(std::filesystem::exists(out));
  expect_rejected("reparam " + q(dir.path / "m.obj") + " " + q(dir.path / "huge.png") + " -o " + q(out),
                  dir.path / "huge.png", "PNG of 11000000x25 pixels is larger than the 8192x8192 limit");
  EXPECT_FALSE(std::filesystem::exists(out));
  // The same images, and /dev/zero, as decal images of a stroke file.
  for (const char* image : {"psd.png", "huge.png", "/dev/zero"}) {
    const auto strokes = dir.path / "s.json";
    test::write_text(strokes, std::string(R"({"format": "adaptex.strokes", "version": 1, "strokes": [)") +
                                  R"({"type": "decal", "image": ")" + image +
                                  R"(", "eye": [0, 0, 3], "target": [0, 0, 0]}]})");
    const auto normalized = dir.path / "n.json";
    expect_rejected("strokes check " + q(strokes) + " -o " + q(normalized), strokes,
                    std::string(image) == "/dev/zero" ? "not a regular file"
                    : std::string(image) == "psd.png" ? "not a PNG file"
                                                      : "larger than the 8192x8192 limit");
    EXPECT_FALSE(std::filesystem::exists(normalized));
  }
}

TEST(HostileFiles, ReparamTexturesInJpegAndTgaTruncatedForgedOrOversized) {
  TempDir dir;
  const TriMesh mesh = shapes::plane(2);
  Parameterization param;  // UV = the plane's x, y: one chart
  for (int v = 0; v < mesh.num_vertices(); ++v) {
    param.uv.emplace_back(mesh.positions[v].x(), mesh.positions[v].y());
    param.wedge_vertex.push_back(v);
  }
  param.uv_faces = mesh.faces;
  param.face_chart.assign(mesh.faces.size(), 0);
  param.num_charts = 1;
  write_obj(dir.path / "m.obj", mesh, &param);
  const ImageRGBA8 img = test::solid(64, 64, 200, 100, 50);
  const std::string jpeg = test::jpeg_bytes(img), tga = test::tga_bytes(img, false);
  test::write_text(dir.path / "cut.jpg", jpeg.substr(0, jpeg.size() / 2));
  test::write_text(dir.path / "cut.tga", tga.substr(0, tga.size() - 100));
  std::string forged = tga;
  forged[12] = static_cast<char>(0x40), forged[13] = static_cast<char>(0x1F);  // 8000 x 64
  test::write_text(dir.path / "forged.tga", forged);
  std::string huge = jpeg;
  const std::size_t sof = huge.find("\xFF\xC0");
  ASSERT_NE(sof, std::string::npos);
  huge[sof + 7] = static_cast<char>(0x27), huge[sof + 8] = static_cast<char>(0x10);  // width 10000
  test::write_text(dir.path / "huge.jpg", huge);
  const auto out = dir.path / "out";
  const std::pair<const char*, const char*> cases[] = {
      {"cut.jpg", "corrupt JPEG: truncated"},
      {"cut.tga", "corrupt TGA: truncated"},
      {"forged.tga", "corrupt TGA: truncated: the pixel data needs 2048018 bytes"},
      {"huge.jpg", "JPEG of 10000x64 pixels is larger than the 8192x8192 limit"}};
  for (const auto& [file, what] : cases) {
    expect_rejected("reparam " + q(dir.path / "m.obj") + " " + q(dir.path / file) + " -o " + q(out), dir.path / file,
                    what);
    EXPECT_FALSE(std::filesystem::exists(out)) << file;
  }
  // The same textures whole are accepted.
  test::write_text(dir.path / "whole.tga", tga);
  const auto r = run_bounded("-q reparam " + q(dir.path / "m.obj") + " " + q(dir.path / "whole.tga") + " --size 32 -o " + q(out));
  EXPECT_EQ(r.exit_code, 0) << r.err;
}

}  // namespace
}  // namespace adaptex
