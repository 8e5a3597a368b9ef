// hdrfusion sensors: the OpenNI2 devices connected, with their serials and profiles.
// hdrfusion record: a live device to a sequence folder (lossless) or an .oni file.
#include <atomic>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <string>

#include "io/output_file.h"
#include "cli/commands.h"
#include "cli/interrupt.h"
#include "cli/progress.h"
#include "sensors/live_source.h"
#include "sensors/profiles.h"
#include "sensors/recorder.h"

namespace hdrf::cli {

namespace fs = std::filesystem;

Command AddSensorsCommand(CLI::App& app) {
  auto* cmd = app.add_subcommand("sensors", "List the connected OpenNI2 cameras, their serials and profiles");
  return {cmd, [] {
    const auto devices = sensors::ListDevices();
    if (devices.empty()) {
      std::printf("no OpenNI2 device is connected\n");
      return 0;
    }
    std::printf("%zu device%s connected (profiles in %s):\n", devices.size(), devices.size() == 1 ? "" : "s",
                sensors::ProfileFolder().string().c_str());
    for (const auto& d : devices) {
      const fs::path profile = d.serial.empty() ? fs::path() : sensors::ProfilePath(d.serial);
      const bool found = !profile.empty() && fs::exists(profile);
      std::printf("  %s (%s)\n    URI     %s\n    serial  %s\n    profile %s\n", d.name.c_str(), d.vendor.c_str(),
                  d.uri.c_str(), d.serial.empty() ? "(unreadable: device in use?)" : d.serial.c_str(),
                  found ? profile.string().c_str()
                        : "none: the built-in Xtion profile is used (its response is not this device's)");
    }
    return 0;
  }};
}

Command AddRecordCommand(CLI::App& app) {
  auto* cmd = app.add_subcommand("record", "Record a live camera to a sequence folder or an .oni file");
  struct Args {
    std::string device, out, mode = "vga", exposure = "auto";
    int frames = 0, gain = 0;
    double seconds = 0;
    bool awb_off = false;
  };
  auto a = std::make_shared<Args>();
  cmd->add_option("--device", a->device, "URI or serial (default: the first device)");
  cmd->add_option("--out", a->out, "New sequence folder, or FILE.oni for an OpenNI2 recording")->required();
  cmd->add_option("--frames", a->frames, "Frames to record")->check(CLI::PositiveNumber);
  cmd->add_option("--seconds", a->seconds, "Seconds to record")->check(CLI::PositiveNumber);
  cmd->add_option("--mode", a->mode, "vga (640x480) or qvga (320x240), 30 Hz")->capture_default_str();
  cmd->add_option("--exposure", a->exposure,
                  "auto, or a fixed exposure in milliseconds (needs the device's profile to give its unit)")
      ->capture_default_str();
  cmd->add_option("--gain", a->gain, "Fixed gain (100 = unity)")->check(CLI::PositiveNumber);
  cmd->add_flag("--awb-off", a->awb_off, "Switch auto white balance off");
  return {cmd, [a] {
    if (a->frames == 0 && a->seconds == 0) throw SettingError("--frames", "give --frames N or --seconds S");
    sensors::LiveOptions o;
    o.device = a->device;
    o.mode = sensors::ParseCaptureMode(a->mode);
    if (a->exposure == "auto") {
      o.auto_exposure = true;
    } else {
      try {
        o.exposure_ms = std::stod(a->exposure);
      } catch (const std::logic_error&) {
        throw SettingError("--exposure", "expected auto or milliseconds, got '" + a->exposure + "'");
      }
      if (!(*o.exposure_ms > 0)) throw SettingError("--exposure", "must be positive");
      o.auto_exposure = false;
    }
    if (a->gain > 0) o.gain = a->gain;
    if (a->awb_off) o.auto_white_balance = false;
    const fs::path out = a->out;
    const bool oni = out.extension() == ".oni";
    if (oni ? fs::exists(out) : (fs::exists(out) && !fs::is_empty(out)))
      throw InputError(out, "exists and is not empty; choose a new name");
    if (!out.parent_path().empty() && !fs::is_directory(out.parent_path()))
      throw InputError(out.parent_path(), "folder does not exist");
    if (oni) io::CheckOutputFile(out, {}, {".oni"});
    else io::CheckOutputFolderEarly(out);

    sensors::LiveFrameSource live(o);
    for (const std::string& w : live.sensor().warnings) std::fprintf(stderr, "record: warning: %s\n", Printable(w).c_str());
    const auto st = live.camera().exposure();
    std::fprintf(stderr, "record: %s, auto exposure %s, white balance %s%s\n", live.description().c_str(),
                 st.auto_exposure ? "on" : "off", st.auto_white_balance ? "auto" : "fixed",
                 st.auto_exposure ? "" : (", exposure " + std::to_string(st.exposure_raw) + " (device unit), gain " +
                                          std::to_string(st.gain)).c_str());
    std::unique_ptr<sensors::SequenceRecorder> seq;
    std::unique_ptr<sensors::OniRecording> rec;
    if (oni)
      rec = std::make_unique<sensors::OniRecording>(out, live.camera(), live.sensor());
    else
      seq = std::make_unique<sensors::SequenceRecorder>(out, live.sensor());
    std::optional<StopOnInterrupt> interrupt;
    interrupt.emplace();
    const auto t0 = std::chrono::steady_clock::now();
    const int total = a->frames > 0 ? a->frames : int(a->seconds * o.mode.fps + 0.5);
    Progress progress("record", total);
    std::string failure;
    long taken = 0;
    const long dropped_before = live.camera().dropped();
    try {
      while (!interrupt->raised() && taken < total) {
        if (a->seconds > 0 &&
            std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() >= a->seconds)
          break;
        sensors::LiveFrame lf = live.NextFrame();
        const auto ms = live.ExposureMs(lf);
        const std::optional<double> gain = lf.GainFactor();
        if (seq) {
          seq->Push(std::move(lf), ms, gain);
          if (seq->failed()) break;
        } else {
          rec->NoteFrame(lf, ms, gain);
        }
        ++taken;
        progress.Step();
      }
    } catch (const std::exception& e) {
      failure = e.what();
    }
    interrupt.reset();
    progress.Done();
    const long device_dropped = live.camera().dropped() - dropped_before;
    if (seq) {
      const sensors::RecordingStats s = seq->Finish();
      std::printf("recorded %ld frames to %s (%.1f MB, %.1f s, %.1f frames/s, %.1f MB/s); dropped %ld by the "
                  "writer, %ld by the device link\n",
                  s.written, out.string().c_str(), s.bytes / 1e6, s.seconds, s.seconds > 0 ? s.written / s.seconds : 0.0,
                  s.seconds > 0 ? s.bytes / 1e6 / s.seconds : 0.0, s.dropped, device_dropped);
      if (!s.error.empty()) failure = s.error + (failure.empty() ? "" : "; " + failure);
    } else {
      rec->Stop();
      std::error_code ec;
      const double mb = double(fs::file_size(out, ec)) / 1e6;
      std::printf("recorded %ld frames to %s (%.1f MB) with %s.exposure.txt and %s.sensor.json; dropped %ld by the "
                  "device link\n",
                  taken, out.string().c_str(), mb, out.filename().string().c_str(), out.filename().string().c_str(),
                  device_dropped);
    }
    if (!failure.empty()) throw Error("recording ended early: " + failure);
    return 0;
  }};
}

}  // namespace hdrf::cli
