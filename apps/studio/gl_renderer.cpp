/// \file gl_renderer.cpp
/// OpenGL 3.3 core renderer (see gl_renderer.h). GL entry points come from libGL through
/// GL_GLEXT_PROTOTYPES (Mesa exports every core function).
#define GL_GLEXT_PROTOTYPES 1
#include "gl_renderer.h"

#include <GL/gl.h>
#include <GL/glext.h>

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "adaptex/paint/tangent_frame.h"

#include "backend.h"

namespace adaptex::studio {
namespace {

constexpr int kStride = 12;  // floats per vertex: position, normal, uv, tangent

const char* kMeshVs = R"(#version 330 core
layout(location = 0) in vec3 a_pos;
layout(location = 1) in vec3 a_normal;
layout(location = 2) in vec2 a_uv;
layout(location = 3) in vec4 a_tangent;  // MikkTSpace, w = handedness (the exporter's frame)
uniform mat4 u_view;
uniform mat4 u_proj;
out vec3 v_normal_eye;
out vec4 v_tangent_eye;
out vec3 v_pos_eye;
out vec2 v_uv;
void main() {
  vec4 pe = u_view * vec4(a_pos, 1.0);
  v_pos_eye = pe.xyz;
  v_normal_eye = mat3(u_view) * a_normal;
  v_tangent_eye = vec4(mat3(u_view) * a_tangent.xyz, a_tangent.w);
  v_uv = a_uv;
  gl_Position = u_proj * pe;
})";

// Base colour: the painted texture under a soft studio light. Lit material (u_mode 2): GGX specular
// (Smith-Schlick visibility, Schlick Fresnel) of one key light plus an analytic sky/ground environment
// (its radiance blurred towards the irradiance with the roughness, Karis' split-sum fit for the BRDF
// scale), metallic workflow, the normal map decoded in the interpolated tangent frame.
const char* kMeshFs = R"(#version 330 core
in vec3 v_normal_eye;
in vec4 v_tangent_eye;
in vec3 v_pos_eye;
in vec2 v_uv;
uniform sampler2D u_tex;
uniform sampler2D u_mr;      // glTF packing: G = roughness, B = metallic
uniform sampler2D u_normal;  // tangent space, (n + 1) / 2
uniform int u_mode;  // 0 = base colour, 1 = flat colour, 2 = lit material
uniform vec4 u_color;
uniform vec3 u_up;   // world +Y in eye space (the environment's zenith)
uniform float u_checker;  // > 0: checker squares per unit of uv (texture size / texels per square)
out vec4 frag;
const float PI = 3.14159265;
vec3 sky(vec3 d) {  // radiance of the environment along eye-space direction d
  float y = dot(d, u_up);
  vec3 up = mix(vec3(1.1, 1.15, 1.2), vec3(0.35, 0.55, 0.95), smoothstep(0.0, 0.7, y));
  vec3 down = mix(vec3(0.45, 0.4, 0.35), vec3(0.18, 0.15, 0.12), smoothstep(0.0, 0.5, -y));
  return y >= 0.0 ? up : down;
}
vec3 irradiance(vec3 n) {  // cosine-weighted sky over the hemisphere of n, a cheap fit
  float y = dot(n, u_up);
  return mix(vec3(0.3, 0.27, 0.23), vec3(0.75, 0.85, 1.05), 0.5 + 0.5 * y);
}
vec3 lit(vec3 base, float rough, float metal, vec3 n, vec3 v) {
  rough = clamp(rough, 0.04, 1.0);
  float a = rough * rough, a2 = a * a;
  vec3 f0 = mix(vec3(0.04), base, metal);
  vec3 diffuse = base * (1.0 - metal);
  float nv = max(dot(n, v), 1e-4);
  vec3 l = normalize(vec3(0.45, 0.6, 0.66));
  vec3 h = normalize(l + v);
  float nl = max(dot(n, l), 0.0), nh = max(dot(n, h), 0.0), vh = max(dot(v, h), 0.0);
  float dn = nh * nh * (a2 - 1.0) + 1.0;
  float D = a2 / (PI * dn * dn);
  float k = (rough + 1.0) * (rough + 1.0) / 8.0;
  float G = nv / (nv * (1.0 - k) + k) * nl / (nl * (1.0 - k) + k);
  vec3 F = f0 + (1.0 - f0) * pow(1.0 - vh, 5.0);
  vec3 key = (diffuse * (1.0 - F) / PI + D * G * F / max(4.0 * nl * nv, 1e-4)) * nl * 3.2;
  // Environment: Karis' analytic fit of the split-sum BRDF scale and bias.
  vec4 c0 = vec4(-1.0, -0.0275, -0.572, 0.022), c1 = vec4(1.0, 0.0425, 1.04, -0.04);
  vec4 r = rough * c0 + c1;
  float a004 = min(r.x * r.x, exp2(-9.28 * nv)) * r.x + r.y;
  vec2 ab = vec2(-1.04, 1.04) * a004 + r.zw;
  vec3 refl = mix(sky(reflect(-v, n)), irradiance(n), rough);
  vec3 env = diffuse * irradiance(n) * 0.6 + refl * (f0 * ab.x + ab.y);
  return key + env;
}
void main() {
  if (u_mode == 1) { frag = u_color; return; }
  vec3 n = normalize(v_normal_eye);
  vec3 v = normalize(-v_pos_eye);
  if (dot(n, v) < 0.0) n = -n;  // the back of an open surface
  vec3 albedo = texture(u_tex, v_uv).rgb;
  if (u_checker > 0.0) {  // texel-density checker: every square holds the same number of texels
    vec2 c = floor(v_uv * u_checker);
    float odd = mod(c.x + c.y, 2.0);
    albedo = mix(albedo, mix(vec3(0.93), vec3(0.18, 0.2, 0.28), odd), 0.45);
  }
  if (u_mode == 2) {
    vec3 t = v_tangent_eye.xyz - n * dot(n, v_tangent_eye.xyz);
    t = dot(t, t) > 1e-12 ? normalize(t) : normalize(cross(n, abs(n.x) < 0.9 ? vec3(1, 0, 0) : vec3(0, 1, 0)));
    vec3 b = (v_tangent_eye.w < 0.0 ? -1.0 : 1.0) * cross(n, t);
    vec3 tn = texture(u_normal, v_uv).xyz * 2.0 - 1.0;
    vec3 nm = normalize(t * tn.x + b * tn.y + n * tn.z);
    vec2 mr = texture(u_mr, v_uv).gb;
    vec3 c = lit(pow(albedo, vec3(2.2)), mr.x, mr.y, nm, v);
    c = c / (1.0 + 0.25 * c);  // a gentle shoulder, then sRGB
    frag = vec4(pow(c, vec3(1.0 / 2.2)), 1.0);
    return;
  }
  vec3 l = normalize(vec3(0.3, 0.5, 1.0));
  float d = abs(dot(n, l));
  vec3 h = normalize(l + v);
  float s = pow(abs(dot(n, h)), 48.0) * 0.12;
  frag = vec4(albedo * (0.35 + 0.65 * d) + vec3(s), 1.0);
})";

