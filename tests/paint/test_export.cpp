// Export (docs/export.md): the .glb loads back with tinygltf with one vertex per wedge, UVs flipped to
// glTF's convention, the embedded texture as baseColorTexture; OBJ/MTL/PNG reference each other and
// the OBJ keeps the input positions; nothing is visible before commit.
#include <gtest/gtest.h>
#include <tiny_gltf.h>

#include <cstring>
#include <fstream>
#include <sstream>

#include "adaptex/core/errors.h"
#include "adaptex/core/shapes.h"
#include "adaptex/io/image_io.h"
#include "adaptex/paint/export.h"
#include "test_support.h"

using namespace adaptex;
namespace fs = std::filesystem;

namespace {

/// A two-chart layout of a 4x4-quad plane: the left half in [0.05,0.45]x[0.1,0.9] and the right
/// half in [0.55,0.95]x[0.1,0.9], so the middle column of vertices has two wedges each.
struct Fixture {
  TriMesh mesh = shapes::plane(4, 2.0);
  Parameterization param;
  ImageRGBA8 texture{24, 16};

  Fixture() {
    for (Vec3& p : mesh.positions) p += Vec3(0.125, -3.5, 7.0);  // off-origin, non-unit coordinates
    const int nv = mesh.num_vertices();
    std::vector<int> left(nv, -1), right(nv, -1);
    param.uv_faces.resize(mesh.faces.size());
    param.face_chart.resize(mesh.faces.size());
    for (int f = 0; f < mesh.num_faces(); ++f) {
      const Vec3 c = point_on_face(mesh, f, 1.0 / 3, 1.0 / 3);
      const bool is_left = c.x() < 0.125 + 1.0;
      param.face_chart[f] = is_left ? 0 : 1;
      for (int k = 0; k < 3; ++k) {
        const int v = mesh.faces[f][k];
        std::vector<int>& map = is_left ? left : right;
        if (map[v] < 0) {
          map[v] = param.num_wedges();
          const double x = (mesh.positions[v].x() - 0.125) / 2.0, y = (mesh.positions[v].y() + 3.5) / 2.0;
          const double u = is_left ? 0.05 + 0.8 * x : 0.55 + 0.8 * (x - 0.5);
          param.uv.emplace_back(u, 0.1 + 0.8 * y);
          param.wedge_vertex.push_back(v);
        }
        param.uv_faces[f][k] = map[v];
      }
    }
    param.num_charts = 2;
    for (int j = 0; j < texture.height; ++j)
      for (int i = 0; i < texture.width; ++i) {
        std::uint8_t* t = texture.texel(i, j);
        t[0] = static_cast<std::uint8_t>(10 * i);
        t[1] = static_cast<std::uint8_t>(15 * j);
        t[2] = static_cast<std::uint8_t>((i * 7 + j * 3) % 256);
        t[3] = 255;
      }
  }
};

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

template <class T>
std::vector<T> read_accessor(const tinygltf::Model& m, int acc_index, int comps) {
  const tinygltf::Accessor& acc = m.accessors[acc_index];
  const tinygltf::BufferView& view = m.bufferViews[acc.bufferView];
  const tinygltf::Buffer& buf = m.buffers[view.buffer];
  const size_t stride = view.byteStride ? view.byteStride : sizeof(T) * comps;
  std::vector<T> out(acc.count * comps);
  for (size_t k = 0; k < acc.count; ++k)
    std::memcpy(&out[k * comps], buf.data.data() + view.byteOffset + acc.byteOffset + k * stride,
                sizeof(T) * comps);
  return out;
}

}  // namespace

