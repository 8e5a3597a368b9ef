// hdrfusion radiance IMAGE --sensor sensor.json --exposure MS --out OUT.exr
// Converts one colour frame to linear radiance through the calibrated inverse response.
#include <cstdio>
#include <string>

#include "io/output_file.h"
#include "cli/commands.h"
#include "common/error.h"
#include "io/exr.h"
#include "io/image_io.h"
#include "io/sensor_json.h"
#include "radiometry/radiance.h"

namespace hdrf::cli {

Command AddRadianceCommand(CLI::App& app) {
  struct Args {
    std::string image, sensor, out, device = "cpu", response;
    double exposure_ms = 1.0;
  };
  auto a = std::make_shared<Args>();
  auto* cmd = app.add_subcommand(
      "radiance", "Convert a colour image to linear radiance (OpenEXR) through a response");
  cmd->add_option("IMAGE", a->image, "8-bit colour image (PNG)")->required();
  cmd->add_option("--sensor", a->sensor, "sensor.json with response.inverse");
  cmd->add_option("--response", a->response,
                  "Fallback response when --sensor has none: 'srgb'")
      ->check(CLI::IsMember({"srgb"}));
  cmd->add_option("--exposure", a->exposure_ms, "Exposure time in ms (radiance = R / exposure)")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--out", a->out, "Output OpenEXR file")->required();
  cmd->add_option("--device", a->device, "cpu or cuda")->check(CLI::IsMember({"cpu", "cuda"}));
  return {cmd, [a] {
    // Before any work: an output that is an input, or OpenEXR under another format's name.
    io::CheckOutputFile(a->out, {a->image, a->sensor}, {".exr"});
    radiometry::InverseResponse inverse;
    if (!a->sensor.empty() && io::ReadSensorJson(a->sensor).response) {
      inverse = *io::ReadSensorJson(a->sensor).response;
    } else if (a->response == "srgb") {
      inverse = radiometry::InverseResponse::Srgb();
    } else {
      throw Error((a->sensor.empty() ? std::string("no --sensor given")
                                     : a->sensor + ": has no response.inverse") +
                  "; calibrate the camera (hdrfusion calibrate) or pass --response srgb");
    }
    Device device = a->device == "cuda" ? Device::kCuda : Device::kCpu;
    std::string why;
    if (device == Device::kCuda && !CudaAvailable(&why)) {
      std::fprintf(stderr, "hdrfusion: CUDA not usable (%s); running on the CPU\n", why.c_str());
      device = Device::kCpu;
    }
    const ColorImage color = io::ReadColorImage(a->image);
    RadianceImage out;
    radiometry::ConvertToRadiance(color, inverse, float(a->exposure_ms), out, device);
    io::WriteExr(a->out, out, io::ExrPrecision::kFloat);
    std::printf("wrote %s (%dx%d, %s)\n", a->out.c_str(), out.width(), out.height(),
                DeviceName(device));
    return 0;
  }};
}

}  // namespace hdrf::cli
