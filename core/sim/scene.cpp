#include "sim/scene.h"

#include <algorithm>
#include <cmath>
#include <random>

#include "common/error.h"
#include "sim/noise.h"

namespace hdrf::sim {

namespace {

constexpr float kPi = 3.14159265358979f;

Primitive Box(Float3 lo, Float3 hi, int m) {
  Primitive p;
  p.shape = Shape::kBox;
  p.lo = lo;
  p.hi = hi;
  p.material = m;
  return p;
}
Primitive Sphere(Float3 c, float r, int m) {
  Primitive p;
  p.shape = Shape::kSphere;
  p.centre = c;
  p.radius = r;
  p.material = m;
  return p;
}
// Vertical cylinder: axis at (cx, cy), radius r, from z0 to z1.
Primitive Cylinder(float cx, float cy, float r, float z0, float z1, int m) {
  Primitive p;
  p.shape = Shape::kCylinder;
  p.lo = {cx, cy, z0};
  p.hi = {r, 0, z1};
  p.material = m;
  return p;
}

bool IntersectBox(const Primitive& b, Float3 o, Float3 d, float t_min, float t_max, float* t_out,
                  Float3* n_out) {
  float t0 = t_min, t1 = t_max;
  int axis = -1;
  float sign = 0;
  const float ov[3] = {o.x, o.y, o.z}, dv[3] = {d.x, d.y, d.z};
  const float lo[3] = {b.lo.x, b.lo.y, b.lo.z}, hi[3] = {b.hi.x, b.hi.y, b.hi.z};
  for (int a = 0; a < 3; ++a) {
    if (std::abs(dv[a]) < 1e-12f) {
      if (ov[a] < lo[a] || ov[a] > hi[a]) return false;
      continue;
    }
    const float inv = 1.0f / dv[a];
    float tn = (lo[a] - ov[a]) * inv, tf = (hi[a] - ov[a]) * inv;
    float s = -1;
    if (tn > tf) {
      std::swap(tn, tf);
      s = 1;
    }
    if (tn > t0) {
      t0 = tn;
      axis = a;
      sign = s;
    }
    t1 = std::min(t1, tf);
    if (t0 > t1) return false;
  }
  if (axis < 0) return false;  // origin inside the box: not a visible hit from outside
  *t_out = t0;
  *n_out = {axis == 0 ? sign : 0.f, axis == 1 ? sign : 0.f, axis == 2 ? sign : 0.f};
  return true;
}

bool IntersectSphere(const Primitive& s, Float3 o, Float3 d, float t_min, float t_max,
                     float* t_out, Float3* n_out) {
  const Float3 oc = o - s.centre;
  const float b = Dot(oc, d);
  const float c = Dot(oc, oc) - s.radius * s.radius;
  const float disc = b * b - c;
  if (disc < 0) return false;
  const float sq = std::sqrt(disc);
  float t = -b - sq;
  if (t < t_min) t = -b + sq;
  if (t < t_min || t > t_max) return false;
  *t_out = t;
  *n_out = (o + d * t - s.centre) / s.radius;
  return true;
}

bool IntersectCylinder(const Primitive& c, Float3 o, Float3 d, float t_min, float t_max,
                       float* t_out, Float3* n_out) {
  const float cx = c.lo.x, cy = c.lo.y, z0 = c.lo.z, r = c.hi.x, z1 = c.hi.z;
  bool hit = false;
  float best = t_max;
  const float ox = o.x - cx, oy = o.y - cy;
  const float a = d.x * d.x + d.y * d.y;
  if (a > 1e-12f) {
    const float b = ox * d.x + oy * d.y;
    const float cc = ox * ox + oy * oy - r * r;
    const float disc = b * b - a * cc;
    if (disc >= 0) {
      const float sq = std::sqrt(disc);
      for (float t : {(-b - sq) / a, (-b + sq) / a}) {
        if (t < t_min || t >= best) continue;
        const float z = o.z + t * d.z;
        if (z < z0 || z > z1) continue;
        best = t;
        hit = true;
        *n_out = {(ox + t * d.x) / r, (oy + t * d.y) / r, 0};
        break;
      }
    }
  }
  if (std::abs(d.z) > 1e-12f) {
    for (float zc : {z0, z1}) {
      const float t = (zc - o.z) / d.z;
      if (t < t_min || t >= best) continue;
      const float x = ox + t * d.x, y = oy + t * d.y;
      if (x * x + y * y > r * r) continue;
      best = t;
      hit = true;
      *n_out = {0, 0, zc == z1 ? 1.f : -1.f};
    }
  }
  if (hit) *t_out = best;
  return hit;
}

// Entry distance of a ray (origin o, inverse direction inv) into a box, if the ray enters it
// within (t_min, t_max). Branch-free slab test.
inline bool SlabEnter(Float3 lo, Float3 hi, Float3 o, Float3 inv, float t_min, float t_max,
                      float* t) {
  const float x1 = (lo.x - o.x) * inv.x, x2 = (hi.x - o.x) * inv.x;
  const float y1 = (lo.y - o.y) * inv.y, y2 = (hi.y - o.y) * inv.y;
  const float z1 = (lo.z - o.z) * inv.z, z2 = (hi.z - o.z) * inv.z;
  const float tn = std::max(std::max(std::min(x1, x2), std::min(y1, y2)), std::min(z1, z2));
  const float tf = std::min(std::min(std::max(x1, x2), std::max(y1, y2)), std::max(z1, z2));
  *t = tn;
  return tn <= tf && tn > t_min && tn < t_max;
}

// Outward normal of the box face a point on its surface lies on.
Float3 BoxNormal(Float3 lo, Float3 hi, Float3 p) {
  const float d[6] = {std::abs(p.x - lo.x), std::abs(p.x - hi.x), std::abs(p.y - lo.y),
                      std::abs(p.y - hi.y), std::abs(p.z - lo.z), std::abs(p.z - hi.z)};
  const int k = int(std::min_element(d, d + 6) - d);
  static const Float3 kN[6] = {{-1, 0, 0}, {1, 0, 0}, {0, -1, 0}, {0, 1, 0}, {0, 0, -1}, {0, 0, 1}};
  return kN[k];
}

inline Float3 Inverse(Float3 d) {
  auto inv = [](float v) { return std::abs(v) > 1e-20f ? 1.0f / v : std::copysign(1e20f, v); };
  return {inv(d.x), inv(d.y), inv(d.z)};
}

bool IntersectPrimitive(const Primitive& p, Float3 o, Float3 d, float t_min, float t_max,
                        float* t, Float3* n) {
  switch (p.shape) {
    case Shape::kBox: return IntersectBox(p, o, d, t_min, t_max, t, n);
    case Shape::kSphere: return IntersectSphere(p, o, d, t_min, t_max, t, n);
    case Shape::kCylinder: return IntersectCylinder(p, o, d, t_min, t_max, t, n);
  }
  return false;
}

// Signed distance to a primitive and the outward normal of its nearest surface.
float PrimitiveDistance(const Primitive& p, Float3 q, Float3* n) {
  switch (p.shape) {
    case Shape::kSphere: {
      const Float3 v = q - p.centre;
      const float len = Length(v);
      *n = len > 0 ? v / len : Float3{0, 0, 1};
      return len - p.radius;
    }
    case Shape::kCylinder: {
      const float dx = q.x - p.lo.x, dy = q.y - p.lo.y;
      const float rho = std::sqrt(dx * dx + dy * dy);
      const float side = rho - p.hi.x;
      const float zmid = 0.5f * (p.lo.z + p.hi.z), zh = 0.5f * (p.hi.z - p.lo.z);
      const float cap = std::abs(q.z - zmid) - zh;
      if (side > 0 && cap > 0) {
        *n = Normalized(Float3{rho > 0 ? dx / rho * side : 0, rho > 0 ? dy / rho * side : 0,
                               (q.z > zmid ? 1.f : -1.f) * cap});
        return std::sqrt(side * side + cap * cap);
      }
      if (side > cap) {
        *n = rho > 0 ? Float3{dx / rho, dy / rho, 0} : Float3{1, 0, 0};
        return side;
      }
      *n = {0, 0, q.z > zmid ? 1.f : -1.f};
      return cap;
    }
    case Shape::kBox: {
      const Float3 c = (p.lo + p.hi) * 0.5f, h = (p.hi - p.lo) * 0.5f;
      const float e[3] = {std::abs(q.x - c.x) - h.x, std::abs(q.y - c.y) - h.y,
                          std::abs(q.z - c.z) - h.z};
      const float s[3] = {q.x > c.x ? 1.f : -1.f, q.y > c.y ? 1.f : -1.f, q.z > c.z ? 1.f : -1.f};
      const float ex = std::max(e[0], 0.f), ey = std::max(e[1], 0.f), ez = std::max(e[2], 0.f);
      const float outside = std::sqrt(ex * ex + ey * ey + ez * ez);
      if (outside > 0) {
        *n = Normalized(Float3{ex * s[0], ey * s[1], ez * s[2]});
        return outside;
      }
      const int a = e[0] > e[1] ? (e[0] > e[2] ? 0 : 2) : (e[1] > e[2] ? 1 : 2);
      *n = {a == 0 ? s[0] : 0.f, a == 1 ? s[1] : 0.f, a == 2 ? s[2] : 0.f};
      return e[a];
    }
  }
  return 1e9f;
}

// Seeded jitter of a colour (each channel x [1-j, 1+j], clamped to a valid albedo).
Float3 Jitter(std::mt19937& rng, Float3 c, float j) {
  std::uniform_real_distribution<float> u(1 - j, 1 + j);
  return {std::clamp(c.x * u(rng), 0.02f, 0.95f), std::clamp(c.y * u(rng), 0.02f, 0.95f),
          std::clamp(c.z * u(rng), 0.02f, 0.95f)};
}

}  // namespace

std::vector<std::string> Scene::Names() { return {"room", "desk", "hall"}; }

std::string Scene::NamesText() {
  std::string text;
  for (const std::string& n : Names()) text += (text.empty() ? "" : ", ") + n;
  return text;
}

Scene Scene::Build(const std::string& name, std::uint32_t seed) {
  Scene s;
  s.name_ = name;
  s.seed_ = seed;
  std::mt19937 rng(seed * 2654435761u + 17u);
  std::uniform_real_distribution<float> u(-1.f, 1.f);
  auto mat = [&](Pattern p, Float3 a, Float3 b, float scale) {
    s.materials_.push_back({p, Jitter(rng, a, 0.15f), Jitter(rng, b, 0.15f), scale, {0, 0, 0}});
    return int(s.materials_.size()) - 1;
  };
  auto emissive = [&](Float3 e) {
    Material m;
    m.emission = e;
    s.materials_.push_back(m);
    return int(s.materials_.size()) - 1;
  };
  auto light = [&](Float3 p, Float3 i) {
    const float k = 1.f + 0.2f * u(rng);
    s.lights_.push_back({p, i * k});
  };

  if (name == "room") {
    s.room_lo_ = {0, 0, 0};
    s.room_hi_ = {5, 4, 2.7f};
    s.wall_material_[0] = mat(Pattern::kNoise, {0.75f, 0.70f, 0.60f}, {0.55f, 0.50f, 0.42f}, 0.4f);
    s.wall_material_[1] = mat(Pattern::kStripes, {0.80f, 0.78f, 0.72f}, {0.45f, 0.55f, 0.65f}, 0.3f);
    s.wall_material_[2] = mat(Pattern::kChecker, {0.70f, 0.72f, 0.75f}, {0.35f, 0.38f, 0.45f}, 0.5f);
    s.wall_material_[3] = mat(Pattern::kDetails, {0.72f, 0.74f, 0.70f}, {0.05f, 0.05f, 0.08f}, 0.2f);
    s.wall_material_[4] = mat(Pattern::kChecker, {0.55f, 0.38f, 0.22f}, {0.35f, 0.22f, 0.12f}, 0.3f);
    s.wall_material_[5] = mat(Pattern::kUniform, {0.85f, 0.85f, 0.85f}, {0.85f, 0.85f, 0.85f}, 1.f);
    const int window = emissive({250.f, 260.f, 285.f});
    const int table = mat(Pattern::kNoise, {0.60f, 0.42f, 0.25f}, {0.40f, 0.26f, 0.14f}, 0.08f);
    const int dark = mat(Pattern::kUniform, {0.12f, 0.12f, 0.13f}, {0.1f, 0.1f, 0.1f}, 1.f);
    const int sofa = mat(Pattern::kNoise, {0.65f, 0.15f, 0.12f}, {0.40f, 0.08f, 0.08f}, 0.12f);
    const int cabinet = mat(Pattern::kStripes, {0.85f, 0.85f, 0.80f}, {0.20f, 0.35f, 0.25f}, 0.12f);
    const int ball = mat(Pattern::kDetails, {0.90f, 0.85f, 0.20f}, {0.05f, 0.10f, 0.60f}, 0.06f);
    const int ball2 = mat(Pattern::kChecker, {0.20f, 0.60f, 0.30f}, {0.90f, 0.90f, 0.90f}, 0.1f);
    const int metal = mat(Pattern::kUniform, {0.55f, 0.55f, 0.58f}, {0.5f, 0.5f, 0.5f}, 1.f);
    const int books = mat(Pattern::kStripes, {0.20f, 0.30f, 0.70f}, {0.85f, 0.80f, 0.30f}, 0.05f);
    // A very bright window in the +x wall (a thin emissive slab on the wall).
    s.primitives_.push_back(Box({4.99f, 1.2f, 0.9f}, {5.1f, 2.8f, 2.2f}, window));
    // Table with legs: dark underneath.
    s.primitives_.push_back(Box({1.6f, 1.2f, 0.72f}, {2.8f, 2.0f, 0.77f}, table));
    for (float x : {1.65f, 2.70f})
      for (float y : {1.25f, 1.90f})
        s.primitives_.push_back(Box({x, y, 0.f}, {x + 0.05f, y + 0.05f, 0.72f}, dark));
    s.primitives_.push_back(Box({1.9f, 1.4f, 0.f}, {2.3f, 1.8f, 0.25f}, dark));  // box under it
    // Sofa (base and back) against the +y wall.
    s.primitives_.push_back(Box({0.3f, 2.9f, 0.f}, {2.3f, 3.9f, 0.45f}, sofa));
    s.primitives_.push_back(Box({0.3f, 3.6f, 0.45f}, {2.3f, 3.9f, 0.95f}, sofa));
    // Cabinet with books on top.
    s.primitives_.push_back(Box({3.9f, 0.15f, 0.f}, {4.8f, 0.75f, 1.1f}, cabinet));
    s.primitives_.push_back(Box({4.0f, 0.25f, 1.1f}, {4.5f, 0.5f, 1.35f}, books));
    // Spheres and cylinders.
    s.primitives_.push_back(Sphere({2.2f + 0.1f * u(rng), 1.6f, 0.97f}, 0.2f, ball));
    s.primitives_.push_back(Sphere({3.4f, 2.8f + 0.1f * u(rng), 0.3f}, 0.3f, ball2));
    s.primitives_.push_back(Cylinder(4.3f, 3.3f, 0.2f, 0.f, 0.6f, metal));
    s.primitives_.push_back(Cylinder(0.5f, 0.5f, 0.03f, 0.f, 1.6f, metal));  // lamp pole
    // Light: the window (two point lights just inside it), a warm floor lamp, ambient.
    light({4.6f, 1.6f, 1.7f}, {3.0f, 3.1f, 3.4f});
    light({4.6f, 2.4f, 1.4f}, {3.0f, 3.1f, 3.4f});
    light({0.5f, 0.5f, 1.75f}, {1.2f, 0.95f, 0.65f});
    s.ambient_ = {0.03f, 0.03f, 0.032f};
    s.bright_targets_ = {{5.f, 2.0f, 1.5f}, {4.3f, 0.5f, 1.2f}, {0.5f, 0.6f, 1.4f}};
    s.dark_targets_ = {{2.1f, 1.6f, 0.2f}, {0.4f, 3.5f, 0.3f}, {2.5f, 0.1f, 0.4f}};
  } else if (name == "desk") {
    s.room_lo_ = {0, 0, 0};
    s.room_hi_ = {4, 3.5f, 2.6f};
    s.wall_material_[0] = mat(Pattern::kStripes, {0.78f, 0.76f, 0.70f}, {0.60f, 0.62f, 0.55f}, 0.25f);
    s.wall_material_[1] = mat(Pattern::kNoise, {0.70f, 0.72f, 0.78f}, {0.50f, 0.52f, 0.60f}, 0.5f);
    s.wall_material_[2] = mat(Pattern::kDetails, {0.75f, 0.72f, 0.68f}, {0.10f, 0.10f, 0.12f}, 0.15f);
    s.wall_material_[3] = mat(Pattern::kChecker, {0.68f, 0.70f, 0.66f}, {0.50f, 0.48f, 0.45f}, 0.6f);
    s.wall_material_[4] = mat(Pattern::kNoise, {0.45f, 0.45f, 0.48f}, {0.25f, 0.25f, 0.28f}, 0.2f);
    s.wall_material_[5] = mat(Pattern::kUniform, {0.85f, 0.85f, 0.85f}, {0.85f, 0.85f, 0.85f}, 1.f);
    const int window = emissive({300.f, 310.f, 330.f});
    const int screen = emissive({1.2f, 1.4f, 1.8f});
    const int desk = mat(Pattern::kNoise, {0.70f, 0.55f, 0.35f}, {0.50f, 0.36f, 0.20f}, 0.05f);
    const int panel = mat(Pattern::kUniform, {0.30f, 0.22f, 0.15f}, {0.3f, 0.2f, 0.1f}, 1.f);
    const int black = mat(Pattern::kUniform, {0.06f, 0.06f, 0.07f}, {0.1f, 0.1f, 0.1f}, 1.f);
    const int cup = mat(Pattern::kStripes, {0.90f, 0.90f, 0.88f}, {0.80f, 0.15f, 0.10f}, 0.03f);
    const int book = mat(Pattern::kDetails, {0.15f, 0.45f, 0.20f}, {0.95f, 0.95f, 0.90f}, 0.03f);
    const int ball = mat(Pattern::kChecker, {0.95f, 0.60f, 0.10f}, {0.10f, 0.10f, 0.40f}, 0.04f);
    const int chair = mat(Pattern::kNoise, {0.20f, 0.25f, 0.45f}, {0.10f, 0.12f, 0.25f}, 0.05f);
    s.primitives_.push_back(Box({-0.1f, 0.8f, 1.0f}, {0.01f, 2.2f, 2.1f}, window));
    // Desk against the +y wall, closed on three sides below: a dark cave under it.
    s.primitives_.push_back(Box({1.0f, 2.4f, 0.73f}, {2.6f, 3.3f, 0.77f}, desk));
    s.primitives_.push_back(Box({1.0f, 2.4f, 0.f}, {1.05f, 3.3f, 0.73f}, panel));
    s.primitives_.push_back(Box({2.55f, 2.4f, 0.f}, {2.6f, 3.3f, 0.73f}, panel));
    s.primitives_.push_back(Box({1.05f, 3.25f, 0.f}, {2.55f, 3.3f, 0.73f}, panel));
    // Monitor: dark housing with a glowing screen facing -y.
    s.primitives_.push_back(Box({1.45f, 3.0f, 0.80f}, {2.15f, 3.06f, 1.22f}, black));
    s.primitives_.push_back(Box({1.48f, 2.99f, 0.83f}, {2.12f, 3.0f, 1.19f}, screen));
    s.primitives_.push_back(Box({1.75f, 3.0f, 0.77f}, {1.85f, 3.06f, 0.80f}, black));
    // Objects on the desk.
    s.primitives_.push_back(Cylinder(1.25f, 2.6f, 0.04f, 0.77f, 0.87f, cup));
    s.primitives_.push_back(Cylinder(2.35f + 0.03f * u(rng), 2.65f, 0.035f, 0.77f, 0.90f, cup));
    s.primitives_.push_back(Box({1.5f, 2.5f, 0.77f}, {1.75f, 2.85f, 0.82f}, book));
    s.primitives_.push_back(Box({1.52f, 2.52f, 0.82f}, {1.72f, 2.80f, 0.85f}, book));
    s.primitives_.push_back(Sphere({2.05f, 2.6f, 0.85f}, 0.08f, ball));
    s.primitives_.push_back(Cylinder(2.45f, 3.05f, 0.015f, 0.77f, 1.15f, black));  // lamp arm
    // A chair in front of the desk.
    s.primitives_.push_back(Box({1.5f, 1.6f, 0.42f}, {2.0f, 2.1f, 0.47f}, chair));
    s.primitives_.push_back(Box({1.5f, 1.55f, 0.47f}, {2.0f, 1.6f, 0.95f}, chair));
    s.primitives_.push_back(Cylinder(1.75f, 1.85f, 0.03f, 0.f, 0.42f, black));
    light({0.35f, 1.3f, 1.8f}, {2.5f, 2.6f, 2.9f});   // daylight through the window
    light({0.35f, 1.8f, 1.3f}, {2.5f, 2.6f, 2.9f});
    light({2.40f, 2.95f, 1.15f}, {0.35f, 0.30f, 0.22f});  // desk lamp, close to the desk
    s.ambient_ = {0.02f, 0.02f, 0.022f};
    s.bright_targets_ = {{0.f, 2.6f, 1.2f}, {2.2f, 2.7f, 0.8f}, {1.8f, 3.0f, 1.0f}};
    s.dark_targets_ = {{1.8f, 3.0f, 0.2f}, {3.9f, 3.3f, 0.4f}, {3.5f, 0.2f, 0.3f}};
  } else if (name == "hall") {
    // A 12 x 8 m hall, 3.5 m high: furniture along every wall, a row of pillars and islands
    // of furniture down the middle, windows on two walls, lamps under the ceiling. Walked
    // round by CameraPath::Walk, which keeps the walls and furniture within depth range.
    s.room_lo_ = {0, 0, 0};
    s.room_hi_ = {12, 8, 3.5f};
    s.walked_round_ = true;
    s.wall_material_[0] = mat(Pattern::kNoise, {0.74f, 0.70f, 0.62f}, {0.52f, 0.48f, 0.40f}, 0.45f);
    s.wall_material_[1] = mat(Pattern::kChecker, {0.72f, 0.72f, 0.76f}, {0.40f, 0.42f, 0.50f}, 0.6f);
    s.wall_material_[2] = mat(Pattern::kStripes, {0.80f, 0.78f, 0.70f}, {0.50f, 0.58f, 0.66f}, 0.35f);
    s.wall_material_[3] = mat(Pattern::kDetails, {0.74f, 0.74f, 0.70f}, {0.06f, 0.06f, 0.09f}, 0.25f);
    s.wall_material_[4] = mat(Pattern::kChecker, {0.55f, 0.40f, 0.25f}, {0.33f, 0.22f, 0.13f}, 0.4f);
    s.wall_material_[5] = mat(Pattern::kUniform, {0.85f, 0.85f, 0.85f}, {0.85f, 0.85f, 0.85f}, 1.f);
    const int window = emissive({240.f, 250.f, 280.f});
    const int wood = mat(Pattern::kNoise, {0.62f, 0.44f, 0.26f}, {0.40f, 0.27f, 0.14f}, 0.08f);
    const int dark = mat(Pattern::kUniform, {0.12f, 0.12f, 0.13f}, {0.1f, 0.1f, 0.1f}, 1.f);
    const int shelf = mat(Pattern::kStripes, {0.85f, 0.84f, 0.78f}, {0.22f, 0.34f, 0.26f}, 0.14f);
    const int books = mat(Pattern::kStripes, {0.20f, 0.30f, 0.70f}, {0.85f, 0.80f, 0.30f}, 0.06f);
    const int crate = mat(Pattern::kChecker, {0.70f, 0.55f, 0.30f}, {0.45f, 0.32f, 0.15f}, 0.15f);
    const int fabric = mat(Pattern::kNoise, {0.62f, 0.16f, 0.14f}, {0.38f, 0.08f, 0.08f}, 0.12f);
    const int stone = mat(Pattern::kNoise, {0.66f, 0.66f, 0.64f}, {0.42f, 0.42f, 0.44f}, 0.2f);
    const int ball = mat(Pattern::kDetails, {0.90f, 0.85f, 0.20f}, {0.05f, 0.10f, 0.60f}, 0.06f);
    const int ball2 = mat(Pattern::kChecker, {0.20f, 0.60f, 0.30f}, {0.90f, 0.90f, 0.90f}, 0.1f);
    const int metal = mat(Pattern::kUniform, {0.55f, 0.55f, 0.58f}, {0.5f, 0.5f, 0.5f}, 1.f);
    // Windows in the +x and -y walls.
    s.primitives_.push_back(Box({11.99f, 2.5f, 1.0f}, {12.1f, 5.5f, 2.6f}, window));
    s.primitives_.push_back(Box({4.0f, -0.1f, 1.1f}, {7.0f, 0.01f, 2.5f}, window));
    // Along the -x wall: shelves with books.
    for (float y : {0.8f, 3.2f, 5.6f}) {
      s.primitives_.push_back(Box({0.f, y, 0.f}, {0.45f, y + 1.6f, 1.9f}, shelf));
      s.primitives_.push_back(Box({0.45f, y + 0.1f, 0.9f + 0.1f * u(rng)}, {0.55f, y + 1.5f, 1.2f}, books));
    }
    // Along the +y wall: a long sofa, a table, crates.
    s.primitives_.push_back(Box({1.5f, 7.0f, 0.f}, {4.5f, 8.f, 0.45f}, fabric));
    s.primitives_.push_back(Box({1.5f, 7.7f, 0.45f}, {4.5f, 8.f, 0.95f}, fabric));
    s.primitives_.push_back(Box({6.0f, 6.6f, 0.72f}, {8.0f, 7.6f, 0.77f}, wood));
    for (float x : {6.05f, 7.90f})
      for (float y : {6.65f, 7.50f}) s.primitives_.push_back(Box({x, y, 0.f}, {x + 0.05f, y + 0.05f, 0.72f}, dark));
    s.primitives_.push_back(Box({9.2f, 7.0f, 0.f}, {10.0f, 7.8f, 0.8f}, crate));
    s.primitives_.push_back(Box({10.2f, 7.2f, 0.f}, {10.8f, 7.8f, 0.6f}, crate));
    s.primitives_.push_back(Box({9.4f, 7.2f, 0.8f}, {9.9f, 7.7f, 1.2f}, crate));
    // Along the +x wall (beside the window) and the -y wall: cabinets, crates, a bench.
    s.primitives_.push_back(Box({11.3f, 0.5f, 0.f}, {12.f, 1.8f, 1.1f}, shelf));
    s.primitives_.push_back(Box({11.4f, 6.2f, 0.f}, {12.f, 7.6f, 0.9f}, crate));
    s.primitives_.push_back(Box({1.0f, 0.f, 0.f}, {3.0f, 0.5f, 0.5f}, wood));
    s.primitives_.push_back(Box({8.5f, 0.f, 0.f}, {10.5f, 0.6f, 1.4f}, shelf));
    s.primitives_.push_back(Box({8.7f, 0.6f, 0.9f + 0.05f * u(rng)}, {10.3f, 0.7f, 1.15f}, books));
    // Pillars down the middle, and islands of furniture between them.
    for (float x : {4.f, 6.f, 8.f}) s.primitives_.push_back(Cylinder(x, 4.f, 0.3f, 0.f, 3.5f, stone));
    s.primitives_.push_back(Box({4.6f, 3.6f, 0.f}, {5.4f, 4.4f, 0.75f}, crate));
    s.primitives_.push_back(Box({6.7f, 3.6f, 0.f}, {7.3f, 4.4f, 1.0f}, shelf));
    s.primitives_.push_back(Sphere({5.0f + 0.1f * u(rng), 4.0f, 0.95f}, 0.2f, ball));
    s.primitives_.push_back(Sphere({10.6f, 2.6f + 0.1f * u(rng), 0.35f}, 0.35f, ball2));
    s.primitives_.push_back(Sphere({0.9f, 2.8f, 0.3f}, 0.3f, ball));
    s.primitives_.push_back(Cylinder(7.5f, 1.0f, 0.2f, 0.f, 0.7f, metal));
    s.primitives_.push_back(Cylinder(2.0f, 6.0f, 0.03f, 0.f, 1.7f, metal));  // lamp pole
    // Light: the windows (point lights inside them), lamps under the ceiling, a floor lamp.
    light({11.6f, 4.0f, 1.8f}, {4.0f, 4.1f, 4.5f});
    light({5.5f, 0.4f, 1.8f}, {4.0f, 4.1f, 4.5f});
    for (float x : {3.f, 6.f, 9.f}) light({x, 2.f, 3.3f}, {1.2f, 1.1f, 0.9f});
    for (float x : {3.f, 9.f}) light({x, 6.f, 3.3f}, {1.2f, 1.1f, 0.9f});
    light({2.0f, 6.0f, 1.85f}, {1.0f, 0.8f, 0.55f});
    s.ambient_ = {0.03f, 0.03f, 0.032f};
    s.bright_targets_ = {{12.f, 4.0f, 1.8f}, {5.5f, 0.f, 1.8f}, {2.0f, 6.0f, 1.5f}, {11.6f, 1.2f, 1.0f}};
    s.dark_targets_ = {{6.9f, 7.1f, 0.3f}, {0.5f, 2.0f, 0.3f}, {10.0f, 7.5f, 0.3f}, {3.0f, 0.3f, 0.3f}};
  } else {
    throw SettingError("--scene", "unknown scene '" + name + "'; choose one of: " + NamesText());
  }
  s.Index();
  return s;
}

void Scene::Index() {
  boxes_.clear();
  curved_.clear();
  for (std::size_t i = 0; i < primitives_.size(); ++i) {
    if (primitives_[i].shape == Shape::kBox)
      boxes_.push_back({primitives_[i].lo, primitives_[i].hi, int(i)});
    else
      curved_.push_back(int(i));
  }
}

Hit Scene::Intersect(Float3 o, Float3 d, float t_min) const {
  Hit h;
  // The room from inside: the first wall the ray leaves through.
  const float ov[3] = {o.x, o.y, o.z}, dv[3] = {d.x, d.y, d.z};
  const float lo[3] = {room_lo_.x, room_lo_.y, room_lo_.z};
  const float hi[3] = {room_hi_.x, room_hi_.y, room_hi_.z};
  float best = 1e30f;
  int wall = 0;
  for (int a = 0; a < 3; ++a) {
    if (std::abs(dv[a]) < 1e-12f) continue;
    const float t = ((dv[a] > 0 ? hi[a] : lo[a]) - ov[a]) / dv[a];
    if (t < best) {
      best = t;
      wall = 2 * a + (dv[a] > 0 ? 1 : 0);
    }
  }
  static const Float3 kInward[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0},
                                    {0, -1, 0}, {0, 0, 1},  {0, 0, -1}};
  h.t = best;
  h.normal = kInward[wall];
  h.material = wall_material_[wall];
  h.primitive = -1;
  const Float3 inv = Inverse(d);
  int best_box = -1;
  for (std::size_t i = 0; i < boxes_.size(); ++i) {
    float t;
    if (SlabEnter(boxes_[i].lo, boxes_[i].hi, o, inv, t_min, h.t, &t)) {
      h.t = t;
      best_box = int(i);
    }
  }
  if (best_box >= 0) {
    const BoxRef& b = boxes_[std::size_t(best_box)];
    h.normal = BoxNormal(b.lo, b.hi, o + d * h.t);
    h.material = primitives_[std::size_t(b.index)].material;
    h.primitive = b.index;
  }
  for (int i : curved_) {
    float t;
    Float3 n;
    if (IntersectPrimitive(primitives_[std::size_t(i)], o, d, t_min, h.t, &t, &n)) {
      h.t = t;
      h.normal = n;
      h.material = primitives_[std::size_t(i)].material;
      h.primitive = i;
    }
  }
  h.point = o + d * h.t;
  return h;
}

