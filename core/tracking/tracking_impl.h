// Per-pixel Gauss-Newton terms of the tracker, shared by the CPU loops (tracking.cpp) and
// the CUDA reductions (tracking_cuda.cu): the same residual, Jacobian and robust weight on
// both backends; only the order of the final sums differs. A term hands its Jacobian to
// AddRobustTerm of its accumulator: GnSystem adds it at once (the GPU's threads), the CPU's
// TermBatch gathers terms and adds them several at a time.
#pragma once

#include "common/camera.h"
#include "common/host_device.h"
#include "common/image_view.h"
#include "common/vec.h"
#include "imaging/imaging_impl.h"

namespace hdrf::tracking {

// The normal equations of one Gauss-Newton step and the health sums, as plain doubles so
// that they can be reduced on a GPU: H (upper triangle, row-major), g, then the robust
// residual sums and counts of the ICP and photometric terms.
struct GnSystem {
  static constexpr int kH = 21, kG = 6, kSize = 33;
  double v[kSize] = {};
  HDRF_HD double& icp_r2() { return v[27]; }
  HDRF_HD double& photo_r2() { return v[28]; }
  HDRF_HD double& icp_w() { return v[29]; }
  HDRF_HD double& photo_w() { return v[30]; }
  HDRF_HD double& icp_n() { return v[31]; }
  HDRF_HD double& photo_n() { return v[32]; }
  // Adds w * J J^T and w * r * J.
  HDRF_HD void Add(const double J[6], double r, double w) {
    int k = 0;
    for (int i = 0; i < 6; ++i) {
      const double wj = w * J[i];
      for (int j = i; j < 6; ++j) v[k++] += wj * J[j];
      v[kH + i] += w * r * J[i];
    }
  }
  HDRF_HD void Merge(const GnSystem& o) {
    for (int i = 0; i < kSize; ++i) v[i] += o.v[i];
  }
};

HDRF_HD double HuberWeight(double r_scaled, double k) {
  const double a = r_scaled < 0 ? -r_scaled : r_scaled;
  return a <= k ? 1.0 : k / a;
}

// Adds one robustly weighted term: J and r are already scaled by `s`; `first` is the index
// of the term kind's residual sum in GnSystem::v (27: ICP, 28: photometric), followed two
// and four places on by its weight sum and count.
// `share` scales the term's weight in the normal equations, not in the health sums.
HDRF_HD void AddRobustTerm(GnSystem& acc, const double J[6], double r, double s, double huber_k, int first,
                           double share = 1) {
  const double wgt = HuberWeight(r * s, huber_k);
  acc.Add(J, r * s, wgt * share);
  acc.v[first] += wgt * r * r;
  acc.v[first + 2] += wgt;
  acc.v[first + 4] += 1;
}

// Point-to-plane ICP: live vertex (camera frame) against the reference vertex and normal
// (world frame) found by projecting into the reference camera.
struct IcpArgs {
  ImageView<const Float3> live_vertex, live_normal;  // camera frame
  ImageView<const Float3> ref_vertex, ref_normal;    // world frame; zero = none
  PinholeCamera ref_cam;
  RigidTransform T_world_live, T_ref_world;
  double R_world_live[9];  // rotation of the live pose, row-major, double
  float cos_max_angle, max_dist, inv_sigma, huber_k;
  float z_ref_m;  // > 0: residuals scaled by (z_ref / z)^2 (TrackerOptions::icp_depth_ref_m)
};
// IcpTerm in two halves: the live vertex carried into the world and projected into the
// reference (IcpProject: false where it has no term), then the term at the reference pixel
// found (IcpAt). The CPU runs a row's first halves before their second halves (the look-ups
// of a row then wait on each other less); the GPU runs IcpTerm. The same operations.
HDRF_HD bool IcpProject(const IcpArgs& a, int x, int y, Float3* p, int* ux, int* uy) {
  const Float3 v = a.live_vertex(x, y);
  const Float3 nl = a.live_normal(x, y);
  if (v.z <= 0.f || Dot(nl, nl) == 0.f) return false;  // (a length is 0 exactly where this is)
  *p = a.T_world_live.Apply(v);
  const Float3 pr = a.T_ref_world.Apply(*p);
  if (pr.z <= 0.f) return false;
  const Float2 u = a.ref_cam.Project(pr);
  *ux = RoundToInt(u.x), *uy = RoundToInt(u.y);
  return !(*ux < 0 || *uy < 0 || *ux >= a.ref_cam.width || *uy >= a.ref_cam.height);
}
template <typename Acc>
HDRF_HD bool IcpAt(const IcpArgs& a, int x, int y, const Float3& p, int ux, int uy, Acc& acc) {
  const Float3 m = a.ref_vertex(ux, uy), n = a.ref_normal(ux, uy);
  if (Dot(n, n) == 0.f) return false;
  const Float3 d = p - m;
  if (Length(d) > a.max_dist) return false;
  const Float3 v = a.live_vertex(x, y);
  const Float3 nl = a.live_normal(x, y);
  if (Dot(n, a.T_world_live.Rotate(nl)) < a.cos_max_angle) return false;
  const double r = Dot(n, d);
  const double* R = a.R_world_live;
  const double nx = n.x, ny = n.y, nz = n.z;
  // a = R^T n; J = [a, v x a] (derivative of the residual w.r.t. the right-multiplied twist).
  const double ax = R[0] * nx + R[3] * ny + R[6] * nz;
  const double ay = R[1] * nx + R[4] * ny + R[7] * nz;
  const double az = R[2] * nx + R[5] * ny + R[8] * nz;
  const double vx = v.x, vy = v.y, vz = v.z;
  double s = a.inv_sigma;
  if (a.z_ref_m > 0.f) {
    // Clamped to a factor of 4 either way: a few pixels much nearer than the rest (an object
    // held close, the floor at the frame's edge) must not outweigh the view.
    double q = double(a.z_ref_m) / vz;
    q = q < 0.5 ? 0.5 : q > 2.0 ? 2.0 : q;
    s *= q * q;
  }
  const double J[6] = {ax * s, ay * s, az * s, (vy * az - vz * ay) * s, (vz * ax - vx * az) * s,
                       (vx * ay - vy * ax) * s};
  AddRobustTerm(acc, J, r, s, a.huber_k, 27);
  return true;
}
template <typename Acc>
HDRF_HD bool IcpTerm(const IcpArgs& a, int x, int y, Acc& acc) {
  Float3 p;
  int ux, uy;
  return IcpProject(a, x, y, &p, &ux, &uy) && IcpAt(a, x, y, p, ux, uy, acc);
}

// Photometric: reference pixel (world vertex, NR) warped into the live frame; residual
// NR_ref - NR_live(u'), scaled by the live PCF (the residual sums record it so scaled).
struct PhotoArgs {
  ImageView<const Float3> ref_vertex;  // world frame; zero = none
  ImageView<const float> ref_intensity;
  ImageView<const float> live_intensity, live_weight, live_gx, live_gy;
  PinholeCamera live_cam;
  RigidTransform T_live_world;
  float photo_sigma, huber_k;
  float share;  // the term's weight in the solve, 0..1 (the health sums count it whole)
};
// PhotoTerm in two halves, as IcpTerm: the reference point carried into the live camera and
// its bilinear position there (PhotoProject: false where it has no term), then the term
// (PhotoAt). The CPU runs a row's first halves before their second halves; the GPU runs
// PhotoTerm. The same operations.
HDRF_HD bool PhotoProject(const PhotoArgs& a, int x, int y, Float3* q, imaging::BilinearAt* at, float* i_ref) {
  const Float3 m = a.ref_vertex(x, y);
  if (m.x == 0.f && m.y == 0.f && m.z == 0.f) return false;
  *i_ref = a.ref_intensity(x, y);
  if (*i_ref == 0.f) return false;  // no model radiance here
  *q = a.T_live_world.Apply(m);
  if (q->z <= 0.1f) return false;
  const Float2 u = a.live_cam.Project(*q);
  // The live level's images share one size: the position is found once for all four.
  return at->Set(a.live_intensity.width, a.live_intensity.height, u.x, u.y);
}
template <typename Acc>
HDRF_HD bool PhotoAt(const PhotoArgs& a, const Float3& q, const imaging::BilinearAt& at, float i_ref, Acc& acc) {
  const PinholeCamera& c = a.live_cam;
  const float wl = at(a.live_weight);
  if (wl <= 0.f) return false;
  const float il = at(a.live_intensity), gx = at(a.live_gx), gy = at(a.live_gy);
  const double r = double(i_ref) - double(il);
  const double iz = 1.0 / double(q.z);
  // d(pi)/dq times dq/dxi, with dq/dxi = [-I, [q]x] for T_live <- T_live exp(xi).
  const double gu = double(gx * c.fx) * iz, gv = double(gy * c.fy) * iz;
  const double qx = q.x, qy = q.y, qz = q.z;
  const double dz = -(gu * qx + gv * qy) * iz;
  const double s = double(wl / a.photo_sigma);
  const double J[6] = {gu * s, gv * s, dz * s, (qy * dz - qz * gv) * s, (qz * gu - qx * dz) * s,
                       (qx * gv - qy * gu) * s};
  // The residual as the solve weighs it (confidence times difference), so that its recorded
  // scale is the one the measured scales must match.
  AddRobustTerm(acc, J, r * double(wl), 1.0 / double(a.photo_sigma), a.huber_k, 28, double(a.share));
  return true;
}
template <typename Acc>
HDRF_HD bool PhotoTerm(const PhotoArgs& a, int x, int y, Acc& acc) {
  Float3 q;
  imaging::BilinearAt at;
  float i_ref;
  return PhotoProject(a, x, y, &q, &at, &i_ref) && PhotoAt(a, q, at, i_ref, acc);
}

}  // namespace hdrf::tracking
