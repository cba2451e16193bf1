/// \file topology_report.cpp
/// Per-component topology for the CLI outputs (topology_report.h).
#include "topology_report.h"

#include <algorithm>
#include <sstream>

namespace adaptex::cli {

nlohmann::json component_topology_json(const MeshTopology& topo) {
  nlohmann::json arr = nlohmann::json::array();
  for (const ComponentTopology& c : topo.components) {
    std::vector<std::size_t> lengths;
    for (int l : c.loops) lengths.push_back(topo.boundary_loops[l].size());
    arr.push_back({{"faces", c.faces},
                   {"vertices", c.vertices},
                   {"edges", c.edges},
                   {"euler", c.euler},
                   {"genus", c.genus},
                   {"boundary_loops", c.loops.size()},
                   {"boundary_loop_lengths", lengths},
                   {"orientable", c.orientable},
                   {"consistently_oriented", c.consistently_oriented}});
  }
  return arr;
}

std::string component_topology_text(const MeshTopology& topo, int max_shown) {
  std::ostringstream os;
  const int shown = std::min(topo.num_components, max_shown);
  for (int i = 0; i < shown; ++i) {
    const ComponentTopology& c = topo.components[i];
    const size_t nl = c.loops.size();
    os << "  component " << i << ": genus " << c.genus << ", " << nl << " boundary loop" << (nl == 1 ? "" : "s");
    if (nl > 0) {
      os << " (lengths:";
      for (size_t k = 0; k < std::min<size_t>(nl, 10); ++k) os << " " << topo.boundary_loops[c.loops[k]].size();
      os << (nl > 10 ? " ..." : "") << " edges)";
    }
    os << ", euler char. " << c.euler << ", " << c.faces << " faces, " << c.vertices << " vertices, " << c.edges
       << " edges" << (!c.orientable ? ", NOT orientable" : !c.consistently_oriented ? ", mixed winding" : "")
       << "\n";
  }
  if (shown < topo.num_components) os << "  ... (" << topo.num_components - shown << " more components)\n";
  return os.str();
}

}  // namespace adaptex::cli