bool Scene::Occluded(Float3 p, Float3 light) const {
  const Float3 v = light - p;
  const float dist = Length(v);
  const Float3 d = v / dist;
  const Float3 inv = Inverse(d);
  float t;
  for (const BoxRef& b : boxes_)
    if (SlabEnter(b.lo, b.hi, p, inv, 1e-3f, dist - 1e-3f, &t)) return true;
  Float3 n;
  for (int i : curved_)
    if (IntersectPrimitive(primitives_[std::size_t(i)], p, d, 1e-3f, dist - 1e-3f, &t, &n))
      return true;
  return false;
}

Float3 Scene::Albedo(int material, Float3 p) const {
  const Material& m = materials_[material];
  switch (m.pattern) {
    case Pattern::kUniform: return m.a;
    case Pattern::kChecker: {
      const int k = int(std::floor(p.x / m.scale + 1e-4f)) + int(std::floor(p.y / m.scale + 1e-4f)) +
                    int(std::floor(p.z / m.scale + 1e-4f));
      return (k & 1) ? m.b : m.a;
    }
    case Pattern::kStripes: {
      const float s = std::sin((p.x + p.y + 0.5f * p.z) * (2 * kPi / m.scale));
      return s > 0 ? m.a : m.b;
    }
    case Pattern::kNoise: {
      const float v = FractalNoise(p * (1.f / m.scale), seed_ + std::uint32_t(material) * 101u);
      return m.a + (m.b - m.a) * v;
    }
    case Pattern::kDetails: {
      // Dots of radius 0.18 * scale on a jittered grid: small, high-contrast features.
      const Float3 q = p * (1.f / m.scale);
      const float fx = q.x - std::floor(q.x) - 0.5f, fy = q.y - std::floor(q.y) - 0.5f,
                  fz = q.z - std::floor(q.z) - 0.5f;
      // Products in unsigned arithmetic: the same bits as before, without signed overflow.
      const float on = HashToUnit(std::uint32_t(int(std::floor(q.x))) * 73856093u ^
                                  std::uint32_t(int(std::floor(q.y))) * 19349663u ^
                                  std::uint32_t(int(std::floor(q.z))) * 83492791u ^ seed_);
      const float r2 = fx * fx + fy * fy + fz * fz;
      return (on > 0.35f && r2 < 0.1f) ? m.b : m.a;
    }
  }
  return m.a;
}

