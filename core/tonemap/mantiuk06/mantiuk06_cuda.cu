// Mantiuk 2006 on the GPU: the pyramid, the transducer and the conjugate-gradient solve on
// the device through the per-element functions of mantiuk06_impl.h; dot products by the
// deterministic reduction (par::Reducer), so runs repeat exactly.
#include <algorithm>
#include <cmath>

#include "common/parallel_cuda.cuh"
#include "tonemap/mantiuk06/mantiuk06.h"

namespace hdrf::tonemap::m06 {

namespace {

struct Acc1 {
  double v[1] = {};
};
struct Acc2 {
  double v[2] = {};
};

__device__ bool NoDataPixel(Float3 c) {
  return !(isfinite(c.x) && isfinite(c.y) && isfinite(c.z)) || (c.x == 0 && c.y == 0 && c.z == 0);
}

struct DevLevel {
  int w = 0, h = 0;
  DeviceBuffer<float> value, gx, gy, wx, wy, sum;
  ImageView<float> V(DeviceBuffer<float>& b) { return {b.data(), w, h}; }
  ImageView<const float> C(const DeviceBuffer<float>& b) const { return {b.data(), w, h}; }
};

class Solver {
 public:
  Solver(int w, int h) : reducer_(2) {
    while (w >= 3 && h >= 3) {
      DevLevel l;
      l.w = w, l.h = h;
      const std::size_t n = std::size_t(w) * std::size_t(h);
      for (auto* b : {&l.value, &l.gx, &l.gy, &l.wx, &l.wy, &l.sum}) *b = DeviceBuffer<float>(n);
      lv_.push_back(std::move(l));
      w /= 2, h /= 2;
    }
  }
  std::vector<DevLevel>& levels() { return lv_; }

  void DownsampleChain() {
    for (std::size_t k = 1; k < lv_.size(); ++k) {
      const ImageView<const float> fine = lv_[k - 1].C(lv_[k - 1].value);
      const ImageView<float> out = lv_[k].V(lv_[k].value);
      const int ow = lv_[k].w, oh = lv_[k].h;
      par::ForEachPixel(par::Gpu{}, ow, oh, [=] __device__(int x, int y) { out(x, y) = Downsample(fine, ow, oh, x, y); });
    }
  }

  void DivergenceSum(bool targets) {
    for (int k = int(lv_.size()) - 1; k >= 0; --k) {
      DevLevel& l = lv_[std::size_t(k)];
      const ImageView<float> s = l.V(l.sum);
      if (!targets) {
        const ImageView<const float> v = l.C(l.value), wx = l.C(l.wx), wy = l.C(l.wy);
        const ImageView<float> gx = l.V(l.gx), gy = l.V(l.gy);
        par::ForEachPixel(par::Gpu{}, l.w, l.h, [=] __device__(int x, int y) {
          gx(x, y) = wx(x, y) * GradX(v, x, y);
          gy(x, y) = wy(x, y) * GradY(v, x, y);
        });
      }
      const ImageView<const float> gx = l.C(l.gx), gy = l.C(l.gy);
      const bool coarsest = k + 1 == int(lv_.size());
      const ImageView<const float> coarse =
          coarsest ? ImageView<const float>{} : lv_[std::size_t(k + 1)].C(lv_[std::size_t(k + 1)].sum);
      const int w = l.w, h = l.h;
      par::ForEachPixel(par::Gpu{}, w, h, [=] __device__(int x, int y) {
        s(x, y) = Divergence(gx, gy, x, y) + (coarsest ? 0.f : Upsample(coarse, w, h, x, y));
      });
    }
  }

  // ax = A x (x and ax of the finest level's size).
  void Apply(const float* x, float* ax) {
    DevLevel& f = lv_[0];
    const std::size_t n = std::size_t(f.w) * std::size_t(f.h);
    HDRF_CUDA_CHECK(cudaMemcpyAsync(f.value.data(), x, n * sizeof(float), cudaMemcpyDeviceToDevice, 0));
    DownsampleChain();
    DivergenceSum(false);
    HDRF_CUDA_CHECK(cudaMemcpyAsync(ax, f.sum.data(), n * sizeof(float), cudaMemcpyDeviceToDevice, 0));
  }

  double Dot(const float* a, const float* b, int n) {
    return reducer_.Sum<Acc1>(n, 1, [=] __device__(int i, int, Acc1& acc) { acc.v[0] += double(a[i]) * double(b[i]); }).v[0];
  }
  par::Reducer& reducer() { return reducer_; }

