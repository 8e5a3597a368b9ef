#include "sim/auto_exposure.h"

#include <algorithm>
#include <cmath>

#include "common/error.h"
#include "sim/noise.h"

namespace hdrf::sim {

void AeOptions::Check() const {
  auto positive = [](const std::vector<double>& v) {
    return std::all_of(v.begin(), v.end(), [](double x) { return x > 0 && std::isfinite(x); });
  };
  if (mode == AeMode::kFixed && !(fixed_ms > 0)) throw SettingError("--exposure", "must be > 0 ms");
  if (mode == AeMode::kList && (list_ms.empty() || !positive(list_ms)))
    throw SettingError("--exposures", "needs one or more positive exposure times in ms");
  if (mode == AeMode::kFlicker && (flicker_ms.size() < 2 || !positive(flicker_ms)))
    throw SettingError("--ae flicker", "needs at least two positive exposure times");
  if (mode == AeMode::kSmooth &&
      !(min_ms > 0 && max_ms > min_ms && damping > 0 && damping <= 1 && target > 0))
    throw SettingError("--ae smooth", "needs 0 < min < max exposure, 0 < damping <= 1");
}

AeMode ParseAeMode(const std::string& s) {
  if (s == "fixed") return AeMode::kFixed;
  if (s == "smooth") return AeMode::kSmooth;
  if (s == "flicker") return AeMode::kFlicker;
  if (s == "list") return AeMode::kList;
  throw SettingError("--ae", "unknown mode '" + s + "'; choose fixed, smooth, flicker or list");
}

const char* AeModeName(AeMode m) {
  switch (m) {
    case AeMode::kFixed: return "fixed";
    case AeMode::kSmooth: return "smooth";
    case AeMode::kFlicker: return "flicker";
    case AeMode::kList: return "list";
  }
  return "?";
}

AutoExposure::AutoExposure(AeOptions options, std::uint32_t seed)
    : o_(std::move(options)), seed_(seed), current_ms_(o_.fixed_ms) {
  o_.Check();
}

double AutoExposure::Next(int i, double metered) {
  switch (o_.mode) {
    case AeMode::kFixed: return o_.fixed_ms;
    case AeMode::kList: return o_.list_ms[std::size_t(i) % o_.list_ms.size()];
    case AeMode::kFlicker: {
      const int n = int(o_.flicker_ms.size());
      int k = int(Hash(seed_, std::uint32_t(i), 0xf11c4e7u) % std::uint32_t(n));
      if (k == last_flicker_) k = (k + 1 + int(Hash(seed_, std::uint32_t(i), 7u) % std::uint32_t(n - 1))) % n;
      last_flicker_ = k;
      return o_.flicker_ms[std::size_t(k)];
    }
    case AeMode::kSmooth: {
      if (metered > 0) {
        const double wanted = std::clamp(o_.target / metered, o_.min_ms, o_.max_ms);
        current_ms_ *= std::pow(wanted / current_ms_, o_.damping);
        current_ms_ = std::clamp(current_ms_, o_.min_ms, o_.max_ms);
      }
      return current_ms_;
    }
  }
  return o_.fixed_ms;
}

}  // namespace hdrf::sim