/// A 1x1 texture of \p rgba (linear filtering, clamped): the default of a material map.
GLuint make_texture(const unsigned char rgba[4]) {
  GLuint t = 0;
  glGenTextures(1, &t);
  glBindTexture(GL_TEXTURE_2D, t);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, 1, 1, 0, GL_RGBA, GL_UNSIGNED_BYTE, rgba);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  return t;
}

/// Uploads \p img into texture \p t, or \p fallback (1x1) when \p img is empty.
void upload(GLuint t, const ImageRGBA8& img, const unsigned char fallback[4]) {
  glBindTexture(GL_TEXTURE_2D, t);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glPixelStorei(GL_UNPACK_ROW_LENGTH, 0);
  if (img.empty())
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, 1, 1, 0, GL_RGBA, GL_UNSIGNED_BYTE, fallback);
  else
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, img.width, img.height, 0, GL_RGBA, GL_UNSIGNED_BYTE, img.data.data());
}

const unsigned char kWhite[4] = {255, 255, 255, 255};
const unsigned char kPlainMr[4] = {255, 128, 0, 255};  // roughness 0.5, metallic 0
const unsigned char kFlatNormal[4] = {128, 128, 255, 255};

GLuint compile(GLenum type, const char* src) {
  GLuint s = glCreateShader(type);
  glShaderSource(s, 1, &src, nullptr);
  glCompileShader(s);
  GLint ok = 0;
  glGetShaderiv(s, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    char log[2048];
    glGetShaderInfoLog(s, sizeof log, nullptr, log);
    throw std::runtime_error(std::string("studio: shader compile failed: ") + log);
  }
  return s;
}

}  // namespace

struct GlRenderer::Impl {
  GLuint program = 0, vao = 0, vbo = 0, ibo = 0, tex = 0, mr = 0, normal = 0;
  GLsizei index_count = 0;
  int tex_w = 0, tex_h = 0;
  std::map<int, std::pair<GLuint, std::pair<int, int>>> ui_textures;
};

