// HDR texture baking from the fused frames, and renders of the textured mesh.
//
// Every texel of the atlas is a point on the surface. Its radiance is the weighted mean of
// the frames' pixels around it (those nearest it weigh most): each frame's radiance already
// in the model's exposure, weighted by the pixel's confidence, the viewing angle (cos^2)
// and the distance (1 / z^2), and only where the point is the nearest surface along the pixel's ray -- checked against a
// depth buffer of the mesh itself, away from its depth edges. Texels no frame saw take the
// volume's radiance (the mesh's vertex radiance, interpolated) and are counted apart.
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include "common/camera.h"
#include "common/image.h"
#include "common/se3.h"
#include "mesh/uv_atlas.h"

namespace hdrf::mesh {

struct BakeView {
  Pose T_world_camera = Pose::Identity();  // in the mesh's frame
  PinholeCamera camera;
  RadianceImage radiance;   // in the model's units (exposure compensated)
  Image<float> confidence;  // 0..1 per pixel; 0 = not to be used (saturated, black)
};

struct BakeOptions {
  float min_cos = 0.25f;            // views more grazing than ~75 degrees are not used
  float occlusion_tolerance = 0.015f;  // metres (plus 1 % of the depth) behind the depth buffer
  int edge_margin_px = 2;           // pixels this close to a depth edge or the border are not used
  // Each frame's four pixels around a texel are weighted by a Gaussian of their distance
  // (this sigma, pixels) across all frames at once, so that the frames' samples nearest a
  // texel decide it; 0 = each frame interpolated bilinearly, then averaged (softer).
  float sample_sigma_px = 0.35f;
  void Check() const;               // throws SettingError naming the option
};

enum class TexelSource : std::uint8_t { kEmpty = 0, kFrames = 1, kVolume = 2, kPadding = 3 };

struct BakedTexture {
  RadianceImage radiance;          // the atlas, model units; padding filled from its own chart
  Image<std::uint8_t> source;      // TexelSource per texel
  Image<std::int32_t> triangle;    // the atlas triangle of a surface texel (-1 elsewhere)
  long surface_texels = 0, from_frames = 0, from_volume = 0;
  double mean_views = 0;           // frames averaged per texel seen by frames
};

// `progress(fraction)` returning false cancels (throws hdrf::Cancelled).
BakedTexture BakeTexture(const Atlas& atlas, const std::vector<BakeView>& views, const BakeOptions& o = {},
                         const std::function<bool(double)>& progress = {});

// The per-vertex alternative on the same atlas: every surface texel the volume's radiance
// interpolated over its triangle (what a viewer shows of per-vertex colour).
RadianceImage VertexRadianceTexture(const Atlas& atlas, const BakedTexture& layout);

// Depth buffer of a mesh seen from a camera (metres along z; 0 where nothing is seen).
DepthImage RenderDepth(const Mesh& m, const Pose& T_world_camera, const PinholeCamera& cam);

// A render of the textured mesh at any camera: linear radiance (bilinear texture lookups),
// alpha (1 on the mesh, 0 elsewhere) and depth (metres along z, 0 where empty).
struct TexturedRender {
  RadianceImage radiance;
  Image<float> alpha;
  DepthImage depth;
};
TexturedRender RenderTextured(const Atlas& atlas, const RadianceImage& texture, const Pose& T_world_camera,
                              const PinholeCamera& cam);

// Bilinear lookup at atlas texel coordinates (centres at integers), clamped to the edges.
Float3 SampleBilinear(const RadianceImage& img, float x, float y);

}  // namespace hdrf::mesh
