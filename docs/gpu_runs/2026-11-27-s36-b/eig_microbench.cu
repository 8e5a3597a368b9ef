// Diagnostic (not kept): SymmetricEigen6 before/after on the GPU, clock64, and bit equality.
#include <cstdio>
#include <cstring>
#include <random>
#include "tracking/gn_step.h"
namespace hdrf::tracking {
#include "old.inc"
}
using namespace hdrf::tracking;
__global__ void Run(const double* A, int n, double* out_new, double* out_old, long long* cyc) {
  long long c0 = clock64(), c1 = 0, c2 = 0;
  for (int m = 0; m < n; ++m) {
    SymmetricEigen6(A + 36 * m, out_new + 42 * m, out_new + 42 * m + 6);
  }
  c1 = clock64();
  for (int m = 0; m < n; ++m) {
    OldEigen6(A + 36 * m, out_old + 42 * m, out_old + 42 * m + 6);
  }
  c2 = clock64();
  cyc[0] = c1 - c0; cyc[1] = c2 - c1;
}
int main() {
  const int n = 200;
  std::mt19937 rng(7);
  std::normal_distribution<double> N(0, 1);
  std::vector<double> A(36 * n);
  for (int m = 0; m < n; ++m) {
    double J[6][40];
    for (int i = 0; i < 6; ++i) for (int r = 0; r < 40; ++r) J[i][r] = N(rng) * (i < 3 ? 1.0 : (m % 3 == 0 ? 1e-3 : 0.1));
    for (int i = 0; i < 6; ++i) for (int j = 0; j < 6; ++j) { double s = 0; for (int r = 0; r < 40; ++r) s += J[i][r] * J[j][r]; A[36 * m + 6 * i + j] = s; }
  }
  double *dA, *dn, *dold; long long* dc;
  cudaMalloc(&dA, 8 * A.size()); cudaMalloc(&dn, 8 * 42 * n); cudaMalloc(&dold, 8 * 42 * n); cudaMalloc(&dc, 16);
  cudaMemcpy(dA, A.data(), 8 * A.size(), cudaMemcpyHostToDevice);
  Run<<<1, 1>>>(dA, n, dn, dold, dc);  // warm
  Run<<<1, 1>>>(dA, n, dn, dold, dc);
  std::vector<double> hn(42 * n), ho(42 * n), hh(42 * n); long long c[2];
  cudaMemcpy(hn.data(), dn, 8 * hn.size(), cudaMemcpyDeviceToHost);
  cudaMemcpy(ho.data(), dold, 8 * ho.size(), cudaMemcpyDeviceToHost);
  cudaMemcpy(c, dc, 16, cudaMemcpyDeviceToHost);
  for (int m = 0; m < n; ++m) SymmetricEigen6(&A[36 * m], &hh[42 * m], &hh[42 * m + 6]);
  int dgo = 0, dgh = 0;
  for (int k = 0; k < 42 * n; ++k) { dgo += std::memcmp(&hn[k], &ho[k], 8) != 0; dgh += std::memcmp(&hn[k], &hh[k], 8) != 0; }
  std::printf("eigen6 x%d: new %.0f cycles a call, old %.0f; values differing new/old %d, new/host %d of %d\n", n, double(c[0]) / n, double(c[1]) / n, dgo, dgh, 42 * n);
  return 0;
}
