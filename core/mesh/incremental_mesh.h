// The surface kept up to date piece by piece: a mirror of the model's bricks, fed with the
// bricks that changed (volume::BrickSet), and one piece of mesh per brick. Only the bricks a
// change can reach are meshed again: the changed ones and their 26 neighbours (a brick's
// cubes read the voxels one step beyond it, and its vertex normals the TSDF gradient around
// them). The pieces together hold exactly the triangles of ExtractMesh over the same voxels;
// vertices on brick borders appear once per piece that uses them. For views that redraw the
// surface while a scan goes on, off the scan's thread; exports use ExtractMesh.
//
// A coarser surface for a view that must redraw cheaply while the scan goes on: with step 2
// each piece is meshed from every other voxel (cubes two voxels on a side: an eighth of the
// cubes, about a quarter of the triangles), with step 4 from every fourth (a sixteenth of
// the triangles). The pieces of each step are kept apart, and a brick changed since its piece
// of a step was meshed is meshed again when that step is next asked for (a scan previewed at
// step 2 or 4 and shown whole at step 1 when it stops).
#pragma once

#include <array>
#include <cstdint>
#include <unordered_map>
#include <unordered_set>

#include "mesh/mesh.h"
#include "volume/volume.h"

namespace hdrf::mesh {

class IncrementalMesher {
 public:
  static constexpr int kSteps = 3;  // steps 1 (every voxel), 2 and 4
  explicit IncrementalMesher(const volume::VolumeOptions& o);
  // Takes changed bricks in, and meshes at `step` every brick a change has reached since that
  // step's pieces were last brought up to date. Returns the number of bricks meshed. Bricks
  // past the mirror's memory limit are left out (full() says so). `refresh_after` > 0 (a
  // preview while scanning): a brick whose surface was meshed at this step fewer than that
  // many calls ago waits (it stays stale for a later call), so the surface a scan keeps
  // refining costs a fraction; bricks without surface at this step yet are meshed at once.
  std::size_t Apply(const volume::BrickSet& changed, int step = 1, int refresh_after = 0);
  // All pieces of a step as one mesh (in brick key order).
  Mesh Assemble(int step = 1) const;
  std::size_t bricks() const { return mirror_.allocated_bricks(); }
  std::size_t pieces(int step = 1) const { return level(step).pieces.size(); }
  std::size_t stale(int step = 1) const { return level(step).stale.size(); }
  bool full() const { return mirror_.full(); }

 private:
  struct Level {
    std::unordered_map<std::uint64_t, Mesh> pieces;  // brick key -> its cubes' surface
    std::unordered_set<std::uint64_t> stale;         // bricks a change reached since meshed
    std::unordered_map<std::uint64_t, std::uint32_t> meshed_at;  // brick key -> call it was meshed in
    std::uint32_t calls = 0;                                      // Apply calls at this step
  };
  const Level& level(int step) const;
  Level& level(int step);
  volume::Volume mirror_;
  std::array<Level, kSteps> levels_;
};

}  // namespace hdrf::mesh
