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

const char* kMeshVs = R"(#version 330 core
layout(location = 0) in vec3 a_pos;
layout(location = 1) in vec3 a_normal;
layout(location = 2) in vec2 a_uv;
uniform mat4 u_view;
uniform mat4 u_proj;
out vec3 v_normal_eye;
out vec3 v_pos_eye;
out vec2 v_uv;
void main() {
  vec4 pe = u_view * vec4(a_pos, 1.0);
  v_pos_eye = pe.xyz;
  v_normal_eye = mat3(u_view) * a_normal;
  v_uv = a_uv;
  gl_Position = u_proj * pe;
})";

const char* kMeshFs = R"(#version 330 core
in vec3 v_normal_eye;
in vec3 v_pos_eye;
in vec2 v_uv;
uniform sampler2D u_tex;
uniform int u_mode;  // 0 = lit textured, 1 = flat colour
uniform vec4 u_color;
uniform float u_checker;  // > 0: checker squares per unit of uv (texture size / texels per square)
out vec4 frag;
void main() {
  if (u_mode == 1) { frag = u_color; return; }
  vec3 n = normalize(v_normal_eye);
  vec3 l = normalize(vec3(0.3, 0.5, 1.0));
  vec3 v = normalize(-v_pos_eye);
  float d = abs(dot(n, l));
  vec3 h = normalize(l + v);
  float s = pow(abs(dot(n, h)), 48.0) * 0.12;
  vec3 albedo = texture(u_tex, v_uv).rgb;
  if (u_checker > 0.0) {  // texel-density checker: every square holds the same number of texels
    vec2 c = floor(v_uv * u_checker);
    float odd = mod(c.x + c.y, 2.0);
    albedo = mix(albedo, mix(vec3(0.93), vec3(0.18, 0.2, 0.28), odd), 0.45);
  }
  frag = vec4(albedo * (0.35 + 0.65 * d) + vec3(s), 1.0);
})";

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
  GLuint program = 0, vao = 0, vbo = 0, ibo = 0, tex = 0;
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
  glGenTextures(1, &I.tex);
  glBindTexture(GL_TEXTURE_2D, I.tex);
  const unsigned char white[4] = {255, 255, 255, 255};
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, 1, 1, 0, GL_RGBA, GL_UNSIGNED_BYTE, white);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
}

GlRenderer::~GlRenderer() {
  Impl& I = *impl_;
  glDeleteProgram(I.program);
  glDeleteVertexArrays(1, &I.vao);
  glDeleteBuffers(1, &I.vbo);
  glDeleteBuffers(1, &I.ibo);
  glDeleteTextures(1, &I.tex);
  for (auto& [slot, t] : I.ui_textures) glDeleteTextures(1, &t.first);
}

void GlRenderer::set_mesh(const TriMesh& mesh, const Parameterization& param, const std::vector<Vec3>* normals) {
  Impl& I = *impl_;
  // One vertex per wedge: position, normal, uv.
  const std::vector<Vec3> own = normals ? std::vector<Vec3>() : vertex_normals(mesh);
  const std::vector<Vec3>& vn = normals ? *normals : own;
  std::vector<float> vb(size_t(param.num_wedges()) * 8);
  for (int w = 0; w < param.num_wedges(); ++w) {
    const int v = param.wedge_vertex[w];
    const Vec3 n = vn[size_t(v)].normalized();
    float* o = &vb[size_t(w) * 8];
    for (int k = 0; k < 3; ++k) o[k] = float(mesh.positions[v][k]);
    for (int k = 0; k < 3; ++k) o[3 + k] = std::isfinite(n[k]) ? float(n[k]) : 0.f;
    o[6] = float(param.uv[w].x());
    o[7] = float(param.uv[w].y());
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
  for (int a = 0; a < 3; ++a) glEnableVertexAttribArray(a);
  glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 8 * sizeof(float), reinterpret_cast<void*>(0));
  glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, 8 * sizeof(float), reinterpret_cast<void*>(3 * sizeof(float)));
  glVertexAttribPointer(2, 2, GL_FLOAT, GL_FALSE, 8 * sizeof(float), reinterpret_cast<void*>(6 * sizeof(float)));
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
  const GLint mode = glGetUniformLocation(I.program, "u_mode"), colour = glGetUniformLocation(I.program, "u_color");
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_2D, I.tex);
  glUniform1i(mode, 0);
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
