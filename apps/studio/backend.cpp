/// \file backend.cpp
/// The studio's bridge to the adaptex library (see backend.h). Each ADAPTEX_STUDIO_HAVE_* switch
/// (set in apps/studio/CMakeLists.txt) selects the library function; the #else branches are small
/// stand-ins used only while a library part has not landed yet.
#include "backend.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

#include "adaptex/core/atomic_output.h"
#include "adaptex/core/errors.h"
#include "adaptex/core/shapes.h"
#include "adaptex/io/image_io.h"
#include "stroke_json.h"

#if ADAPTEX_STUDIO_HAVE_MESH_IO
#include "adaptex/io/mesh_io.h"
#endif
#if ADAPTEX_STUDIO_HAVE_UNWRAP
#include "adaptex/param/unwrap.h"
#endif
#if ADAPTEX_STUDIO_HAVE_PAINTER
#include "adaptex/paint/painter.h"
#endif
#if ADAPTEX_STUDIO_HAVE_EXPORT
#include "adaptex/paint/export.h"
#endif

namespace adaptex::studio {

// ---- mesh -------------------------------------------------------------------------------------

namespace {
TriMesh builtin_mesh(const std::string& name) {
  if (name == "sphere") return shapes::sphere(64, 32, 1.0);
  if (name == "icosphere") return shapes::icosphere(4, 1.0);
  if (name == "torus") return shapes::torus(96, 48);
  if (name == "trefoil") return shapes::trefoil_knot();
  if (name == "plane") return shapes::plane(32, 2.0);
  throw InvalidInputError("builtin:" + name + ": unknown built-in shape (sphere, icosphere, torus, trefoil, plane)");
}

#if !ADAPTEX_STUDIO_HAVE_MESH_IO
// Stand-in reader: OBJ (v/f) and OFF, fan-triangulated.
TriMesh read_simple(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) throw IoError(path.string() + ": cannot open file");
  TriMesh m;
  const std::string ext = path.extension().string();
  std::string line;
  auto add_poly = [&](const std::vector<int>& p) {
    for (size_t k = 2; k < p.size(); ++k) m.faces.push_back({p[0], p[k - 1], p[k]});
  };
  if (ext == ".off") {
    std::string tok;
    in >> tok;
    int nv = 0, nf = 0, ne = 0;
    in >> nv >> nf >> ne;
    std::getline(in, line);
    for (int i = 0; i < nv && std::getline(in, line);) {
      std::istringstream ls(line);
      double x, y, z;
      if (ls >> x >> y >> z) {
        m.positions.emplace_back(x, y, z);
        ++i;
      }
    }
    for (int i = 0; i < nf && std::getline(in, line);) {
      std::istringstream ls(line);
      int n;
      if (!(ls >> n)) continue;
      std::vector<int> p(n);
      for (int& v : p) ls >> v;
      add_poly(p);
      ++i;
    }
  } else if (ext == ".obj") {
    while (std::getline(in, line)) {
      std::istringstream ls(line);
      std::string t;
      ls >> t;
      if (t == "v") {
        double x, y, z;
        ls >> x >> y >> z;
        m.positions.emplace_back(x, y, z);
      } else if (t == "f") {
        std::vector<int> p;
        std::string c;
        while (ls >> c) {
          int v = std::stoi(c.substr(0, c.find('/')));
          p.push_back(v < 0 ? int(m.positions.size()) + v : v - 1);
        }
        add_poly(p);
      }
    }
  } else {
    throw IoError(path.string() + ": unsupported format (stand-in reader: .obj, .off)");
  }
  if (m.faces.empty()) throw InvalidInputError(path.string() + ": no faces");
  for (const Face& f : m.faces)
    for (int v : f)
      if (v < 0 || v >= m.num_vertices()) throw InvalidInputError(path.string() + ": face index out of range");
  return m;
}
#endif
}  // namespace

TriMesh load_mesh(const std::string& path) {
  if (path.rfind("builtin:", 0) == 0) return builtin_mesh(path.substr(8));
  if (!std::filesystem::exists(path)) throw IoError(path + ": no such file");
#if ADAPTEX_STUDIO_HAVE_MESH_IO
  return read_mesh(path);
#else
  return read_simple(path);
#endif
}

