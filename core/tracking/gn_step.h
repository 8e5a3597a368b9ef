// One Gauss-Newton step of the tracker, written once for the host and the GPU in plain
// doubles: from the summed normal equations (GnSystem) and the motion prior, the twist that
// updates the pose, and the pose updated. tracking.cpp's loop runs it on the CPU; the CUDA
// tracker (tracking_cuda.cu) runs it in the last block of each reduction, so that a frame's
// iterations need no round trip to the host: the pose stays on the device between them.
#pragma once

#include <cmath>

#include "common/host_device.h"
#include "common/vec.h"
#include "tracking/tracking_impl.h"

namespace hdrf::tracking {

// A rigid pose: rotation (row-major) and translation, in doubles.
struct PoseD {
  double R[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  double t[3] = {0, 0, 0};
};

HDRF_HD PoseD Compose(const PoseD& a, const PoseD& b) {
  PoseD c;
  HDRF_UNROLL
  for (int i = 0; i < 3; ++i) {
    HDRF_UNROLL
    for (int j = 0; j < 3; ++j) c.R[3 * i + j] = a.R[3 * i] * b.R[j] + a.R[3 * i + 1] * b.R[3 + j] + a.R[3 * i + 2] * b.R[6 + j];
    c.t[i] = a.R[3 * i] * b.t[0] + a.R[3 * i + 1] * b.t[1] + a.R[3 * i + 2] * b.t[2] + a.t[i];
  }
  return c;
}
HDRF_HD PoseD Inverse(const PoseD& a) {
  PoseD c;
  HDRF_UNROLL
  for (int i = 0; i < 3; ++i)
    HDRF_UNROLL
    for (int j = 0; j < 3; ++j) c.R[3 * i + j] = a.R[3 * j + i];
  HDRF_UNROLL
  for (int i = 0; i < 3; ++i) c.t[i] = -(c.R[3 * i] * a.t[0] + c.R[3 * i + 1] * a.t[1] + c.R[3 * i + 2] * a.t[2]);
  return c;
}
HDRF_HD RigidTransform ToRigid(const PoseD& a) {
  RigidTransform r;
  HDRF_UNROLL
  for (int k = 0; k < 9; ++k) r.r[k] = float(a.R[k]);
  r.t = {float(a.t[0]), float(a.t[1]), float(a.t[2])};
  return r;
}

// exp of a twist (translation first, then rotation), as se3::Exp.
HDRF_HD PoseD ExpTwist(const double xi[6]) {
  const double wx = xi[3], wy = xi[4], wz = xi[5];
  const double theta = sqrt(wx * wx + wy * wy + wz * wz);
  const double W[9] = {0, -wz, wy, wz, 0, -wx, -wy, wx, 0};
  double W2[9];
  HDRF_UNROLL
  for (int i = 0; i < 3; ++i)
    HDRF_UNROLL
    for (int j = 0; j < 3; ++j) W2[3 * i + j] = W[3 * i] * W[j] + W[3 * i + 1] * W[3 + j] + W[3 * i + 2] * W[6 + j];
  double a, b, c;  // R = I + a W + b W^2, V = I + b' W + c W^2
  double vb;
  if (theta < 1e-10) {
    a = 1, b = 0, vb = 0.5, c = 0;
  } else {
    a = sin(theta) / theta;
    b = (1.0 - cos(theta)) / (theta * theta);
    c = (1.0 - a) / (theta * theta);
    vb = b;
  }
  PoseD T;
  double V[9];
  HDRF_UNROLL
  for (int k = 0; k < 9; ++k) {
    const double id = (k % 4 == 0) ? 1.0 : 0.0;
    T.R[k] = id + a * W[k] + b * W2[k];
    V[k] = id + vb * W[k] + c * W2[k];
  }
  HDRF_UNROLL
  for (int i = 0; i < 3; ++i) T.t[i] = V[3 * i] * xi[0] + V[3 * i + 1] * xi[1] + V[3 * i + 2] * xi[2];
  return T;
}

// The unit quaternion (x, y, z, w) of a rotation matrix (Shepperd's method: from the largest
// of the trace and the diagonal, for accuracy near any angle).
HDRF_HD void QuaternionOf(const double* R, double q[4]) {
  const double tr = R[0] + R[4] + R[8];
  if (tr > 0) {
    double s = sqrt(tr + 1.0);
    q[3] = 0.5 * s;
    s = 0.5 / s;
    q[0] = (R[7] - R[5]) * s;
    q[1] = (R[2] - R[6]) * s;
    q[2] = (R[3] - R[1]) * s;
  } else {
    int i = 0;
    if (R[4] > R[0]) i = 1;
    if (R[8] > R[4 * i]) i = 2;
    const int j = (i + 1) % 3, k = (j + 1) % 3;
    double s = sqrt(R[4 * i] - R[4 * j] - R[4 * k] + 1.0);
    q[i] = 0.5 * s;
    s = 0.5 / s;
    q[3] = (R[3 * k + j] - R[3 * j + k]) * s;
    q[j] = (R[3 * j + i] + R[3 * i + j]) * s;
    q[k] = (R[3 * k + i] + R[3 * i + k]) * s;
  }
}

// The rotation made exactly orthonormal again (through its normalised quaternion), as
// se3::Orthonormalized.
HDRF_HD PoseD OrthonormalizedD(const PoseD& a) {
  double q[4];
  QuaternionOf(a.R, q);
  const double n = sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
  const double x = q[0] / n, y = q[1] / n, z = q[2] / n, w = q[3] / n;
  const double tx = 2 * x, ty = 2 * y, tz = 2 * z;
  const double twx = tx * w, twy = ty * w, twz = tz * w, txx = tx * x, txy = ty * x, txz = tz * x;
  const double tyy = ty * y, tyz = tz * y, tzz = tz * z;
  PoseD c = a;
  c.R[0] = 1 - (tyy + tzz), c.R[1] = txy - twz, c.R[2] = txz + twy;
  c.R[3] = txy + twz, c.R[4] = 1 - (txx + tzz), c.R[5] = tyz - twx;
  c.R[6] = txz - twy, c.R[7] = tyz + twx, c.R[8] = 1 - (txx + tyy);
  return c;
}

// log of a pose (translation first, then rotation), as se3::Log.
HDRF_HD void LogTwist(const PoseD& T, double xi[6]) {
  double q[4];
  QuaternionOf(T.R, q);
  const double qn = sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
  for (double& c : q) c /= qn;
  const double n = sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2]);
  double w[3] = {0, 0, 0};
  double theta = 0;
  if (n > 0) {
    theta = 2 * atan2(n, fabs(q[3]));
    const double s = (q[3] < 0 ? -theta : theta) / n;
    w[0] = q[0] * s, w[1] = q[1] * s, w[2] = q[2] * s;
  }
  const double W[9] = {0, -w[2], w[1], w[2], 0, -w[0], -w[1], w[0], 0};
  double k = 0;
  if (theta >= 1e-10) {
    const double half = 0.5 * theta;
    k = (1.0 - half * cos(half) / sin(half)) / (theta * theta);
  }
  HDRF_UNROLL
  for (int i = 0; i < 3; ++i) {
    double row = 0;
    HDRF_UNROLL
    for (int j = 0; j < 3; ++j) {
      const double w2 = W[3 * i] * W[j] + W[3 * i + 1] * W[3 + j] + W[3 * i + 2] * W[6 + j];
      const double vinv = (i == j ? 1.0 : 0.0) - 0.5 * W[3 * i + j] + k * w2;
      row += vinv * T.t[j];
    }
    xi[i] = row;
  }
  xi[3] = w[0], xi[4] = w[1], xi[5] = w[2];
}

