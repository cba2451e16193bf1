// The in-memory entry points (read_mesh_from_memory, read_image_from_memory) against the path-based
// readers: a file and its bytes must give the same mesh, report and image, or the same error (same
// exception type, same message), since read_mesh() / read_image() call them after their file checks.
// The fuzz targets (tests/fuzz) use the in-memory entry points, so this is what makes them test the CLI.
#include <gtest/gtest.h>

#include <optional>
#include <typeinfo>

#include "adaptex/core/errors.h"
#include "adaptex/core/shapes.h"
#include "adaptex/io/image_io.h"
#include "adaptex/io/input_file.h"
#include "adaptex/io/mesh_io.h"
#include "io_test_files.h"
#include "test_support.h"

namespace adaptex {
namespace {

using test::TempDir;

/// What a reader produced: the value, or the dynamic type and message of the error it threw.
template <class T>
struct Outcome {
  std::optional<T> value;
  std::string error_type;
  std::string message;
};

template <class T, class F>
Outcome<T> outcome(F&& read) {
  Outcome<T> o;
  try {
    o.value = read();
  } catch (const Error& e) {
    o.error_type = typeid(e).name();
    o.message = e.what();
  }
  return o;
}

struct MeshRead {
  TriMesh mesh;
  ReadReport report;
};

void expect_same_report(const ReadReport& a, const ReadReport& b, const std::string& what) {
  EXPECT_EQ(a.format, b.format) << what;
  EXPECT_EQ(a.dropped_degenerate_faces, b.dropped_degenerate_faces) << what;
  EXPECT_EQ(a.dropped_unreferenced_vertices, b.dropped_unreferenced_vertices) << what;
  EXPECT_EQ(a.dropped_duplicate_faces, b.dropped_duplicate_faces) << what;
  EXPECT_EQ(a.split_nonmanifold_vertices, b.split_nonmanifold_vertices) << what;
  EXPECT_EQ(a.split_pinched_vertices, b.split_pinched_vertices) << what;
  EXPECT_EQ(a.flipped_faces, b.flipped_faces) << what;
  EXPECT_EQ(a.welded_vertices, b.welded_vertices) << what;
  EXPECT_EQ(a.warnings, b.warnings) << what;
}

/// Reads \p path with read_mesh() and its bytes with read_mesh_from_memory() (same name, format from
/// the extension); expects the same mesh and report, or the same error. Returns the file's outcome.
Outcome<MeshRead> expect_same_mesh(const std::filesystem::path& path, const ReadOptions& options = {}) {
  const auto from_file = outcome<MeshRead>([&] {
    MeshRead r;
    r.mesh = read_mesh(path, options, &r.report);
    return r;
  });
  const std::string bytes = read_input_file(path);
  const auto from_memory = outcome<MeshRead>([&] {
    MeshRead r;
    r.mesh = read_mesh_from_memory(bytes, path.extension().string(), path, options, &r.report);
    return r;
  });
  const std::string what = path.filename().string();
  EXPECT_EQ(from_file.value.has_value(), from_memory.value.has_value()) << what << ": " << from_file.message << " / "
                                                                        << from_memory.message;
  EXPECT_EQ(from_file.error_type, from_memory.error_type) << what;
  EXPECT_EQ(from_file.message, from_memory.message) << what;
  if (from_file.value && from_memory.value) {
    EXPECT_EQ(from_file.value->mesh.positions, from_memory.value->mesh.positions) << what;
    EXPECT_EQ(from_file.value->mesh.faces, from_memory.value->mesh.faces) << what;
    expect_same_report(from_file.value->report, from_memory.value->report, what);
  }
  return from_file;
}

TEST(MemoryInput, CodeBuiltMeshesInEveryFormatMatchTheFileReader) {
  TempDir dir;
  const TriMesh torus = shapes::torus(10, 6);
  test::write_off(dir.path / "t.off", torus);
  test::write_off(dir.path / "c.off", torus, true, true);
  test::write_ply_ascii(dir.path / "a.ply", torus, "double");
  test::write_ply_binary(dir.path / "b.ply", torus);
  test::write_stl_ascii(dir.path / "a.stl", torus);
  test::write_stl_binary(dir.path / "b.stl", torus);
  write_obj(dir.path / "t.obj", torus, nullptr);
  for (const char* f : {"t.off", "c.off", "a.ply", "b.ply", "a.stl", "b.stl", "t.obj"}) {
    const auto r = expect_same_mesh(dir.path / f);
    ASSERT_TRUE(r.value) << f << ": " << r.message;
    EXPECT_EQ(r.value->mesh.num_faces(), torus.num_faces()) << f;
  }
  // The repair path: a non-manifold fan is rejected without repair and split with it, alike.
  test::write_off(dir.path / "fan.off", shapes::nonmanifold_fan());
  const auto rejected = expect_same_mesh(dir.path / "fan.off");
  EXPECT_FALSE(rejected.value);
  EXPECT_EQ(rejected.error_type, typeid(TopologyError).name());
  ReadOptions repair;
  repair.repair = true;
  const auto repaired = expect_same_mesh(dir.path / "fan.off", repair);
  ASSERT_TRUE(repaired.value) << repaired.message;
  EXPECT_GT(repaired.value->report.split_nonmanifold_vertices, 0);
}

TEST(MemoryInput, GlbAndGltfWithAnExternalBufferMatchTheFileReader) {
  TempDir dir;
  std::string bin;
  for (float c : {0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 0.f, 1.f, 0.f}) test::put(bin, c);
  const std::string views = R"("bufferViews":[{"buffer":0,"byteLength":36}],
      "accessors":[{"bufferView":0,"componentType":5126,"type":"VEC3","count":3}],
      "meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}],"nodes":[{"mesh":0}],"scenes":[{"nodes":[0]}],"scene":0})";
  test::write_text(dir.path / "tri.glb", test::glb(R"({"asset":{"version":"2.0"},"buffers":[{"byteLength":36}],)" + views, bin));
  test::write_text(dir.path / "tri.bin", bin);
  const std::string external = R"({"asset":{"version":"2.0"},"buffers":[{"uri":"tri.bin","byteLength":36}],)" + views;
  test::write_text(dir.path / "tri.gltf", external);
  for (const char* f : {"tri.glb", "tri.gltf"}) {
    const auto r = expect_same_mesh(dir.path / f);
    ASSERT_TRUE(r.value) << f << ": " << r.message;
    EXPECT_EQ(r.value->mesh.num_faces(), 1) << f;
    EXPECT_EQ(r.value->mesh.positions[1], Vec3(1, 0, 0)) << f;
  }
  // The external buffer is looked for beside the name the bytes are given: elsewhere it does not exist.
  const auto sub = dir.path / "sub";
  std::filesystem::create_directories(sub);
  EXPECT_THROW(read_mesh_from_memory(external, "gltf", sub / "tri.gltf"), IoError);
  // The reader reads the bytes it is given, not the file of that name.
  test::write_text(dir.path / "other.bin", std::string(36, '\0'));
  const TriMesh moved = read_mesh_from_memory(test::glb(R"({"asset":{"version":"2.0"},"buffers":[{"byteLength":36}],)" +
                                                            views, std::string(bin).replace(12, 4, std::string("\0\0\0\x40", 4))),
                                              "glb", dir.path / "tri.glb");
  EXPECT_EQ(moved.positions[1], Vec3(2, 0, 0));
}

TEST(MemoryInput, HostileFilesGiveTheFileReadersError) {
  TempDir dir;
  const std::string bin(36, '\0');
  const std::vector<std::pair<std::string, std::string>> files = {
      {"color.off", "COFF\n3 1 0\n0 0 0 99999999\n1 0 0 1\n0 1 0 2\n3 0 1 2\n"},
      {"neg.off", "OFF\n-3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"},
      {"negidx.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 -1 2\n"},
      {"huge.off", "OFF\n2000000000 2000000000 0\n0 0 0\n"},
      {"st.off", "STCOFF\n3 1 0\n0 0 0 300 0 0\n1 0 0 1 0 0\n0 1 0 1 0 0\n3 0 1 2\n"},
      {"prop.ply", "ply\nformat ascii 1.0\nproperty float x\nend_header\n"},
      {"negative.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                       "element face 1\nproperty list int int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n-5 0 1 2\n"},
      {"count.ply", "ply\nformat ascii 1.0\nelement vertex 4000000000\nproperty float x\nproperty float y\n"
                    "property float z\nend_header\n0 0 0\n"},
      {"short.stl", std::string(80, ' ') + std::string("\xff\xff\xff\x0f", 4)},
      {"nan.obj", "v 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n"},
      {"range.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n"},
      {"forged.glb", test::glb(R"({"asset":{"version":"2.0"},"buffers":[{"byteLength":36}]})", bin, 0xFFFFFFF0u)},
      {"ply.glb", "ply\nformat ascii 1.0\n"},
      {"v1.gltf", R"({"asset":{"version":"1.0"}})"},
      {"nopos.glb", test::glb(R"({"asset":{"version":"2.0"},"meshes":[{"primitives":[{"ittributes":{}}]}]})", bin)},
      {"cycle.gltf", R"({"asset":{"version":"2.0"},"nodes":[{"children":[1]},{"children":[0]}]})"},
      {"zero.gltf", R"({"asset":{"version":"2.0"},"buffers":[{"uri":"../../../../../../../../dev/zero","byteLength":99})"
                    R"(}]})"},
      {"magic.gltf", R"({"asset":{"version":"2.0"},"buffers":[{"uri":"$$$___magic___$$$.gltf","byteLength":9}]})"},
  };
  for (const auto& [file, bytes] : files) {
    test::write_text(dir.path / file, bytes);
    const auto r = expect_same_mesh(dir.path / file);
    EXPECT_FALSE(r.value) << file;
    EXPECT_NE(r.message.find(file), std::string::npos) << r.message;
  }
  // Checks of the bytes themselves, in memory as on disk; an unknown format before anything is read.
  EXPECT_THROW(read_mesh_from_memory("", "off", dir.path / "empty.off"), IoError);
  EXPECT_THROW(read_mesh_from_memory("OFF\n", "txt", dir.path / "m.txt"), IoError);
}

TEST(MemoryInput, ImagesMatchTheFileReader) {
  TempDir dir;
  ImageRGBA8 img(3, 2);
  for (std::size_t k = 0; k < img.data.size(); ++k) img.data[k] = static_cast<std::uint8_t>(k * 11);
  write_png(dir.path / "i.png", img);
  test::write_text(dir.path / "psd.png", test::psd_header());
  test::write_text(dir.path / "huge.png", test::png_header(11'000'000, 25));
  test::write_text(dir.path / "trunc.png", test::png_header(4, 4));
  for (const char* f : {"i.png", "psd.png", "huge.png", "trunc.png"}) {
    const auto path = dir.path / f;
    const auto from_file = outcome<ImageRGBA8>([&] { return read_image(path); });
    const auto from_memory = outcome<ImageRGBA8>([&] { return read_image_from_memory(read_input_file(path), path.string()); });
    EXPECT_EQ(from_file.error_type, from_memory.error_type) << f;
    EXPECT_EQ(from_file.message, from_memory.message) << f;
    ASSERT_EQ(from_file.value.has_value(), from_memory.value.has_value()) << f;
    EXPECT_EQ(from_file.value.has_value(), std::string(f) == "i.png") << f << ": " << from_file.message;
  }
  // The one valid image decodes to the same pixels both ways.
  const ImageRGBA8 a = read_image(dir.path / "i.png");
  const ImageRGBA8 b = read_image_from_memory(read_input_file(dir.path / "i.png"), "i.png");
  EXPECT_EQ(b.width, 3);
  EXPECT_EQ(b.height, 2);
  EXPECT_EQ(b.data, img.data);
  EXPECT_EQ(a.data, img.data);
  EXPECT_THROW(read_image_from_memory("", "empty.png"), IoError);
}

TEST(MemoryInput, PngChunkLongerThanTheFileIsRejectedBeforeDecoding) {
  // Found by the CI's fuzz smoke (session 8): a 116-byte 2x2 PNG whose third chunk claims more
  // bytes than the file has; stb grew its IDAT buffer to 2 GB before reading them.
  const std::string bytes(
      "\x89\x50\x4e\x47\x0d\x0a\x1a\x0a\x00\x00\x00\x0d\x49\x48\x44\x52"
      "\x00\x00\x00\x02\x00\x00\x00\x02\x08\x06\x00\x00\x00\x72\xb6\x0d"
      "\x24\x00\x00\x00\x11\x49\x44\x41\x54\x78\x9c\x63\xf8\xcf\xc0\xf0"
      "\x1f\x84\x19\x60\x0c\x44\x06\x00\x00\x00\x72\xb6\x0d\x24\x74\x00"
      "\x00\x11\x49\x44\x41\x54\x78\x9c\x63\xf8\xcf\xc0\xf0\x1f\xff\x1f"
      "\x60\x0c\x44\x52\x00\x00\x00\x00\x00\x00\x00\x00\x9d\x00\x00\x49"
      "\x45\x52\x00\x00\x00\x00\x00\x00\x00\x00\x9d\x00\x00\x40\x45\x4e"
      "\x44\xae\x42\x60",
      116);
  try {
    read_image_from_memory(bytes, "forged.png");
    ADD_FAILURE() << "a forged chunk length was decoded";
  } catch (const IoError& e) {
    EXPECT_NE(std::string(e.what()).find("forged.png: corrupt PNG: chunk"), std::string::npos) << e.what();
  }
  // A forged chunk type with a newline and a NUL is shown as printable characters (one line).
  std::string nl = bytes.substr(0, 33) + std::string("\x7f\xff\xff\xff\n\0AT", 8);
  try {
    read_image_from_memory(nl, "nl.png");
    ADD_FAILURE() << "a chunk longer than the file was decoded";
  } catch (const IoError& e) {
    EXPECT_NE(std::string(e.what()).find("nl.png: corrupt PNG: chunk \"??AT\" at byte 33 claims 2147483647 bytes"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace adaptex