TEST(Export, GlbLoadsBackWithWedgeVerticesFlippedUvsAndEmbeddedTexture) {
  Fixture fx;
  test::TempDir tmp;
  {
    AtomicOutput out;
    export_textured_mesh(out, tmp.path, "thing", fx.mesh, fx.param, fx.texture);
    out.commit();
  }
  tinygltf::TinyGLTF loader;
  tinygltf::Model model;
  std::string err, warn;
  ASSERT_TRUE(loader.LoadBinaryFromFile(&model, &err, &warn, (tmp.path / "thing.glb").string())) << err;
  EXPECT_TRUE(err.empty()) << err;
  ASSERT_EQ(model.meshes.size(), 1u);
  ASSERT_EQ(model.meshes[0].primitives.size(), 1u);
  const tinygltf::Primitive& prim = model.meshes[0].primitives[0];
  EXPECT_EQ(prim.mode, TINYGLTF_MODE_TRIANGLES);
  ASSERT_TRUE(prim.attributes.count("POSITION"));
  ASSERT_TRUE(prim.attributes.count("TEXCOORD_0"));
  ASSERT_TRUE(prim.attributes.count("NORMAL"));
  const int nw = fx.param.num_wedges();
  EXPECT_GT(nw, fx.mesh.num_vertices());  // the seam column is split
  const tinygltf::Accessor& pacc = model.accessors[prim.attributes.at("POSITION")];
  EXPECT_EQ(static_cast<int>(pacc.count), nw);
  ASSERT_EQ(pacc.minValues.size(), 3u);
  ASSERT_EQ(pacc.maxValues.size(), 3u);
  const auto pos = read_accessor<float>(model, prim.attributes.at("POSITION"), 3);
  const auto uv = read_accessor<float>(model, prim.attributes.at("TEXCOORD_0"), 2);
  const auto nrm = read_accessor<float>(model, prim.attributes.at("NORMAL"), 3);
  ASSERT_EQ(static_cast<int>(uv.size()), 2 * nw);
  for (int w = 0; w < nw; ++w) {
    const Vec3& p = fx.mesh.positions[fx.param.wedge_vertex[w]];
    for (int k = 0; k < 3; ++k) {
      EXPECT_FLOAT_EQ(pos[3 * w + k], static_cast<float>(p[k]));
      EXPECT_GE(pos[3 * w + k], pacc.minValues[k]);
      EXPECT_LE(pos[3 * w + k], pacc.maxValues[k]);
    }
    EXPECT_GE(uv[2 * w], 0.0f);
    EXPECT_LE(uv[2 * w], 1.0f);
    EXPECT_FLOAT_EQ(uv[2 * w], static_cast<float>(fx.param.uv[w].x()));
    EXPECT_FLOAT_EQ(uv[2 * w + 1], static_cast<float>(1.0 - fx.param.uv[w].y()));
    EXPECT_NEAR(std::abs(nrm[3 * w + 2]), 1.0f, 1e-6);  // flat plane: normal along z
  }
  const auto idx = read_accessor<std::uint32_t>(model, prim.indices, 1);
  ASSERT_EQ(idx.size(), 3 * fx.mesh.faces.size());
  for (int f = 0; f < fx.mesh.num_faces(); ++f)
    for (int k = 0; k < 3; ++k) EXPECT_EQ(static_cast<int>(idx[3 * f + k]), fx.param.uv_faces[f][k]);

  // Material -> texture -> image embedded in a bufferView, decoded to the texture size; the glTF
  // image's first row is the texture's top row (v = 1).
  ASSERT_EQ(model.materials.size(), 1u);
  const int ti = model.materials[prim.material].pbrMetallicRoughness.baseColorTexture.index;
  ASSERT_GE(ti, 0);
  const tinygltf::Image& img = model.images[model.textures[ti].source];
  EXPECT_GE(img.bufferView, 0);
  EXPECT_TRUE(img.uri.empty());
  EXPECT_EQ(img.mimeType, "image/png");
  ASSERT_EQ(img.width, fx.texture.width);
  ASSERT_EQ(img.height, fx.texture.height);
  ASSERT_EQ(img.component, 4);
  for (int row = 0; row < img.height; ++row)
    for (int i = 0; i < img.width; ++i)
      ASSERT_EQ(0, std::memcmp(&img.image[(static_cast<size_t>(row) * img.width + i) * 4],
                               fx.texture.texel(i, fx.texture.height - 1 - row), 4))
          << i << "," << row;
  const tinygltf::Sampler& s = model.samplers[model.textures[ti].sampler];
  EXPECT_EQ(s.wrapS, TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE);
  EXPECT_EQ(s.wrapT, TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE);
  EXPECT_EQ(s.magFilter, TINYGLTF_TEXTURE_FILTER_LINEAR);
}

