// Symmetric 6x6 matrices for the eigen decomposition's tests (SymmetricEigen6, gn_step.h):
// the kinds the tracker's weak-direction check meets and those hard for Jacobi rotations.
#pragma once

#include <array>
#include <cmath>
#include <random>
#include <vector>

namespace hdrf::test {

// n matrices, row-major: Q diag(lam) Q^T with a random rotation Q and eigenvalues spread
// over up to 12 decades (the whitened normal equations of a wall seen head on), some with
// repeated or nearly repeated eigenvalues, some already diagonal or with zero entries, and
// plain sums of outer products of random vectors.
inline std::vector<std::array<double, 36>> SymmetricSixes(int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> g(0, 1);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<std::array<double, 36>> out;
  for (int m = 0; m < n; ++m) {
    std::array<double, 36> A{};
    const int kind = m % 5;
    if (kind == 4) {  // outer products
      for (int r = 0; r < 1 + m % 9; ++r) {
        double v[6];
        for (double& x : v) x = g(rng);
        for (int i = 0; i < 6; ++i)
          for (int j = 0; j < 6; ++j) A[std::size_t(6 * i + j)] += v[i] * v[j];
      }
      out.push_back(A);
      continue;
    }
    double lam[6];
    for (int k = 0; k < 6; ++k) lam[k] = std::pow(10.0, 12.0 * u(rng) - 6.0);
    if (kind == 1) lam[1] = lam[0], lam[3] = lam[2] * (1 + 1e-13);  // repeated, nearly repeated
    // Q: Gram-Schmidt of a random matrix (identity for the diagonal kind).
    double Q[36];
    for (double& x : Q) x = g(rng);
    if (kind == 2)
      for (int k = 0; k < 36; ++k) Q[k] = k % 7 == 0 ? 1.0 : 0.0;
    for (int c = 0; c < 6; ++c) {
      for (int p = 0; p < c; ++p) {
        double d = 0;
        for (int r = 0; r < 6; ++r) d += Q[6 * r + c] * Q[6 * r + p];
        for (int r = 0; r < 6; ++r) Q[6 * r + c] -= d * Q[6 * r + p];
      }
      double l = 0;
      for (int r = 0; r < 6; ++r) l += Q[6 * r + c] * Q[6 * r + c];
      for (int r = 0; r < 6; ++r) Q[6 * r + c] /= std::sqrt(l);
    }
    for (int i = 0; i < 6; ++i)
      for (int j = 0; j < 6; ++j) {
        double s = 0;
        for (int k = 0; k < 6; ++k) s += Q[6 * i + k] * lam[k] * Q[6 * j + k];
        A[std::size_t(6 * i + j)] = s;
      }
    for (int i = 0; i < 6; ++i)  // exactly symmetric
      for (int j = 0; j < i; ++j) A[std::size_t(6 * i + j)] = A[std::size_t(6 * j + i)];
    if (kind == 3) A[1] = A[6] = 0, A[2 * 6 + 5] = A[5 * 6 + 2] = 0;  // zero entries to skip
    out.push_back(A);
  }
  return out;
}

}  // namespace hdrf::test