Float3 Scene::Shade(const Hit& hit) const {
  const Material& m = materials_[hit.material];
  if (m.emission.x > 0 || m.emission.y > 0 || m.emission.z > 0) return m.emission;
  Float3 e = ambient_;
  const Float3 p = hit.point + hit.normal * 1e-3f;
  for (const PointLight& l : lights_) {
    const Float3 v = l.position - hit.point;
    const float d2 = Dot(v, v);
    const float cos_theta = Dot(hit.normal, v) / std::sqrt(d2);
    if (cos_theta <= 0) continue;
    if (Occluded(p, l.position)) continue;
    e += l.intensity * (cos_theta / d2);
  }
  return Mul(Albedo(hit.material, hit.point), e) * (1.f / kPi);
}

float Scene::DistanceToSurface(Float3 p) const {
  float d = std::min({p.x - room_lo_.x, room_hi_.x - p.x, p.y - room_lo_.y, room_hi_.y - p.y,
                      p.z - room_lo_.z, room_hi_.z - p.z});
  d = std::abs(d);
  for (const Primitive& prim : primitives_) {
    Float3 n;
    d = std::min(d, std::abs(PrimitiveDistance(prim, p, &n)));
  }
  return d;
}

Float3 Scene::RadianceAt(Float3 p) const {
  // Nearest surface: a wall, or a primitive.
  const float wd[6] = {p.x - room_lo_.x, room_hi_.x - p.x, p.y - room_lo_.y,
                       room_hi_.y - p.y, p.z - room_lo_.z, room_hi_.z - p.z};
  static const Float3 kInward[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0},
                                    {0, -1, 0}, {0, 0, 1},  {0, 0, -1}};
  Hit h;
  int wall = int(std::min_element(wd, wd + 6) - wd);
  float best = std::abs(wd[wall]);
  float signed_d = wd[wall];  // positive inside the room
  h.normal = kInward[wall];
  h.material = wall_material_[wall];
  for (std::size_t i = 0; i < primitives_.size(); ++i) {
    Float3 n;
    const float sd = PrimitiveDistance(primitives_[i], p, &n);
    if (std::abs(sd) < best) {
      best = std::abs(sd);
      signed_d = sd;
      h.normal = n;
      h.material = primitives_[i].material;
      h.primitive = int(i);
    }
  }
  // Shade the nearest surface point, not p itself: a point a little inside an object
  // would otherwise be in its own shadow.
  h.point = p - h.normal * signed_d;
  return Shade(h);
}

}  // namespace hdrf::sim