GlRenderer::GlRenderer() : impl_(std::make_unique<Impl>()) {
  Impl& I = *impl_;
  GLuint vs = compile(GL_VERTEX_SHADER, kMeshVs), fs = compile(GL_FRAGMENT_SHADER, kMeshFs);
  I.program = glCreateProgram();
  glAttachShader(I.program, vs);
  glAttachShader(I.program, fs);
  glLinkProgram(I.program);
  glDeleteShader(vs);
  glDeleteShader(fs);
  GLint ok = 0;
  glGetProgramiv(I.program, GL_LINK_STATUS, &ok);
  if (!ok) throw std::runtime_error("studio: shader link failed");
  glGenVertexArrays(1, &I.vao);
  glGenBuffers(1, &I.vbo);
  glGenBuffers(1, &I.ibo);
  I.tex = make_texture(kWhite);
  I.mr = make_texture(kPlainMr);
  I.normal = make_texture(kFlatNormal);
}

GlRenderer::~GlRenderer() {
  Impl& I = *impl_;
  glDeleteProgram(I.program);
  glDeleteVertexArrays(1, &I.vao);
  glDeleteBuffers(1, &I.vbo);
  glDeleteBuffers(1, &I.ibo);
  for (GLuint t : {I.tex, I.mr, I.normal}) glDeleteTextures(1, &t);
  for (auto& [slot, t] : I.ui_textures) glDeleteTextures(1, &t.first);
}

void GlRenderer::set_mesh(const TriMesh& mesh, const Parameterization& param, const std::vector<Vec3>* normals) {
  Impl& I = *impl_;
  // One vertex per wedge: position, normal, uv, tangent (the lit preview's normal-map frame).
  const std::vector<Vec3> own = normals ? std::vector<Vec3>() : vertex_normals(mesh);
  const std::vector<Vec3>& vn = normals ? *normals : own;
  const std::vector<Eigen::Vector4d> tangents = wedge_tangents(mesh, param, vn);
  std::vector<float> vb(size_t(param.num_wedges()) * kStride);
  for (int w = 0; w < param.num_wedges(); ++w) {
    const int v = param.wedge_vertex[w];
    const Vec3 n = vn[size_t(v)].normalized();
    float* o = &vb[size_t(w) * kStride];
    for (int k = 0; k < 3; ++k) o[k] = float(mesh.positions[v][k]);
    for (int k = 0; k < 3; ++k) o[3 + k] = std::isfinite(n[k]) ? float(n[k]) : 0.f;
    o[6] = float(param.uv[w].x());
    o[7] = float(param.uv[w].y());
    for (int k = 0; k < 4; ++k) o[8 + k] = std::isfinite(tangents[size_t(w)][k]) ? float(tangents[size_t(w)][k]) : 0.f;
  }
  std::vector<unsigned> ib;
  ib.reserve(param.uv_faces.size() * 3);
  for (const Face& f : param.uv_faces)
    for (int k : f) ib.push_back(unsigned(k));
  glBindVertexArray(I.vao);
  glBindBuffer(GL_ARRAY_BUFFER, I.vbo);
  glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(vb.size() * sizeof(float)), vb.data(), GL_STATIC_DRAW);
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, I.ibo);
  glBufferData(GL_ELEMENT_ARRAY_BUFFER, GLsizeiptr(ib.size() * sizeof(unsigned)), ib.data(), GL_STATIC_DRAW);
  const int sizes[4] = {3, 3, 2, 4}, offsets[4] = {0, 3, 6, 8};
  for (int a = 0; a < 4; ++a) {
    glEnableVertexAttribArray(GLuint(a));
    glVertexAttribPointer(GLuint(a), sizes[a], GL_FLOAT, GL_FALSE, kStride * sizeof(float),
                          reinterpret_cast<void*>(size_t(offsets[a]) * sizeof(float)));
  }
  glBindVertexArray(0);
  I.index_count = GLsizei(ib.size());
}

void GlRenderer::set_texture(const ImageRGBA8& tex) {
  Impl& I = *impl_;
  glBindTexture(GL_TEXTURE_2D, I.tex);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glPixelStorei(GL_UNPACK_ROW_LENGTH, 0);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, tex.width, tex.height, 0, GL_RGBA, GL_UNSIGNED_BYTE, tex.data.data());
  I.tex_w = tex.width;
  I.tex_h = tex.height;
}

void GlRenderer::set_material_maps(const ImageRGBA8& metallic_roughness, const ImageRGBA8& normal) {
  upload(impl_->mr, metallic_roughness, kPlainMr);
  upload(impl_->normal, normal, kFlatNormal);
}

