/// \file read_mtl.cpp
/// parse_mtl(): Wavefront MTL material files, written for adaptex rather than taken from tinyobjloader,
/// whose reader opens whatever `mtllib` names and keeps no line numbers. Statements used: newmtl, Kd,
/// d, Tr, Ke, Pr, Pm and the map statements (below), with the texture options of the MTL spec
/// (-bm, -blendu, -blendv, -boost, -cc, -clamp, -imfchan, -mm, -o, -s, -t, -texres, -type) before
/// the file name. The file name is the rest of the line, so names with spaces work.
#include <algorithm>
#include <charconv>
#include <cmath>

#include "adaptex/core/errors.h"
#include "adaptex/io/asset_io.h"

namespace adaptex {

namespace {

struct MapStatement {
  const char* keyword;
  MapSlot slot;
};

// Both spellings of the bump statement are common; map_Bump often holds a normal map (Blender writes
// one there): read_textured_asset() tells them apart by the image.
constexpr MapStatement kMapStatements[] = {
    {"map_Kd", MapSlot::BaseColor}, {"map_Pr", MapSlot::Roughness}, {"map_Pm", MapSlot::Metallic},
    {"map_Ke", MapSlot::Emissive},  {"norm", MapSlot::Normal},      {"map_Bump", MapSlot::Bump},
    {"map_bump", MapSlot::Bump},    {"bump", MapSlot::Bump},
};

/// Number of numeric arguments each texture option takes (at most; -o/-s/-t take 1 to 3).
int option_arguments(std::string_view option, bool& variable) {
  variable = false;
  if (option == "-bm" || option == "-boost" || option == "-texres") return 1;
  if (option == "-blendu" || option == "-blendv" || option == "-cc" || option == "-clamp" || option == "-imfchan" ||
      option == "-type")
    return 1;
  if (option == "-mm") return 2;
  if (option == "-o" || option == "-s" || option == "-t") {
    variable = true;
    return 3;
  }
  return -1;
}

bool parse_number(std::string_view t, double& out) {
  if (!t.empty() && t.front() == '+') t.remove_prefix(1);
  const auto res = std::from_chars(t.data(), t.data() + t.size(), out);
  return !t.empty() && res.ec == std::errc() && res.ptr == t.data() + t.size() && std::isfinite(out);
}

bool is_mtl_blank(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v'; }

/// A line split into tokens, each remembered with its offset (so that the rest of the line can be taken
/// verbatim as a file name).
struct Line {
  std::string_view text;
  std::vector<std::string_view> tokens;
  explicit Line(std::string_view t) : text(t) {
    for (std::size_t p = 0; p < t.size();) {
      while (p < t.size() && is_mtl_blank(t[p])) ++p;
      if (p >= t.size() || t[p] == '#') break;
      const std::size_t start = p;
      while (p < t.size() && !is_mtl_blank(t[p])) ++p;
      tokens.push_back(t.substr(start, p - start));
    }
  }
  /// The text from token \p k to the end of the line (up to a comment), trimmed.
  std::string rest(std::size_t k) const {
    std::string_view r = text.substr(static_cast<std::size_t>(tokens[k].data() - text.data()));
    while (!r.empty() && is_mtl_blank(r.back())) r.remove_suffix(1);
    return std::string(r);
  }
};

class MtlParser {
 public:
  MtlParser(const std::filesystem::path& name, std::vector<std::string>* warnings)
      : file_(name.string()), dir_(name.parent_path()), warnings_(warnings) {}

  std::vector<Material> parse(const std::string& text) {
    int line_no = 0;
    for (std::size_t pos = 0; pos < text.size();) {
      std::size_t end = text.find('\n', pos);
      if (end == std::string::npos) end = text.size();
      ++line_no;
      statement(Line(std::string_view(text).substr(pos, end - pos)), line_no);
      pos = end + 1;
    }
    if (ignored_before_newmtl_ > 0) warn(std::to_string(ignored_before_newmtl_) + " statement(s) before the first newmtl ignored");
    return std::move(materials_);
  }

 private:
  [[noreturn]] void fail(int line, const std::string& what) const {
    throw IoError(file_ + ": line " + std::to_string(line) + ": " + what);
  }
  void warn(const std::string& what) {
    if (warnings_) warnings_->push_back(file_ + ": " + what);
  }

  /// \p count numbers after the keyword (the first \p required of them must be there).
  std::vector<double> numbers(const Line& l, int line, std::size_t required, std::size_t count) const {
    std::vector<double> out;
    std::string key(l.tokens[0]);
    for (std::size_t k = 1; k < l.tokens.size() && out.size() < count; ++k) {
      double d = 0;
      if (!parse_number(l.tokens[k], d)) {
        std::string what = key;
        what.append(" has a non-numeric or non-finite value: ").append(l.tokens[k]);
        fail(line, what);
      }
      out.push_back(d);
    }
    if (out.size() < required) fail(line, key.append(" needs ").append(std::to_string(required)).append(" number(s)"));
    return out;
  }

  void statement(const Line& l, int line) {
    if (l.tokens.empty()) return;
    const std::string_view key = l.tokens[0];
    if (key == "newmtl") {
      if (l.tokens.size() < 2) fail(line, "'newmtl' without a name");
      Material m;
      m.name = l.rest(1);
      const auto same = [&](const Material& o) { return o.name == m.name; };
      if (std::any_of(materials_.begin(), materials_.end(), same)) {
        warn("line " + std::to_string(line) + ": material '" + m.name + "' is defined again; the first definition is used");
        current_ = -1;
        return;
      }
      materials_.push_back(std::move(m));
      current_ = static_cast<int>(materials_.size()) - 1;
      return;
    }
    const bool known = key == "Kd" || key == "d" || key == "Tr" || key == "Ke" || key == "Pr" || key == "Pm" ||
                       std::any_of(std::begin(kMapStatements), std::end(kMapStatements),
                                   [&](const MapStatement& s) { return key == s.keyword; });
    if (!known) return;  // Ka, Ks, Ns, illum, map_Ks, map_d, ...: not used by adaptex
    if (current_ < 0) {
      if (materials_.empty()) ++ignored_before_newmtl_;
      return;
    }
    Material& m = materials_[static_cast<std::size_t>(current_)];
    if (key == "Kd" || key == "Ke") {
      const auto v = numbers(l, line, 1, 3);
      for (int c = 0; c < 3; ++c) (key == "Kd" ? m.base_color[c] : m.emissive[c]) = v[std::min<std::size_t>(c, v.size() - 1)];
    } else if (key == "d") {
      m.base_color[3] = numbers(l, line, 1, 1)[0];
    } else if (key == "Tr") {
      m.base_color[3] = 1.0 - numbers(l, line, 1, 1)[0];
    } else if (key == "Pr") {
      m.roughness = numbers(l, line, 1, 1)[0];
    } else if (key == "Pm") {
      m.metallic = numbers(l, line, 1, 1)[0];
    } else {
      map(l, line, m);
    }
  }

  void map(const Line& l, int line, Material& m) {
    const std::string keyword(l.tokens[0]);
    const auto st = std::find_if(std::begin(kMapStatements), std::end(kMapStatements),
                                 [&](const MapStatement& s) { return keyword == s.keyword; });
    TextureMap map;
    map.slot = st->slot;
    map.srgb = map.slot == MapSlot::BaseColor || map.slot == MapSlot::Emissive;
    std::size_t k = 1;
    bool transform = false;
    while (k < l.tokens.size() && l.tokens[k].size() > 1 && l.tokens[k][0] == '-') {
      const std::string option(l.tokens[k]);
      bool variable = false;
      const int n = option_arguments(option, variable);
      if (n < 0) fail(line, "'" + keyword + "': unknown texture option '" + option + "'");
      ++k;
      for (int a = 0; a < n; ++a, ++k) {
        double d = 0;
        const bool numeric = k < l.tokens.size() && parse_number(l.tokens[k], d);
        // -o/-s/-t take 1 to 3 numbers; the file name is never taken as one.
        if (variable && a > 0 && (!numeric || k + 1 >= l.tokens.size())) break;
        if (k + 1 >= l.tokens.size()) fail(line, "'" + keyword + "': option '" + option + "' leaves no file name");
        if ((variable || option == "-bm" || option == "-boost" || option == "-mm") && !numeric)
          fail(line, "'" + keyword + "': option '" + option + "' needs a number, not '" + std::string(l.tokens[k]) + "'");
        if (option == "-bm") map.scale = d;
        if ((option == "-o" && d != 0.0) || (option == "-s" && d != 1.0)) transform = true;
      }
    }
    if (transform)
      warn("line " + std::to_string(line) + ": '" + keyword +
           "': the texture transform (-o / -s) is ignored: the map is read as if it were not there");
    if (k >= l.tokens.size()) fail(line, "'" + keyword + "' without a file name");
    const std::string written = l.rest(k);
    map.origin = file_ + ": line " + std::to_string(line) + ": " + keyword + " '" + written + "'";
    map.path = dir_ / std::filesystem::path(written);
    if (m.find(map.slot)) {
      warn("line " + std::to_string(line) + ": material '" + m.name + "' has a second " + map_slot_name(map.slot) +
           " map; the first is used");
      return;
    }
    m.maps.push_back(std::move(map));
  }

  std::string file_;
  std::filesystem::path dir_;
  std::vector<std::string>* warnings_;
  std::vector<Material> materials_;
  int current_ = -1;  ///< The material the statements belong to (-1: none, or a repeated name).
  int ignored_before_newmtl_ = 0;
};

}  // namespace

const char* map_slot_name(MapSlot slot) {
  switch (slot) {
    case MapSlot::BaseColor: return "base_color";
    case MapSlot::MetallicRoughness: return "metallic_roughness";
    case MapSlot::Roughness: return "roughness";
    case MapSlot::Metallic: return "metallic";
    case MapSlot::Normal: return "normal";
    case MapSlot::Bump: return "bump";
    case MapSlot::Occlusion: return "occlusion";
    case MapSlot::Emissive: return "emissive";
  }
  return "unknown";
}

const TextureMap* Material::find(MapSlot slot) const {
  for (const TextureMap& m : maps)
    if (m.slot == slot) return &m;
  return nullptr;
}

std::vector<Material> parse_mtl(const std::string& text, const std::filesystem::path& name,
                                std::vector<std::string>* warnings) {
  return MtlParser(name, warnings).parse(text);
}

}  // namespace adaptex