// Cholesky factor of a symmetric 6x6 matrix (lower, row-major); false unless it is
// positive definite.
HDRF_HD bool Cholesky6(const double A[36], double L[36]) {
  HDRF_UNROLL
  for (int k = 0; k < 36; ++k) L[k] = 0;
  HDRF_UNROLL
  for (int j = 0; j < 6; ++j) {
    double d = A[6 * j + j];
    HDRF_UNROLL
    for (int k = 0; k < j; ++k) d -= L[6 * j + k] * L[6 * j + k];
    if (!(d > 0)) return false;
    const double s = sqrt(d);
    L[6 * j + j] = s;
    HDRF_UNROLL
    for (int i = j + 1; i < 6; ++i) {
      double v = A[6 * i + j];
      HDRF_UNROLL
      for (int k = 0; k < j; ++k) v -= L[6 * i + k] * L[6 * j + k];
      L[6 * i + j] = v / s;
    }
  }
  return true;
}

// Eigenvalues (ascending) and unit eigenvectors (column k of V for value k) of a symmetric
// 6x6 matrix, by cyclic Jacobi rotations.
HDRF_HD void SymmetricEigen6(const double A_in[36], double evals[6], double V[36]) {
  double A[36];
  for (int k = 0; k < 36; ++k) A[k] = A_in[k], V[k] = (k % 7 == 0) ? 1.0 : 0.0;
  for (int sweep = 0; sweep < 30; ++sweep) {
    double off = 0, diag = 0;
    for (int i = 0; i < 6; ++i) {
      diag += A[7 * i] * A[7 * i];
      for (int j = i + 1; j < 6; ++j) off += A[6 * i + j] * A[6 * i + j];
    }
    if (!(off > 1e-30 * diag)) break;
    for (int p = 0; p < 5; ++p)
      for (int q = p + 1; q < 6; ++q) {
        const double apq = A[6 * p + q];
        if (apq == 0) continue;
        const double theta = (A[7 * q] - A[7 * p]) / (2 * apq);
        const double t = (theta >= 0 ? 1.0 : -1.0) / (fabs(theta) + sqrt(theta * theta + 1));
        const double c = 1 / sqrt(t * t + 1), s = t * c;
        for (int k = 0; k < 6; ++k) {  // A <- A J (columns p, q)
          const double akp = A[6 * k + p], akq = A[6 * k + q];
          A[6 * k + p] = c * akp - s * akq;
          A[6 * k + q] = s * akp + c * akq;
        }
        for (int k = 0; k < 6; ++k) {  // A <- J^T A (rows p, q)
          const double apk = A[6 * p + k], aqk = A[6 * q + k];
          A[6 * p + k] = c * apk - s * aqk;
          A[6 * q + k] = s * apk + c * aqk;
        }
        for (int k = 0; k < 6; ++k) {
          const double vkp = V[6 * k + p], vkq = V[6 * k + q];
          V[6 * k + p] = c * vkp - s * vkq;
          V[6 * k + q] = s * vkp + c * vkq;
        }
      }
  }
  int order[6] = {0, 1, 2, 3, 4, 5};
  for (int i = 1; i < 6; ++i)
    for (int j = i; j > 0 && A[7 * order[j]] < A[7 * order[j - 1]]; --j) {
      const int tmp = order[j];
      order[j] = order[j - 1], order[j - 1] = tmp;
    }
  double Vs[36];
  for (int k = 0; k < 6; ++k) {
    evals[k] = A[7 * order[k]];
    for (int r = 0; r < 6; ++r) Vs[6 * r + k] = V[6 * r + order[k]];
  }
  for (int k = 0; k < 36; ++k) V[k] = Vs[k];
}

