// Built-in analytic HDR indoor scenes: a room of axis-aligned walls with furniture made of
// boxes, spheres and vertical cylinders, procedural albedo textures, a very bright window,
// point lights with inverse-square falloff, cosine term and hard shadows, and a little
// ambient light. Everything is known exactly: radiance and distance to the surface at any
// 3-D point, for rendering and for evaluation.
//
// World frame: metres, z up, floor at z = 0.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "common/vec.h"

namespace hdrf::sim {

enum class Pattern : std::uint8_t {
  kUniform,   // colour a
  kChecker,   // 3-D checker of cell `scale` metres, colours a and b
  kStripes,   // stripes along x+y of period `scale`, colours a and b
  kNoise,     // smooth value noise (3 octaves) between a and b, feature size `scale`
  kDetails,   // colour a with small high-contrast dots of colour b (spacing `scale`)
};

struct Material {
  Pattern pattern = Pattern::kUniform;
  Float3 a{0.5f, 0.5f, 0.5f};  // albedo in [0, 1] per channel
  Float3 b{0.5f, 0.5f, 0.5f};
  float scale = 0.25f;
  Float3 emission{0, 0, 0};    // emitted radiance (the window); 0 for ordinary surfaces
};

enum class Shape : std::uint8_t { kBox, kSphere, kCylinder };

struct Primitive {
  Shape shape = Shape::kBox;
  Float3 lo{}, hi{};       // box: corners; cylinder: (cx, cy, z0) and (radius, -, z1)
  Float3 centre{};         // sphere centre
  float radius = 0;        // sphere radius
  int material = 0;
};

struct PointLight {
  Float3 position{};
  Float3 intensity{};  // radiant intensity per channel (irradiance = I cos / d^2)
};

struct Hit {
  float t = 0;
  Float3 point{}, normal{};
  int material = -1;
  int primitive = -1;  // -1 for the room's walls/floor/ceiling
};

class Scene {
 public:
  // Names: "room", "desk", "hall". Throws hdrf::SettingError for an unknown name. The seed varies
  // texture colours, furniture placement and light strengths within plausible bounds.
  static Scene Build(const std::string& name, std::uint32_t seed);
  static std::vector<std::string> Names();

  const std::string& name() const { return name_; }
  // True for scenes too large to be seen from near their centre (the hall): the synthetic
  // sensor walks round them (CameraPath::Walk) instead of looking about (Handheld).
  bool walked_round() const { return walked_round_; }
  // The names, for messages: "room, desk, hall".
  static std::string NamesText();
  Float3 room_lo() const { return room_lo_; }
  Float3 room_hi() const { return room_hi_; }

  // Nearest surface along o + t d (d unit), t > t_min. Always hits (the room is closed).
  Hit Intersect(Float3 o, Float3 d, float t_min = 1e-4f) const;

  // Outgoing radiance of a surface point (Lambertian: albedo * irradiance / pi, or the
  // emission of the window).
  Float3 Shade(const Hit& hit) const;

  // Unsigned distance from p to the nearest surface (room walls and furniture).
  float DistanceToSurface(Float3 p) const;

  // Radiance of the surface nearest to p (for evaluating fused models).
  Float3 RadianceAt(Float3 p) const;

  bool IsEmissive(int material) const { return MaxComponent(materials_[material].emission) > 0; }

  // Albedo at a surface point of material m.
  Float3 Albedo(int material, Float3 p) const;

  // Points of interest for camera paths: bright and dark places to look at.
  const std::vector<Float3>& bright_targets() const { return bright_targets_; }
  const std::vector<Float3>& dark_targets() const { return dark_targets_; }

 private:
  bool Occluded(Float3 p, Float3 light) const;

  std::string name_;
  std::uint32_t seed_ = 0;
  Float3 room_lo_{}, room_hi_{};
  bool walked_round_ = false;
  int wall_material_[6] = {0, 0, 0, 0, 0, 0};  // -x, +x, -y, +y, floor, ceiling
  std::vector<Material> materials_;
  std::vector<Primitive> primitives_;
  // Acceleration: boxes apart (a branch-free slab test with a per-ray inverse direction),
  // and the curved shapes apart.
  struct BoxRef {
    Float3 lo, hi;
    int index;
  };
  std::vector<BoxRef> boxes_;
  std::vector<int> curved_;
  void Index();
  std::vector<PointLight> lights_;
  Float3 ambient_{};  // irradiance everywhere (indirect light stand-in)
  std::vector<Float3> bright_targets_, dark_targets_;
};

}  // namespace hdrf::sim
