// Surface extraction with HDR radiance: a triangle mesh from the TSDF zero level set.
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <vector>

#include "common/vec.h"
#include "volume/volume.h"

namespace hdrf::volume {
class DeviceVolume;
}

namespace hdrf::mesh {

struct Mesh {
  std::vector<Float3> position;  // metres, world frame of the first camera
  std::vector<Float3> normal;    // unit, pointing into free space
  std::vector<Float3> radiance;  // linear HDR radiance, model units (0 where never seen)
  std::vector<std::array<std::int32_t, 3>> triangles;
};

// Marching tetrahedra over every cube of 8 observed voxels: each cube is split into six
// tetrahedra around its main diagonal, so no ambiguous cases and no holes; vertices are
// shared along voxel edges. Progress callback (0..1) may be null.
Mesh ExtractMesh(const volume::Volume& volume, void (*progress)(double, void*) = nullptr,
                 void* user = nullptr);
// The same surface from the model on the GPU (mesh_cuda.cu; CUDA builds only).
Mesh ExtractMeshOnGpu(const volume::DeviceVolume& volume);

}  // namespace hdrf::mesh
