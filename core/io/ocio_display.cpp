#include "io/ocio_display.h"

#include <OpenColorIO/OpenColorIO.h>

#include <algorithm>
#include <cmath>
#include <sstream>

#include "common/error.h"

namespace OCIO = OCIO_NAMESPACE;

namespace hdrf::io {

struct OcioDisplay::Impl {
  OCIO::ConstConfigRcPtr config;
  OCIO::ConstCPUProcessorRcPtr cpu;
  std::string display, view;

  void Init(const std::string& source, const std::string& want_display, const std::string& want_view) {
    try {
      config->validate();
      display = want_display.empty() ? config->getDefaultDisplay() : want_display;
      bool found = false;
      for (int i = 0; i < config->getNumDisplays(); ++i) found |= display == config->getDisplay(i);
      if (!found) throw InputError(source, "has no display '" + display + "'");
      view = want_view.empty() ? config->getDefaultView(display.c_str()) : want_view;
      found = false;
      for (int i = 0; i < config->getNumViews(display.c_str()); ++i) found |= view == config->getView(display.c_str(), i);
      if (!found) throw InputError(source, "display '" + display + "' has no view '" + view + "'");
      auto t = OCIO::DisplayViewTransform::Create();
      t->setSrc(OCIO::ROLE_SCENE_LINEAR);
      t->setDisplay(display.c_str());
      t->setView(view.c_str());
      cpu = config->getProcessor(t)->getDefaultCPUProcessor();
    } catch (const OCIO::Exception& e) {
      throw InputError(source, std::string("OpenColorIO config: ") + e.what());
    }
  }
};

OcioDisplay::OcioDisplay(const std::string& display, const std::string& view) : impl_(std::make_unique<Impl>()) {
  std::istringstream in(BuiltinOcioConfig());
  try {
    impl_->config = OCIO::Config::CreateFromStream(in);
  } catch (const OCIO::Exception& e) {
    throw Error(std::string("built-in OpenColorIO config: ") + e.what());
  }
  impl_->Init("built-in OpenColorIO config", display, view);
}

OcioDisplay::OcioDisplay(const std::filesystem::path& file, const std::string& display, const std::string& view)
    : impl_(std::make_unique<Impl>()) {
  if (!std::filesystem::is_regular_file(file)) throw InputError(file, "no such OpenColorIO config file");
  try {
    impl_->config = OCIO::Config::CreateFromFile(file.string().c_str());
  } catch (const OCIO::Exception& e) {
    throw InputError(file, std::string("cannot read the OpenColorIO config: ") + e.what());
  }
  impl_->Init(file.string(), display, view);
}

OcioDisplay::~OcioDisplay() = default;

const std::string& OcioDisplay::display() const { return impl_->display; }
const std::string& OcioDisplay::view() const { return impl_->view; }

void OcioDisplay::Apply(float* rgb, long pixels) const {
  if (pixels <= 0) return;
  OCIO::PackedImageDesc desc(rgb, pixels, 1, 3);
  impl_->cpu->apply(desc);
}

std::vector<Rgb8> OcioDisplay::Encode(std::vector<Float3> lin) const {
  if (!lin.empty()) Apply(&lin.data()->x, long(lin.size()));
  std::vector<Rgb8> out(lin.size());
  auto q = [](float v) { return std::uint8_t(std::lround(std::clamp(std::isfinite(v) ? v : 0.f, 0.f, 1.f) * 255.f)); };
  for (std::size_t i = 0; i < lin.size(); ++i) out[i] = {q(lin[i].x), q(lin[i].y), q(lin[i].z)};
  return out;
}

ColorImage OcioDisplay::Quantise(const Image<Float3>& e) {
  ColorImage out(e.width(), e.height());
  auto q = [](float v) { return std::uint8_t(std::lround(std::clamp(std::isfinite(v) ? v : 0.f, 0.f, 1.f) * 255.f)); };
  for (std::size_t i = 0; i < e.size(); ++i) out[i] = {q(e[i].x), q(e[i].y), q(e[i].z)};
  return out;
}

}  // namespace hdrf::io