// ---- unwrap -----------------------------------------------------------------------------------

Parameterization unwrap_mesh(const TriMesh& mesh, const ProgressCallback& progress) {
#if ADAPTEX_STUDIO_HAVE_UNWRAP
  UnwrapOptions opt;
  opt.progress = progress;
  return unwrap(mesh, opt).param;
#else
  // Stand-in: every face in its own half grid cell (correct, but all edges are seams).
  Parameterization p;
  const int F = mesh.num_faces();
  const int n = std::max(1, int(std::ceil(std::sqrt(F / 2.0))));
  const double cell = 1.0 / n, m = cell * 0.08;
  for (int f = 0; f < F; ++f) {
    if (f % 1024 == 0) report_progress(progress, "unwrap", double(f) / F);
    const int c = f / 2, cx = c % n, cy = c / n;
    const double x0 = cx * cell + m, y0 = cy * cell + m, x1 = (cx + 1) * cell - m, y1 = (cy + 1) * cell - m;
    const int base = p.num_wedges();
    if (f % 2 == 0) {
      p.uv.insert(p.uv.end(), {Vec2(x0, y0), Vec2(x1 - m, y0), Vec2(x0, y1 - m)});
    } else {
      p.uv.insert(p.uv.end(), {Vec2(x1, y1), Vec2(x0 + m, y1), Vec2(x1, y0 + m)});
    }
    p.uv_faces.push_back({base, base + 1, base + 2});
    for (int k = 0; k < 3; ++k) p.wedge_vertex.push_back(mesh.faces[f][k]);
    p.face_chart.push_back(f);
  }
  p.num_charts = F;
  report_progress(progress, "unwrap", 1.0);
  return p;
#endif
}

// ---- canvas -----------------------------------------------------------------------------------

#if ADAPTEX_STUDIO_HAVE_PAINTER
struct Canvas::Impl {
  Painter painter;
  Impl(const TriMesh& mesh, const Parameterization& param, int w, int h, const Vec3& bg)
      : painter(mesh, param, PainterOptions{w, h, 4}, bg) {}
};
Canvas::Canvas(const TriMesh& mesh, const Parameterization& param, int width, int height, const Vec3& background)
    : impl_(std::make_unique<Impl>(mesh, param, width, height, background)), width_(width), height_(height) {}
