// The surface kept up to date piece by piece: a mirror of the model's bricks, fed with the
// bricks that changed (volume::BrickSet), and one piece of mesh per brick. Only the bricks a
// change can reach are meshed again: the changed ones and their 26 neighbours (a brick's
// cubes read the voxels one step beyond it, and its vertex normals the TSDF gradient around
// them). The pieces together hold exactly the triangles of ExtractMesh over the same voxels;
// vertices on brick borders appear once per piece that uses them. For views that redraw the
// surface while a scan goes on, off the scan's thread; exports use ExtractMesh.
#pragma once

#include <cstdint>
#include <unordered_map>

#include "mesh/mesh.h"
#include "volume/volume.h"

namespace hdrf::mesh {

class IncrementalMesher {
 public:
  explicit IncrementalMesher(const volume::VolumeOptions& o);
  // Takes changed bricks in and meshes again every brick they can reach. Returns the number
  // of bricks meshed. Bricks past the mirror's memory limit are left out (full() says so).
  std::size_t Apply(const volume::BrickSet& changed);
  // All pieces as one mesh (in brick key order).
  Mesh Assemble() const;
  std::size_t bricks() const { return mirror_.allocated_bricks(); }
  std::size_t pieces() const { return pieces_.size(); }
  bool full() const { return mirror_.full(); }

 private:
  volume::Volume mirror_;
  std::unordered_map<std::uint64_t, Mesh> pieces_;  // brick key -> its cubes' surface
};

}  // namespace hdrf::mesh
