// Mantiuk 2008 on the GPU: the band-pass analysis and the histogram, and the per-pixel
// apply step, through the per-element functions of mantiuk08_impl.h.
#include "common/parallel_cuda.cuh"
#include "tonemap/mantiuk08/mantiuk08.h"

namespace hdrf::tonemap::m08 {

namespace {
__device__ bool NoDataPixel(Float3 c) {
  return !(isfinite(c.x) && isfinite(c.y) && isfinite(c.z)) || (c.x == 0 && c.y == 0 && c.z == 0);
}
struct SumAcc {
  double v[2] = {};
};
}  // namespace

struct CudaWorkspace::Impl {
  int w = 0, h = 0;
  DeviceBuffer<Float3> rgb, out;
  DeviceBuffer<float> high, low, tmp;
  DeviceBuffer<unsigned char> valid;
  DeviceBuffer<unsigned> counts;
  par::Reducer reducer{2};
};

CudaWorkspace::CudaWorkspace() : impl_(std::make_unique<Impl>()) {}
CudaWorkspace::~CudaWorkspace() = default;

void CudaWorkspace::Upload(const RadianceImage& rgb) {
  Impl& m = *impl_;
  const std::size_t n = rgb.size();
  if (m.w != rgb.width() || m.h != rgb.height()) {
    m.w = rgb.width(), m.h = rgb.height();
    m.out = DeviceBuffer<Float3>(n);
    m.high = DeviceBuffer<float>(n), m.low = DeviceBuffer<float>(n), m.tmp = DeviceBuffer<float>(n);
    m.valid = DeviceBuffer<unsigned char>(n);
  }
  m.rgb.Upload(rgb.data(), n);
}

Density CudaWorkspace::ComputeDensity(float floor, int bands) {
  Impl& m = *impl_;
  Density d;
  d.bands = bands;
  d.count.assign(std::size_t(bands) * kNodes * kContrastBins, 0.0);
  const int w = m.w, h = m.h;
  if (w * h == 0) return d;
  const Float3* rgb = m.rgb.data();
  float* high = m.high.data();
  unsigned char* valid = m.valid.data();
  par::ForEach(par::Gpu{}, w * h, [=] __device__(int i) {
    const Float3 c = rgb[i];
    const float l = Luminance(c);
    const bool ok = isfinite(l) && !NoDataPixel(c);
    valid[i] = ok;
    high[i] = ClampedLog10(ok ? l : 0.f, floor);
  });
  const SumAcc s = m.reducer.Sum<SumAcc>(w, h, [=] __device__(int x, int y, SumAcc& acc) {
    const int i = y * w + x;
    if (valid[i]) acc.v[0] += high[i], acc.v[1] += 1;
  });
  if (s.v[1] == 0) return d;
  const float fill = float(s.v[0] / s.v[1]);
  par::ForEach(par::Gpu{}, w * h, [=] __device__(int i) {
    if (!valid[i]) high[i] = fill;
  });
  const std::size_t cells = std::size_t(kNodes) * kContrastBins;
  m.counts = DeviceBuffer<unsigned>(cells * std::size_t(bands));
  HDRF_CUDA_CHECK(cudaMemset(m.counts.data(), 0, sizeof(unsigned) * cells * std::size_t(bands)));
  float *hi = m.high.data(), *lo = m.low.data(), *tmp = m.tmp.data();
  for (int b = 0; b < bands; ++b) {
    const int step = 1 << b;
    const ImageView<const float> hv{hi, w, h}, tv{tmp, w, h};
    float* t = tmp;
    float* l = lo;
    par::ForEachPixel(par::Gpu{}, w, h, [=] __device__(int x, int y) { t[y * w + x] = LowPassTap(hv, x, y, step, true); });
    par::ForEachPixel(par::Gpu{}, w, h, [=] __device__(int x, int y) { l[y * w + x] = LowPassTap(tv, x, y, step, false); });
    unsigned* counts = m.counts.data() + cells * std::size_t(b);
    const float* hp = hi;
    const float* lp = lo;
    par::ForEach(par::Gpu{}, w * h, [=] __device__(int i) {
      const int cell = valid[i] ? DensityCell(hp[i], lp[i]) : -1;
      if (cell >= 0) atomicAdd(&counts[cell], 1u);
    });
    std::swap(hi, lo);
  }
  std::vector<unsigned> host(cells * std::size_t(bands));
  m.counts.Download(host.data());
  for (std::size_t i = 0; i < host.size(); ++i) d.count[i] = host[i];
  FinishDensity(d);
  return d;
}

void CudaWorkspace::Apply(const CurveLut& lut, Image<Float3>& out) {
  Impl& m = *impl_;
  if (out.width() != m.w || out.height() != m.h) out = Image<Float3>(m.w, m.h);
  DeviceBuffer<CurveLut> d_lut;
  d_lut.Upload(&lut, 1);
  const CurveLut* l = d_lut.data();
  const Float3* rgb = m.rgb.data();
  Float3* o = m.out.data();
  par::ForEach(par::Gpu{}, m.w * m.h, [=] __device__(int i) {
    const Float3 c = rgb[i];
    o[i] = NoDataPixel(c) ? Float3{0, 0, 0} : ApplyCurve(c, *l);
  });
  m.out.Download(out.data());
}

}  // namespace hdrf::tonemap::m08
