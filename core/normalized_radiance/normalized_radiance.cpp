#include "normalized_radiance/normalized_radiance.h"

#include <cmath>

#include "common/error.h"
#include "normalized_radiance/normalized_radiance_driver.h"

namespace hdrf::nr {

void NormalizedRadianceOptions::Check() const {
  if (patch < 3 || patch % 2 == 0) throw SettingError("nr.patch", "must be odd and >= 3");
  if (downsample < 1 || downsample > 8) throw SettingError("nr.downsample", "must be 1 to 8");
  if (!(min_std > 0) || !std::isfinite(min_std)) throw SettingError("nr.min_std", "must be > 0");
}

Image<float> Luminance(const RadianceImage& r) {
  Image<float> out(r.width(), r.height());
  for (std::size_t i = 0; i < r.size(); ++i) out[i] = hdrf::Luminance(r[i]);
  return out;
}

Image<float> NormalizedRadiance(const Image<float>& lum, const NormalizedRadianceOptions& o,
                                Image<float>* mean_out, Image<float>* std_out) {
  o.Check();
  const int w = lum.width(), h = lum.height(), f = o.downsample;
  const int sw = (w + f - 1) / f, sh = (h + f - 1) / f;
  Image<float> cells(sw, sh), mean_s(sw, sh), std_s(sw, sh);
  Image<double> cnt(sw + 1, sh + 1), s1(sw + 1, sh + 1), s2(sw + 1, sh + 1);
  const Scratch scratch{View(cells), View(mean_s), View(std_s), {View(cnt), View(s1), View(s2)}};
  Image<float> out(w, h);
  if (mean_out) *mean_out = Image<float>(w, h);
  if (std_out) *std_out = Image<float>(w, h);
  Normalize(par::Host{}, View(lum), scratch, o, View(out), mean_out ? View(*mean_out) : ImageView<float>{},
            std_out ? View(*std_out) : ImageView<float>{});
  return out;
}

}  // namespace hdrf::nr
