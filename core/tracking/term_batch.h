// The CPU's accumulator of the tracker's per-pixel terms (host only).
#pragma once

#include <cstring>

#include "tracking/tracking_impl.h"

namespace hdrf::tracking {

// The CPU's accumulator of one chunk's terms (SumTerms in tracking.cpp). Added one term at a
// time (GnSystem::Add), the 27 running sums of w J J^T and w r J do not fit the registers:
// each term loads and stores every one. TermBatch keeps up to kCapacity terms' Jacobians and
// weights side by side and adds them four at a time, each sum in four lanes (terms 0, 4, 8,
// ... in the first) that are added together when the batch is emptied: an order fixed by the
// terms' order alone, so the same bits on every run and for any number of threads, within
// rounding of one-at-a-time sums. The robust residual sums and counts are added term by
// term as GnSystem adds them. Empties itself into `out` when destroyed.
class TermBatch {
 public:
  explicit TermBatch(GnSystem& out) : out_(out) {}
  TermBatch(const TermBatch&) = delete;
  TermBatch& operator=(const TermBatch&) = delete;
  ~TermBatch() { Flush(); }

  // As tracking::AddRobustTerm (tracking_impl.h) for a GnSystem.
  friend void AddRobustTerm(TermBatch& b, const double J[6], double r, double s, double huber_k, int first,
                            double share = 1) {
    const double wgt = HuberWeight(r * s, huber_k);
    const int n = b.n_;
    for (int i = 0; i < 6; ++i) b.j_[i][n] = J[i];
    b.w_[n] = wgt * share;
    b.wr_[n] = (wgt * share) * (r * s);
    b.out_.v[first] += wgt * r * r;
    b.out_.v[first + 2] += wgt;
    b.out_.v[first + 4] += 1;
    if (++b.n_ == kCapacity) b.Flush();
  }

 private:
  static constexpr int kLanes = 4, kCapacity = 128;
  using Lanes = double __attribute__((vector_size(kLanes * sizeof(double))));

  void Flush() {
    if (n_ == 0) return;
    for (int k = n_; k % kLanes != 0 && k < kCapacity; ++k) {  // the last group filled with terms of weight 0
      for (int i = 0; i < 6; ++i) j_[i][k] = 0;
      w_[k] = wr_[k] = 0;
    }
    Lanes h[GnSystem::kH] = {}, g[GnSystem::kG] = {};
    for (int k = 0; k < n_; k += kLanes) {
      Lanes J[6], w, wr;
      for (int i = 0; i < 6; ++i) std::memcpy(&J[i], &j_[i][k], sizeof(Lanes));
      std::memcpy(&w, &w_[k], sizeof(Lanes));
      std::memcpy(&wr, &wr_[k], sizeof(Lanes));
      int m = 0;
      for (int i = 0; i < 6; ++i) {
        const Lanes wj = w * J[i];
        for (int j = i; j < 6; ++j) h[m++] += wj * J[j];
        g[i] += wr * J[i];
      }
    }
    for (int m = 0; m < GnSystem::kH; ++m) out_.v[m] += (h[m][0] + h[m][1]) + (h[m][2] + h[m][3]);
    for (int i = 0; i < GnSystem::kG; ++i) out_.v[GnSystem::kH + i] += (g[i][0] + g[i][1]) + (g[i][2] + g[i][3]);
    n_ = 0;
  }

  GnSystem& out_;
  int n_ = 0;
  alignas(32) double j_[6][kCapacity];
  alignas(32) double w_[kCapacity];
  alignas(32) double wr_[kCapacity];
};

}  // namespace hdrf::tracking
