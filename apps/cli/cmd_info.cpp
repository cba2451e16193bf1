// `adaptex info IN [--repair] [--json]`: reads and validates a mesh (io/mesh_io.h) and prints its
// counts, topology (components, genus, boundary loops, manifoldness; per component:
// topology_report.h), bounding box, area and what the reader dropped, welded or split. Bad input:
// exit 2 with one line on stderr (main.cpp).
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdio>
#include <iostream>
#include <sstream>

#include "adaptex/adapt/report_json.h"
#include "adaptex/core/errors.h"
#include "adaptex/core/mesh.h"
#include "adaptex/core/topology.h"
#include "adaptex/io/mesh_io.h"
#include "cli_common.h"
#include "topology_report.h"

namespace adaptex::cli {

namespace {

struct InfoOptions {
  std::string input;
  bool repair = false;
  bool json = false;
};

std::string fmt(double x) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.9g", x);
  return buf;
}

void run_info(const InfoOptions& opt, const Context& ctx) {
  ReadOptions ro;
  ro.repair = opt.repair;
  ReadReport report;
  const TriMesh mesh = read_mesh(opt.input, ro, &report);
  for (const auto& w : report.warnings) ctx.warn(w);
  const MeshTopology topo = analyze_topology(mesh);
  const BoundingBox box = bounding_box(mesh);
  const double area = surface_area(mesh);
  const double volume = signed_volume(mesh);
  const bool closed = topo.total_loops() == 0;
  const char* orientation = !closed ? "n/a (open)" : volume > 0 ? "ccw (outward)" : volume < 0 ? "cw (inward)" : "n/a";

  if (opt.json) {
    nlohmann::json j;
    j["file"] = opt.input;
    j["format"] = report.format;
    j["vertices"] = topo.num_vertices;
    j["faces"] = topo.num_faces;
    j["edges"] = topo.num_edges;
    j["euler_characteristic"] = topo.euler_characteristic;
    j["components"] = topo.num_components;
    j["genus"] = topo.total_genus();
    j["component_genus"] = topo.component_genus;
    j["component_boundary_loops"] = topo.component_loops;
    j["boundary_loops"] = topo.total_loops();
    std::vector<std::size_t> loop_lengths;
    for (const auto& l : topo.boundary_loops) loop_lengths.push_back(l.size());
    j["boundary_loop_lengths"] = loop_lengths;
    j["component_topology"] = component_topology_json(topo);
    j["manifold"] = topo.is_manifold();
    j["nonmanifold_edges"] = topo.nonmanifold_edges.size();
    j["nonmanifold_vertices"] = topo.nonmanifold_vertices.size();
    j["bounding_box"] = {{"min", {box.min.x(), box.min.y(), box.min.z()}},
                         {"max", {box.max.x(), box.max.y(), box.max.z()}},
                         {"diagonal", box.diagonal()}};
    j["surface_area"] = area;
    j["signed_volume"] = volume;
    j["orientation"] = orientation;
    const nlohmann::ordered_json read = read_report_json(report);
    for (const auto& [key, value] : read.items()) j[key] = nlohmann::json(value);
    j["warnings"] = report.warnings;
    std::cout << j.dump(2) << "\n";
    return;
  }
  std::ostringstream os;
  os << "file:        " << opt.input << " (" << report.format << ")\n";
  os << "vertices:    " << topo.num_vertices << "\n";
  os << "faces:       " << topo.num_faces << "\n";
  os << "edges:       " << topo.num_edges << "\n";
  os << "euler char.: " << topo.euler_characteristic << "\n";
  os << "components:  " << topo.num_components << "\n";
  os << component_topology_text(topo);
  os << "genus:       " << topo.total_genus() << " (sum over components)\n";
  os << "boundary:    " << topo.total_loops() << " loop" << (topo.total_loops() == 1 ? "" : "s");
  if (topo.total_loops() > 0) {
    os << " (lengths:";
    for (int l = 0; l < std::min(topo.total_loops(), 10); ++l) os << " " << topo.boundary_loops[l].size();
    if (topo.total_loops() > 10) os << " ...";
    os << " edges)";
  }
  os << "\n";
  os << "manifold:    " << (topo.is_manifold() ? "yes" : "no") << " (" << topo.nonmanifold_edges.size()
     << " non-manifold edges, " << topo.nonmanifold_vertices.size() << " non-manifold vertices)\n";
  os << "bbox min:    " << fmt(box.min.x()) << " " << fmt(box.min.y()) << " " << fmt(box.min.z()) << "\n";
  os << "bbox max:    " << fmt(box.max.x()) << " " << fmt(box.max.y()) << " " << fmt(box.max.z()) << "\n";
  os << "diagonal:    " << fmt(box.diagonal()) << "\n";
  os << "area:        " << fmt(area) << "\n";
  os << "orientation: " << orientation << " (signed volume " << fmt(volume) << ")\n";
  os << "dropped:     " << report.dropped_degenerate_faces << " degenerate faces, "
     << report.dropped_unreferenced_vertices << " unreferenced vertices, " << report.dropped_duplicate_faces
     << " duplicate faces\n";
  os << "welded:      " << report.welded_vertices << " vertices\n";
  os << "pinched:     " << report.split_pinched_vertices << " vertices split (one vertex per fan of faces)\n";
  os << "rewound:     " << report.flipped_faces << " faces flipped to the winding of their neighbours\n";
  if (opt.repair) os << "repaired:    " << report.split_nonmanifold_vertices << " vertices split\n";
  std::cout << os.str();
}

}  // namespace

void add_info_command(CLI::App& app, Context& ctx) {
  auto opt = std::make_shared<InfoOptions>();
  auto* sub = app.add_subcommand(
      "info", "Read and validate a mesh (OBJ, OFF, PLY, STL, glTF/GLB); print counts, topology and bounds");
  sub->add_option("IN", opt->input, "Input mesh file")->required();
  sub->add_flag("--repair", opt->repair,
                "Split non-manifold edges and drop duplicate faces instead of rejecting the mesh "
                "(pinched vertices are always split)");
  sub->add_flag("--json", opt->json, "Print the report as JSON on stdout");
  sub->callback([opt, &ctx] { run_info(*opt, ctx); });
}

}  // namespace adaptex::cli