void GlRenderer::update_texture(const ImageRGBA8& tex, const std::array<int, 4>& r) {
  Impl& I = *impl_;
  if (tex.width != I.tex_w || tex.height != I.tex_h) return set_texture(tex);
  if (r[2] < r[0] || r[3] < r[1]) return;
  glBindTexture(GL_TEXTURE_2D, I.tex);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glPixelStorei(GL_UNPACK_ROW_LENGTH, tex.width);
  glTexSubImage2D(GL_TEXTURE_2D, 0, r[0], r[1], r[2] - r[0] + 1, r[3] - r[1] + 1, GL_RGBA, GL_UNSIGNED_BYTE,
                  tex.texel(r[0], r[1]));
  glPixelStorei(GL_UNPACK_ROW_LENGTH, 0);
}

void GlRenderer::draw(const FrameView& view) {
  Impl& I = *impl_;
  glViewport(0, 0, view.camera.width, view.camera.height);
  glClearColor(float(view.background.x()), float(view.background.y()), float(view.background.z()), 1.f);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  if (!view.has_mesh || I.index_count == 0) return;
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LEQUAL);
  glDisable(GL_CULL_FACE);
  glDisable(GL_BLEND);
  glUseProgram(I.program);
  const Eigen::Matrix4f v = view.camera.view_matrix(), p = view.camera.projection_matrix();
  glUniformMatrix4fv(glGetUniformLocation(I.program, "u_view"), 1, GL_FALSE, v.data());
  glUniformMatrix4fv(glGetUniformLocation(I.program, "u_proj"), 1, GL_FALSE, p.data());
  glUniform1i(glGetUniformLocation(I.program, "u_tex"), 0);
  glUniform1i(glGetUniformLocation(I.program, "u_mr"), 1);
  glUniform1i(glGetUniformLocation(I.program, "u_normal"), 2);
  const Eigen::Vector3f up = v.topLeftCorner<3, 3>() * Eigen::Vector3f::UnitY();
  glUniform3f(glGetUniformLocation(I.program, "u_up"), up.x(), up.y(), up.z());
  const GLint mode = glGetUniformLocation(I.program, "u_mode"), colour = glGetUniformLocation(I.program, "u_color");
  const GLuint units[3] = {I.tex, I.mr, I.normal};
  for (int k = 2; k >= 0; --k) {
    glActiveTexture(GLenum(GL_TEXTURE0 + k));
    glBindTexture(GL_TEXTURE_2D, units[k]);
  }
  glUniform1i(mode, view.pbr ? 2 : 0);
  glUniform1f(glGetUniformLocation(I.program, "u_checker"),
              view.checker && I.tex_w > 0 ? float(I.tex_w) / float(kCheckerTexels) : 0.f);
  glBindVertexArray(I.vao);
  glEnable(GL_POLYGON_OFFSET_FILL);
  glPolygonOffset(1.f, 1.f);
  glDrawElements(GL_TRIANGLES, I.index_count, GL_UNSIGNED_INT, nullptr);
  glDisable(GL_POLYGON_OFFSET_FILL);
  if (view.wireframe) {
    glUniform1i(mode, 1);
    glUniform4f(colour, 0.05f, 0.05f, 0.08f, 1.f);
    glPolygonMode(GL_FRONT_AND_BACK, GL_LINE);
    glDrawElements(GL_TRIANGLES, I.index_count, GL_UNSIGNED_INT, nullptr);
    glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
  }
  glBindVertexArray(0);
  glUseProgram(0);
  glDisable(GL_DEPTH_TEST);
}

ImageRGBA8 GlRenderer::read_pixels(int width, int height) {
  ImageRGBA8 img(width, height);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadBuffer(GL_BACK);
  glReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, img.data.data());
  for (size_t k = 3; k < img.data.size(); k += 4) img.data[k] = 255;
  return img;
}

void* GlRenderer::ui_image(int slot, const ImageRGBA8& img) {
  Impl& I = *impl_;
  auto it = I.ui_textures.find(slot);
  if (it == I.ui_textures.end()) {
    GLuint t = 0;
    glGenTextures(1, &t);
    glBindTexture(GL_TEXTURE_2D, t);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    it = I.ui_textures.emplace(slot, std::make_pair(t, std::make_pair(0, 0))).first;
  }
  if (img.empty()) return reinterpret_cast<void*>(static_cast<intptr_t>(it->second.first));
  glBindTexture(GL_TEXTURE_2D, it->second.first);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, img.width, img.height, 0, GL_RGBA, GL_UNSIGNED_BYTE, img.data.data());
  it->second.second = {img.width, img.height};
  return reinterpret_cast<void*>(static_cast<intptr_t>(it->second.first));
}

}  // namespace adaptex::studio