void Canvas::paint_stroke(const Stroke& s) { impl_->painter.paint_stroke(s); }
void Canvas::begin_stroke(const Stroke& s) { impl_->painter.begin_stroke(s); }
std::array<int, 4> Canvas::add_dab(const Vec3& c) { return impl_->painter.add_dab(c); }
void Canvas::end_stroke() { impl_->painter.end_stroke(); }
const ImageRGBA8& Canvas::texture() { return impl_->painter.texture(); }
#else
// Stand-in painter: rasterized texel points, brute-force dab evaluation of the contract.
double falloff(double t, double h) {
  if (t <= h) return 1.0;
  if (t >= 1.0) return 0.0;
  const double s = (t - h) / (1.0 - h);
  return 1.0 - (3 * s * s - 2 * s * s * s);
}
struct Canvas::Impl {
  int w = 0, h = 0;
  std::vector<int> inside;              // texel indices inside a chart
  std::vector<Vec3f> pos;               // per inside texel
  std::vector<Eigen::Vector3f> colour;  // per inside texel: colour before the open stroke
  std::vector<float> alpha;             // per inside texel: coverage of the open stroke
  std::vector<int> touched;
  Stroke style;
  ImageRGBA8 tex;
  void store(size_t k) {
    const Eigen::Vector3f c = colour[k] * (1 - alpha[k]) + style.color.cast<float>() * alpha[k];
    uint8_t* t = &tex.data[size_t(inside[k]) * 4];
    for (int q = 0; q < 3; ++q) t[q] = uint8_t(std::lround(std::clamp(c[q], 0.f, 1.f) * 255));
  }
};
Canvas::Canvas(const TriMesh& mesh, const Parameterization& param, int width, int height, const Vec3& bg)
    : impl_(std::make_unique<Impl>()), width_(width), height_(height) {
  Impl& I = *impl_;
  I.w = width;
  I.h = height;
  I.tex = ImageRGBA8(width, height, {uint8_t(std::lround(bg.x() * 255)), uint8_t(std::lround(bg.y() * 255)),
                                     uint8_t(std::lround(bg.z() * 255)), 255});
  std::vector<int> owner(size_t(width) * height, -1);
  for (int f = 0; f < mesh.num_faces(); ++f) {
    Vec2 a = param.uv[param.uv_faces[f][0]], b = param.uv[param.uv_faces[f][1]], c = param.uv[param.uv_faces[f][2]];
    const double area = (b - a).x() * (c - a).y() - (b - a).y() * (c - a).x();
    if (std::abs(area) < 1e-300) continue;
    const int i0 = std::max(0, int(std::floor(std::min({a.x(), b.x(), c.x()}) * width - 0.5)));
    const int i1 = std::min(width - 1, int(std::ceil(std::max({a.x(), b.x(), c.x()}) * width - 0.5)));
    const int j0 = std::max(0, int(std::floor(std::min({a.y(), b.y(), c.y()}) * height - 0.5)));
    const int j1 = std::min(height - 1, int(std::ceil(std::max({a.y(), b.y(), c.y()}) * height - 0.5)));
    for (int j = j0; j <= j1; ++j)
      for (int i = i0; i <= i1; ++i) {
        const Vec2 p((i + 0.5) / width, (j + 0.5) / height);
        const double l1 = ((c - b).x() * (p - b).y() - (c - b).y() * (p - b).x()) / area;
        const double l2 = ((a - c).x() * (p - c).y() - (a - c).y() * (p - c).x()) / area;
        const double l3 = 1 - l1 - l2;
        if (l1 < 0 || l2 < 0 || l3 < 0 || owner[size_t(j) * width + i] >= 0) continue;
        owner[size_t(j) * width + i] = f;
        I.inside.push_back(j * width + i);
        I.pos.push_back(point_on_face(mesh, f, l1, l2).cast<float>());
      }
  }
  I.colour.assign(I.inside.size(), bg.cast<float>());
  I.alpha.assign(I.inside.size(), 0.f);
}
void Canvas::begin_stroke(const Stroke& s) {
  impl_->style = s;
  impl_->touched.clear();
}
std::array<int, 4> Canvas::add_dab(const Vec3& c) {
  Impl& I = *impl_;
  std::array<int, 4> rect{I.w, I.h, -1, -1};
  const Vec3f cf = c.cast<float>();
  const float r = float(I.style.radius);
  for (size_t k = 0; k < I.inside.size(); ++k) {
    const float d = (I.pos[k] - cf).norm();
    if (d >= r) continue;
    const float a = float(I.style.opacity * falloff(d / r, I.style.hardness));
    if (a <= I.alpha[k]) continue;
    if (I.alpha[k] == 0.f) I.touched.push_back(int(k));
    I.alpha[k] = a;
    I.store(k);
    const int i = I.inside[k] % I.w, j = I.inside[k] / I.w;
    rect = {std::min(rect[0], i), std::min(rect[1], j), std::max(rect[2], i), std::max(rect[3], j)};
  }
  return rect;
}
void Canvas::end_stroke() {
  Impl& I = *impl_;
  for (int k : I.touched) {
    I.colour[k] = I.colour[k] * (1 - I.alpha[k]) + I.style.color.cast<float>() * I.alpha[k];
    I.alpha[k] = 0.f;
  }
  I.touched.clear();
}
void Canvas::paint_stroke(const Stroke& s) {
  if (s.type != Stroke::Type::Brush) return;  // decals need the library painter
  begin_stroke(s);
  for (const Vec3& d : s.dabs) add_dab(d);
  end_stroke();
}
const ImageRGBA8& Canvas::texture() { return impl_->tex; }
#endif

Canvas::~Canvas() = default;

// ---- files ------------------------------------------------------------------------------------

