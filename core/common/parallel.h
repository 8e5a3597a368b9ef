// The parallel primitives host drivers are written over, once for every device: a loop over
// n indices or over the pixels of a w x h grid. `par::Host` runs it on the CPU's threads
// (OpenMP); `par::Gpu` (parallel_cuda.cuh, .cu files only) launches it as a CUDA kernel. A
// driver templated on the device calls the modules' per-element functions through these,
// so the CPU and CUDA backends run the same steps in the same order:
//
// A .cu file that runs a driver with par::Gpu includes common/parallel_cuda.cuh before the
// driver's header (the driver names par::ForEachPixel; the GPU overload must be declared).
//
//   template <typename Device>
//   void Scale(Device d, ImageView<float> img, float s) {
//     par::ForEachPixel(d, img.width, img.height, HDRF_LAMBDA(int x, int y) { img(x, y) *= s; });
//   }
#pragma once

#include <omp.h>

#include <algorithm>
#include <iterator>

#include "common/host_device.h"

// A lambda the primitives can run on either device (captures by value).
#if defined(__CUDACC__)
#define HDRF_LAMBDA [=] __host__ __device__
#else
#define HDRF_LAMBDA [=]
#endif

namespace hdrf::par {

struct Host {};

template <typename F>
void ForEach(Host, int n, F f) {
#pragma omp parallel for schedule(static)
  for (int i = 0; i < n; ++i) f(i);
}

// Rows in small dynamic chunks: per-pixel costs vary (ray casting, bilateral windows).
template <typename F>
void ForEachPixel(Host, int w, int h, F f) {
#pragma omp parallel for schedule(dynamic, 4)
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) f(x, y);
}

// The same, where neighbouring pixels' work is alike (ray casting): the GPU runs it in
// square tiles, so that a warp's pixels are neighbours in both directions.
template <typename F>
void ForEachPixelInTiles(Host h, int w, int hgt, F f) {
  ForEachPixel(h, w, hgt, f);
}

// Sorts [first, last) by `<` as std::sort does, its two halves side by side on two of the
// CPU's threads and then merged (below 4096 elements, or with one thread, std::sort alone):
// the same order wherever elements that compare equal are alike. Not inside a parallel loop.
template <typename It>
void Sort(Host, It first, It last) {
  const auto n = std::distance(first, last);
  if (n < 4096 || omp_get_max_threads() < 2) {
    std::sort(first, last);
    return;
  }
  const It mid = std::next(first, n / 2);
#pragma omp parallel sections num_threads(2)
  {
#pragma omp section
    std::sort(first, mid);
#pragma omp section
    std::sort(mid, last);
  }
  std::inplace_merge(first, mid, last);
}

}  // namespace hdrf::par