// The motion prior as the step weighs it (tracking.h, MotionPrior): the prediction, the
// deviations per frame interval times the intervals spanned, the weak-direction floor.
struct StepPrior {
  bool on = false;
  PoseD T_predicted_inv;  // the prediction's inverse
  double sigma_m = 0.01, sigma_rad = 0.0174532925199433;
  double floor = 0;       // TrackerOptions::weak_info_floor / spans^2
};

enum StepOutcome : int {
  kStepTaken = 0,     // the pose moved; iterate on
  kStepConverged = 1, // the pose moved by less than the stop threshold: the level is done
  kStepTooFew = 2,    // fewer than 12 terms: the level stops, the pose unchanged
  kStepNotFinite = 3, // the solve failed: the level stops, the pose unchanged
};

// The step's parts, in the order GnStep runs them. The CUDA tracker runs the first three
// side by side (tracking_cuda.cu: the prior's residual, the check for weak directions and
// the factor of the system without them need only the sums and the pose), the same
// operations on the same values: the same bits as GnStep.

// The normal equations as a full 6x6 H and g.
HDRF_HD void StepSystem(const GnSystem& acc, double H[36], double g[6]) {
  HDRF_UNROLL
  for (int i = 0, k = 0; i < 6; ++i) {
    HDRF_UNROLL
    for (int j = i; j < 6; ++j, ++k) H[6 * i + j] = H[6 * j + i] = acc.v[k];
    g[i] = acc.v[GnSystem::kH + i];
  }
}
HDRF_HD bool EnoughTerms(const GnSystem& acc) { return !(acc.v[31] + acc.v[32] < 12); }

// How far T is from the prediction: log(T_predicted^-1 T).
HDRF_HD void PriorResidual(const StepPrior& prior, const PoseD& T, double e[6]) {
  LogTwist(Compose(prior.T_predicted_inv, T), e);
}