StrokeFile load_strokes(const std::filesystem::path& path) {
#if ADAPTEX_STUDIO_HAVE_STROKES_IO
  return read_strokes(path);
#else
  std::ifstream in(path);
  if (!in) throw IoError(path.string() + ": cannot open file");
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(in);
  } catch (const std::exception& e) {
    throw IoError(path.string() + ": not valid JSON");
  }
  return strokes_from_json(j, path.string(), path.parent_path());
#endif
}

void save_strokes(const std::filesystem::path& path, const StrokeFile& file) {
  AtomicOutput out;
  const auto tmp = out.add(path);
#if ADAPTEX_STUDIO_HAVE_STROKES_IO
  write_strokes(tmp, file);
#else
  std::ofstream o(tmp);
  o << strokes_to_json(file).dump(1) << "\n";
  if (!o) throw IoError(path.string() + ": write failed");
#endif
  out.commit();
}

void export_obj(const std::filesystem::path& dir, const std::string& name, const TriMesh& mesh,
                const Parameterization& param, const ImageRGBA8& texture) {
#if ADAPTEX_STUDIO_HAVE_EXPORT && 0
#else
  AtomicOutput out;
  const auto obj = out.add(dir / (name + ".obj"));
  const auto mtl = out.add(dir / (name + ".mtl"));
  const auto png = out.add(dir / (name + ".png"));
  {
    std::ofstream o(obj);
    o.precision(17);
    o << "mtllib " << name << ".mtl\n";
    for (const Vec3& p : mesh.positions) o << "v " << p.x() << " " << p.y() << " " << p.z() << "\n";
    for (const Vec2& t : param.uv) o << "vt " << t.x() << " " << t.y() << "\n";
    o << "usemtl adaptex_paint\n";
    for (int f = 0; f < mesh.num_faces(); ++f) {
      o << "f";
      for (int k = 0; k < 3; ++k) o << " " << mesh.faces[f][k] + 1 << "/" << param.uv_faces[f][k] + 1;
      o << "\n";
    }
    if (!o) throw IoError((dir / (name + ".obj")).string() + ": write failed");
  }
  {
    std::ofstream o(mtl);
    o << "newmtl adaptex_paint\nKd 1 1 1\nmap_Kd " << name << ".png\n";
  }
  write_png(png, texture);
  out.commit();
#endif
}

void export_glb(const std::filesystem::path& path, const TriMesh& mesh, const Parameterization& param,
                const ImageRGBA8& texture) {
#if ADAPTEX_STUDIO_HAVE_EXPORT && 0
#else
  (void)mesh;
  (void)param;
  (void)texture;
  throw IoError(path.string() + ": .glb export is not available in this build yet");
#endif
}

void save_png(const std::filesystem::path& path, const ImageRGBA8& img) {
  AtomicOutput out;
  write_png(out.add(path), img);
  out.commit();
}

ImageRGBA8 load_image(const std::filesystem::path& path) { return read_image(path); }

std::string backend_summary() {
  std::string s;
  s += ADAPTEX_STUDIO_HAVE_MESH_IO ? "mesh_io " : "mesh_io(fallback) ";
  s += ADAPTEX_STUDIO_HAVE_UNWRAP ? "unwrap " : "unwrap(fallback) ";
  s += ADAPTEX_STUDIO_HAVE_PAINTER ? "painter " : "painter(fallback) ";
  s += ADAPTEX_STUDIO_HAVE_STROKES_IO ? "strokes " : "strokes(studio) ";
  s += ADAPTEX_STUDIO_HAVE_EXPORT ? "export" : "export(obj only)";
  return s;
}

}  // namespace adaptex::studio

namespace adaptex::studio {

bool adapt_available() { return ADAPTEX_STUDIO_HAVE_ADAPT != 0; }

AdaptOutcome adapt_step(const TriMesh& mesh, const Parameterization& param, const ImageRGBA8& texture,
                        const StrokeFile& strokes, const AdaptRequest& request, const ProgressCallback& progress) {
  (void)mesh;
  (void)param;
  (void)texture;
  (void)strokes;
  (void)request;
  (void)progress;
  throw Error("adaptive re-parameterization is not available in this build yet");
}

}  // namespace adaptex::studio
