#pragma once
/// \file bench_disks.h
/// Disks for the parameterization benchmarks: generated curved disks of ~10k, 100k, 1M faces and the
/// open shared meshes with one boundary loop.
#include <filesystem>
#include <map>
#include <string>

#include "adaptex/core/mesh.h"
#include "adaptex/io/mesh_io.h"
#include "disk_fixtures.h"  // tests/param: bump(), hemisphere(), ...

namespace adaptex::bench {

/// Generated disk "bump<N>": the unit plane with a Gaussian bump, 2 n² faces.
/// Shared disk: "face" / "camelhead" from ../shared/meshes (empty mesh when absent).
inline const TriMesh& disk(const std::string& name) {
  static std::map<std::string, TriMesh> cache;
  auto it = cache.find(name);
  if (it != cache.end()) return it->second;
  TriMesh m;
  if (name == "bump10k") m = test::bump(71);
  else if (name == "bump100k") m = test::bump(224);
  else if (name == "bump1M") m = test::bump(707);
  else {
    const std::filesystem::path dir = std::filesystem::path(ADAPTEX_SHARED_DIR) / "meshes";
    const std::filesystem::path file = dir / (name == "face" ? "face.obj" : name + ".off");
    if (std::filesystem::exists(file)) m = read_mesh(file);
  }
  return cache.emplace(name, std::move(m)).first->second;
}

}  // namespace adaptex::bench