TEST(Export, ObjMtlPngReferenceEachOtherAndKeepPositions) {
  Fixture fx;
  test::TempDir tmp;
  {
    AtomicOutput out;
    const ExportedFiles files =
        export_textured_mesh(out, tmp.path / "sub", "thing", fx.mesh, fx.param, fx.texture);
    EXPECT_EQ(files.obj, tmp.path / "sub" / "thing.obj");
    out.commit();
  }
  const fs::path dir = tmp.path / "sub";
  const std::string obj = slurp(dir / "thing.obj"), mtl = slurp(dir / "thing.mtl");
  EXPECT_NE(obj.find("mtllib thing.mtl"), std::string::npos);
  EXPECT_NE(obj.find("usemtl adaptex_paint"), std::string::npos);
  EXPECT_NE(mtl.find("newmtl adaptex_paint"), std::string::npos);
  EXPECT_NE(mtl.find("Kd 1 1 1"), std::string::npos);
  EXPECT_NE(mtl.find("map_Kd thing.png"), std::string::npos);
  const ImageRGBA8 png = read_image(dir / "thing.png");
  EXPECT_EQ(png.width, fx.texture.width);
  EXPECT_EQ(png.data, fx.texture.data);  // rows round-trip (write_png / read_image both flip)

  // `v` lines equal the input positions, `vt` the wedge UVs, `f v/vt` the faces.
  std::istringstream in(obj);
  std::string line;
  std::vector<Vec3> v;
  std::vector<Vec2> vt;
  std::vector<std::array<int, 6>> f;
  while (std::getline(in, line)) {
    std::istringstream ls(line);
    std::string tag;
    ls >> tag;
    if (tag == "v") {
      Vec3 p;
      ls >> p.x() >> p.y() >> p.z();
      v.push_back(p);
    } else if (tag == "vt") {
      Vec2 t;
      ls >> t.x() >> t.y();
      vt.push_back(t);
    } else if (tag == "f") {
      std::array<int, 6> c{};
      char slash;
      for (int k = 0; k < 3; ++k) ls >> c[2 * k] >> slash >> c[2 * k + 1];
      f.push_back(c);
    }
  }
  ASSERT_EQ(v.size(), fx.mesh.positions.size());
  for (size_t k = 0; k < v.size(); ++k) EXPECT_EQ(v[k], fx.mesh.positions[k]) << k;
  ASSERT_EQ(vt.size(), fx.param.uv.size());
  ASSERT_EQ(f.size(), fx.mesh.faces.size());
  for (size_t k = 0; k < f.size(); ++k)
    for (int c = 0; c < 3; ++c) {
      EXPECT_EQ(f[k][2 * c] - 1, fx.mesh.faces[k][c]);
      EXPECT_LT((vt[f[k][2 * c + 1] - 1] - fx.param.uv[fx.param.uv_faces[k][c]]).norm(), 1e-9);
    }
}

TEST(Export, NothingIsVisibleWithoutCommitAndTheDirectoryIsRemoved) {
  Fixture fx;
  test::TempDir tmp;
  {
    AtomicOutput out;
    export_textured_mesh(out, tmp.path / "new", "thing", fx.mesh, fx.param, fx.texture);
    // destroyed without commit (as when a later step throws)
  }
  EXPECT_FALSE(fs::exists(tmp.path / "new"));
  EXPECT_TRUE(fs::is_empty(tmp.path));
}

TEST(Export, BadNamesAndInconsistentInputsAreRejected) {
  Fixture fx;
  test::TempDir tmp;
  for (const char* bad : {"", "a/b", "a b", "..", "x\ty"}) {
    AtomicOutput out;
    EXPECT_THROW(export_textured_mesh(out, tmp.path, bad, fx.mesh, fx.param, fx.texture),
                 InvalidInputError)
        << bad;
  }
  EXPECT_EQ(sanitize_export_name("my mesh"), "my_mesh");
  EXPECT_EQ(sanitize_export_name(""), "mesh");
  Parameterization short_param = fx.param;
  short_param.uv_faces.pop_back();
  AtomicOutput out;
  EXPECT_THROW(export_textured_mesh(out, tmp.path, "x", fx.mesh, short_param, fx.texture),
               InvalidInputError);
  EXPECT_THROW(export_textured_mesh(out, tmp.path, "x", fx.mesh, fx.param, ImageRGBA8{}),
               InvalidInputError);
  EXPECT_TRUE(fs::is_empty(tmp.path));
}

TEST(Export, LayoutPictureDrawsTheEdges) {
  Fixture fx;
  const ImageRGBA8 pic = draw_uv_layout(fx.param, nullptr, 100);
  ASSERT_EQ(pic.width, 100);
  // A vertical chart border at u = 0.05 is dark, the gap between charts (u = 0.5) is white.
  EXPECT_EQ(pic.texel(5, 50)[0], (3 * 255 + 2 * 40) / 5);  // white blended 40% towards dark grey
  EXPECT_EQ(pic.texel(50, 50)[0], 255);
}