 private:
  std::vector<DevLevel> lv_;
  par::Reducer reducer_;
};

}  // namespace

// Everything a frame needs on the device, kept between frames of one size (allocations
// cost more than the solve at video rates).
struct CudaWorkspace::Impl {
  int w = 0, h = 0;
  std::unique_ptr<Solver> solver;
  DeviceBuffer<Float3> rgb, out;
  DeviceBuffer<float> log_lum, x, r, p, ap, best, b;
  DeviceBuffer<unsigned char> valid;
  DeviceBuffer<Transducer> tr;
  void Resize(int nw, int nh) {
    if (nw == w && nh == h) return;
    w = nw, h = nh;
    const std::size_t n = std::size_t(w) * std::size_t(h);
    solver = std::make_unique<Solver>(w, h);
    rgb = DeviceBuffer<Float3>(n), out = DeviceBuffer<Float3>(n);
    for (auto* v : {&log_lum, &x, &r, &p, &ap, &best, &b}) *v = DeviceBuffer<float>(n);
    valid = DeviceBuffer<unsigned char>(n);
    if (tr.size() == 0) tr.Upload(&DefaultTransducer(), 1);
  }
};

CudaWorkspace::CudaWorkspace() : impl_(std::make_unique<Impl>()) {}
CudaWorkspace::~CudaWorkspace() = default;

Result MapCuda(const RadianceImage& in, Image<Float3>& out, const Options& o) {
  CudaWorkspace ws;
  return ws.Map(in, out, o);
}

Result CudaWorkspace::Map(const RadianceImage& in, Image<Float3>& out, const Options& o) {
  o.Check();
  const int w = in.width(), h = in.height();
  if (out.width() != w || out.height() != h) out = Image<Float3>(w, h);
  Result res;
  const int n = int(in.size());
  if (n == 0) return res;
  float y_max = 0;
  for (std::size_t i = 0; i < in.size(); ++i) {
    const Float3 c = in[i];
    const bool ok = std::isfinite(c.x) && std::isfinite(c.y) && std::isfinite(c.z) && !(c.x == 0 && c.y == 0 && c.z == 0);
    if (ok) y_max = std::max(y_max, Luminance(c));
  }
  if (!(y_max > 0) || w < 3 || h < 3) return Map(in, out, o);  // nothing to solve: the CPU's answer
  const float clip = 1e-7f * y_max;
  Impl& m = *impl_;
  m.Resize(w, h);
  const std::size_t count = std::size_t(n);
  m.rgb.Upload(in.data(), count);
  DeviceBuffer<Float3>& rgb = m.rgb;
  DeviceBuffer<float>&log_lum = m.log_lum, &x = m.x, &r = m.r, &p = m.p, &ap = m.ap, &best = m.best, &b = m.b;
  DeviceBuffer<unsigned char>& valid = m.valid;
  Solver& solver = *m.solver;
  {
    const Float3* c = rgb.data();
    float* ll = log_lum.data();
    unsigned char* v = valid.data();
    par::ForEach(par::Gpu{}, n, [=] __device__(int i) {
      const bool ok = !NoDataPixel(c[i]);
      v[i] = ok;
      ll[i] = ok ? log10f(fmaxf(Luminance(c[i]), clip)) : 0.f;
    });
    const Acc2 s = solver.reducer().Sum<Acc2>(n, 1, [=] __device__(int i, int, Acc2& acc) {
      if (v[i]) acc.v[0] += ll[i], acc.v[1] += 1;
    });
    const float fill = float(s.v[0] / s.v[1]);
    par::ForEach(par::Gpu{}, n, [=] __device__(int i) {
      if (!v[i]) ll[i] = fill;
    });
  }
  auto& lv = solver.levels();
  HDRF_CUDA_CHECK(cudaMemcpy(lv[0].value.data(), log_lum.data(), sizeof(float) * std::size_t(n), cudaMemcpyDeviceToDevice));
  solver.DownsampleChain();
  const Transducer* trp = m.tr.data();
  const float detail = float(o.detail), factor = float(o.contrast);
  for (DevLevel& l : lv) {
    const ImageView<const float> v = l.C(l.value);
    const ImageView<float> gx = l.V(l.gx), gy = l.V(l.gy);
    par::ForEachPixel(par::Gpu{}, l.w, l.h, [=] __device__(int x, int y) {
      gx(x, y) = ToResponse(*trp, GradX(v, x, y) * detail);
      gy(x, y) = ToResponse(*trp, GradY(v, x, y) * detail);
    });
  }
  if (!o.equalise) {
    for (DevLevel& l : lv) {
      float *gx = l.gx.data(), *gy = l.gy.data();
      par::ForEach(par::Gpu{}, l.w * l.h, [=] __device__(int i) { gx[i] *= factor, gy[i] *= factor; });
    }
  } else {
    std::vector<std::vector<float>> hx(lv.size()), hy(lv.size());
    std::vector<const std::vector<float>*> px, py;
    for (std::size_t k = 0; k < lv.size(); ++k) {
      hx[k].resize(lv[k].gx.size()), hy[k].resize(lv[k].gy.size());
      lv[k].gx.Download(hx[k].data()), lv[k].gy.Download(hy[k].data());
      px.push_back(&hx[k]), py.push_back(&hy[k]);
    }
    float top = 0;
    const std::vector<float> cdf = EqualisationCdf(px, py, &top);
    DeviceBuffer<float> d_cdf;
    d_cdf.Upload(cdf.data(), cdf.size());
    const float* c = d_cdf.data();
    for (DevLevel& l : lv) {
      float *gx = l.gx.data(), *gy = l.gy.data();
      par::ForEach(par::Gpu{}, l.w * l.h, [=] __device__(int i) {
        const float s = EqualiseScale(gx[i], gy[i], c, kEqualiseBins, top, factor);
        gx[i] *= s, gy[i] *= s;
      });
    }
    cuda::Synchronize();
  }
  for (DevLevel& l : lv) {
    const ImageView<float> gx = l.V(l.gx), gy = l.V(l.gy), wx = l.V(l.wx), wy = l.V(l.wy);
    par::ForEachPixel(par::Gpu{}, l.w, l.h, [=] __device__(int x, int y) {
      const float tx = ToContrast(*trp, gx(x, y)) / detail, ty = ToContrast(*trp, gy(x, y)) / detail;
      wx(x, y) = FitWeight(tx), wy(x, y) = FitWeight(ty);
      gx(x, y) = wx(x, y) * tx, gy(x, y) = wy(x, y) * ty;
    });
  }
  solver.DivergenceSum(true);
  HDRF_CUDA_CHECK(cudaMemcpy(b.data(), lv[0].sum.data(), sizeof(float) * std::size_t(n), cudaMemcpyDeviceToDevice));

  // Conjugate gradients, as on the CPU.
  HDRF_CUDA_CHECK(cudaMemcpy(x.data(), log_lum.data(), sizeof(float) * std::size_t(n), cudaMemcpyDeviceToDevice));
  solver.Apply(x.data(), ap.data());
  {
    float *rp = r.data(), *pp = p.data();
    const float *bp = b.data(), *app = ap.data();
    par::ForEach(par::Gpu{}, n, [=] __device__(int i) { rp[i] = bp[i] - app[i], pp[i] = rp[i]; });
  }
  HDRF_CUDA_CHECK(cudaMemcpy(best.data(), x.data(), sizeof(float) * std::size_t(n), cudaMemcpyDeviceToDevice));
  const double bb = std::max(solver.Dot(b.data(), b.data(), n), 1e-30);
  double rr = solver.Dot(r.data(), r.data(), n), best_rr = rr;
  const double tol2 = o.tolerance * o.tolerance;
  int it = 0;
  for (; it < o.iterations && rr / bb > tol2; ++it) {
    solver.Apply(p.data(), ap.data());
    const double pap = solver.Dot(p.data(), ap.data(), n);
    if (pap == 0) break;
    const float alpha = float(rr / pap);
    float *xp = x.data(), *rp = r.data();
    const float *pp = p.data(), *app = ap.data();
    par::ForEach(par::Gpu{}, n, [=] __device__(int i) {
      xp[i] += alpha * pp[i];
      rp[i] -= alpha * app[i];
    });
    const double rr_new = solver.Dot(r.data(), r.data(), n);
    if (rr_new < best_rr) {
      best_rr = rr_new;
      HDRF_CUDA_CHECK(cudaMemcpyAsync(best.data(), x.data(), sizeof(float) * std::size_t(n), cudaMemcpyDeviceToDevice, 0));
    }
    const float beta = float(rr_new / rr);
    rr = rr_new;
    float* pw = p.data();
    const float* rc = r.data();
    par::ForEach(par::Gpu{}, n, [=] __device__(int i) { pw[i] = rc[i] + beta * pw[i]; });
  }
  if (best_rr < rr) {
    HDRF_CUDA_CHECK(cudaMemcpy(x.data(), best.data(), sizeof(float) * std::size_t(n), cudaMemcpyDeviceToDevice));
    rr = best_rr;
  }
  res.iterations = it;
  res.residual = std::sqrt(rr / bb);
  res.converged = rr / bb <= tol2;

  std::vector<float> hx(count);
  std::vector<std::uint8_t> hv(count);
  x.Download(hx.data());
  valid.Download(hv.data());
  float l_lo = 0, l_hi = 0;
  Quantiles(hx, hv, 0.001, 0.999, &l_lo, &l_hi);
  float span = 0;
  DisplaySpan(l_lo, l_hi, &l_lo, &span);
  const float sat = float(o.saturation);
  DeviceBuffer<Float3>& d_out = m.out;
  {
    const Float3* c = rgb.data();
    const float* xs = x.data();
    const unsigned char* v = valid.data();
    Float3* op = d_out.data();
    par::ForEach(par::Gpu{}, n, [=] __device__(int i) {
      op[i] = v[i] ? DisplayPixel(c[i], xs[i], l_lo, span, clip, sat) : Float3{0, 0, 0};
    });
  }
  d_out.Download(out.data());
  return res;
}

}  // namespace hdrf::tonemap::m06
