#pragma once
/// \file topology_report.h
/// Per-component topology in the `info` and `unwrap --report` outputs: faces, vertices
/// (fans), edges, Euler characteristic, genus and boundary loops of every connected component, so
/// that euler == 2 - 2 genus - boundary_loops can be checked component by component.
#include <nlohmann/json.hpp>
#include <string>

#include "adaptex/core/topology.h"

namespace adaptex::cli {

/// JSON array with one object per component: "faces", "vertices", "edges", "euler", "genus",
/// "boundary_loops" (count), "boundary_loop_lengths" (edges per loop, in loop order), "orientable"
/// and "consistently_oriented" (core/topology.h ComponentTopology).
/// \throw nothing beyond std::bad_alloc
nlohmann::json component_topology_json(const MeshTopology& topo);

/// One line per component (up to \p max_shown, then a "... more" line), each starting with
/// "  component C: genus G, N boundary loop(s)" and followed by the loop lengths, the Euler
/// characteristic and the counts.
/// \throw nothing beyond std::bad_alloc
std::string component_topology_text(const MeshTopology& topo, int max_shown = 20);

}  // namespace adaptex::cli