// Directions the pixel terms fix far more weakly than their strongest one are raised to the
// prior's floor (whitened by the prior's deviations, so that metres and radians compare).
// Where the whitened system's smallest eigenvalue is above the floor times its trace (>= the
// largest eigenvalue), nothing would be raised: a Cholesky factor tells, and the
// decomposition is skipped. (With prior.on and prior.floor > 0.)
HDRF_HD void WhitenedSystem(const StepPrior& prior, const double H[36], double sw[6], double Hw[36]) {
  HDRF_UNROLL
  for (int i = 0; i < 6; ++i) sw[i] = i < 3 ? prior.sigma_m : prior.sigma_rad;
  HDRF_UNROLL
  for (int i = 0; i < 6; ++i)
    HDRF_UNROLL
    for (int j = 0; j < 6; ++j) Hw[6 * i + j] = sw[i] * H[6 * i + j] * sw[j];
}
HDRF_HD bool WeakDirections(const StepPrior& prior, const double H[36]) {
  double sw[6], Hw[36];
  WhitenedSystem(prior, H, sw, Hw);
  double trace = 0;
  HDRF_UNROLL
  for (int i = 0; i < 6; ++i) trace += Hw[7 * i];
  double shifted[36], L[36];
  HDRF_UNROLL
  for (int k = 0; k < 36; ++k) shifted[k] = Hw[k] - (k % 7 == 0 ? prior.floor * trace : 0.0);
  return !Cholesky6(shifted, L);
}
// The raise itself (where WeakDirections): H and g gain the prior along the weak directions.
HDRF_HD void RaiseWeakDirections(const StepPrior& prior, const double e[6], double H[36], double g[6]) {
  double sw[6], Hw[36], ew[6];
  WhitenedSystem(prior, H, sw, Hw);
  HDRF_UNROLL
  for (int i = 0; i < 6; ++i) ew[i] = e[i] / sw[i];
  double lam[6], V[36];
  SymmetricEigen6(Hw, lam, V);
  const double top = lam[5];
  HDRF_UNROLL
  for (int k = 0; k < 6; ++k) {
    const double add = prior.floor * top - lam[k];
    if (!(add > 0)) continue;
    double u[6], vew = 0;
    HDRF_UNROLL
    for (int i = 0; i < 6; ++i) u[i] = V[6 * i + k] / sw[i], vew += V[6 * i + k] * ew[i];
    HDRF_UNROLL
    for (int i = 0; i < 6; ++i) {
      HDRF_UNROLL
      for (int j = 0; j < 6; ++j) H[6 * i + j] += add * u[i] * u[j];
      g[i] += add * u[i] * vew;
    }
  }
}

// The prior's information on H's diagonal, then the damping (1e-6 of the mean diagonal):
// H as the step solves it.
HDRF_HD void PriorInformation(const StepPrior& prior, double H[36]) {
  HDRF_UNROLL
  for (int i = 0; i < 6; ++i) {
    const double s = i < 3 ? prior.sigma_m : prior.sigma_rad;
    H[7 * i] += 1.0 / (s * s);
  }
}
HDRF_HD void Damp(double H[36]) {
  double trace = 0;
  HDRF_UNROLL
  for (int i = 0; i < 6; ++i) trace += H[7 * i];
  HDRF_UNROLL
  for (int i = 0; i < 6; ++i) H[7 * i] += 1e-6 * trace / 6.0;
}
// The prior's pull on g.
HDRF_HD void PriorGradient(const StepPrior& prior, const double e[6], double g[6]) {
  HDRF_UNROLL
  for (int i = 0; i < 6; ++i) {
    const double s = i < 3 ? prior.sigma_m : prior.sigma_rad;
    const double lambda = 1.0 / (s * s);
    g[i] += lambda * e[i];
  }
}

// From H's Cholesky factor L and g: the twist, *T moved by it, and whether it converged.
HDRF_HD int SolveAndMove(const double L[36], const double g[6], PoseD* T) {
  double xi[6], y[6];
  HDRF_UNROLL
  for (int i = 0; i < 6; ++i) {  // L y = -g
    double v = -g[i];
    HDRF_UNROLL
    for (int k = 0; k < i; ++k) v -= L[6 * i + k] * y[k];
    y[i] = v / L[7 * i];
  }
  HDRF_UNROLL
  for (int i = 5; i >= 0; --i) {  // L^T xi = y
    double v = y[i];
    HDRF_UNROLL
    for (int k = i + 1; k < 6; ++k) v -= L[6 * k + i] * xi[k];
    xi[i] = v / L[7 * i];
  }
  for (double x : xi)
    if (!(x - x == 0.0)) return kStepNotFinite;  // infinite or NaN
  *T = OrthonormalizedD(Compose(*T, ExpTwist(xi)));
  constexpr double kStop = 1e-4;  // 0.1 mm and 0.006 degrees: far below the depth's noise
  const double nt = sqrt(xi[0] * xi[0] + xi[1] * xi[1] + xi[2] * xi[2]);
  const double nw = sqrt(xi[3] * xi[3] + xi[4] * xi[4] + xi[5] * xi[5]);
  return nt < kStop && nw < kStop ? kStepConverged : kStepTaken;
}

// One step: solves the damped normal equations (with the prior, where on) and moves *T.
HDRF_HD int GnStep(const GnSystem& acc, const StepPrior& prior, PoseD* T) {
  if (!EnoughTerms(acc)) return kStepTooFew;
  double H[36], g[6];
  StepSystem(acc, H, g);
  if (prior.on) {
    double e[6];
    PriorResidual(prior, *T, e);
    if (prior.floor > 0 && WeakDirections(prior, H)) RaiseWeakDirections(prior, e, H, g);
    PriorInformation(prior, H);
    PriorGradient(prior, e, g);
  }
  Damp(H);
  double L[36];
  if (!Cholesky6(H, L)) return kStepNotFinite;
  return SolveAndMove(L, g, T);
}

}  // namespace hdrf::tracking
