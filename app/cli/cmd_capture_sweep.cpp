// hdrfusion capture-sweep: an exposure sweep from a camera to a sweep folder, headless (the
// calibration wizard's Set-up and Capture pages): auto exposure locked and verified,
// exposures planned from the scene, steps checked for motion and flicker, written as they
// come; Ctrl-C keeps what was captured and --resume completes it.
#include <atomic>
#include <cstdio>
#include <filesystem>

#include "io/output_file.h"
#include "cli/commands.h"
#include "cli/interrupt.h"
#include "common/error.h"
#include "io/sweep_capture.h"
#include "sensors/sweep_cameras.h"

namespace hdrf::cli {

namespace fs = std::filesystem;

Command AddCaptureSweepCommand(CLI::App& app) {
  struct Args {
    std::string source = "synthetic", out;
    bool resume = false, keep_auto = false;
    io::SweepPlanOptions plan;
  };
  auto a = std::make_shared<Args>();
  auto* cmd = app.add_subcommand("capture-sweep",
                                 "Capture an exposure sweep for calibration from a camera (live or synthetic)");
  cmd->add_option("--source", a->source,
                  "synthetic[:response=xtion|srgb|linear|gammaG|FILE.json,scene=room|desk|hall,size=WxH,seed=N] or "
                  "openni:[device=URI|SERIAL,mode=vga|qvga,unit=MS,gain=N]")
      ->capture_default_str();
  cmd->add_option("--out", a->out, "Sweep folder to write (absent or empty; with --resume, the one to complete)")
      ->required();
  cmd->add_flag("--resume", a->resume, "Complete an interrupted capture in --out (same camera)");
  cmd->add_option("--step", a->plan.step_stops, "Stops between exposures")->capture_default_str();
  cmd->add_option("--repeats", a->plan.repeats, "Frames per exposure (3 or more for the noise fit)")
      ->capture_default_str();
  cmd->add_option("--min-ms", a->plan.min_ms, "Shortest exposure (0: metered from the scene)")->capture_default_str();
  cmd->add_option("--max-ms", a->plan.max_ms, "Longest exposure (0: metered from the scene)")->capture_default_str();
  cmd->add_option("--max-exposures", a->plan.max_exposures, "At most this many exposures")->capture_default_str();
  cmd->add_option("--retries", a->plan.max_retries, "Re-captures of a step that fails its checks")
      ->capture_default_str();
  cmd->add_flag("--keep-auto", a->keep_auto,
                "Leave auto exposure and white balance as the camera has them (the capture then refuses to "
                "start while they are on)");
  return {cmd, [a] {
    a->plan.Check();
    const fs::path out = a->out;
    if (!a->resume && fs::exists(out) && !(fs::is_directory(out) && fs::is_empty(out)))
      throw InputError(out, "exists and is not empty; choose a new folder (or --resume an interrupted capture)");
    io::CheckOutputFolderEarly(out);
    if (a->resume && !fs::exists(out / "capture.json"))
      throw InputError(out / "capture.json", "is missing: nothing to resume (capture a new sweep without --resume)");
    auto camera = sensors::OpenSweepCamera(a->source);
    std::printf("camera: %s\n", camera->description().c_str());
    if (!a->keep_auto) camera->SetAutomatic(false, false);
    StopOnInterrupt interrupt;  // Ctrl-C: cancel between frames, keeping the complete steps
    auto show = [](const io::CaptureStatus& s) {
      if (!s.note.empty()) std::fprintf(stderr, "  %s\n", s.note.c_str());
      if (s.stage == "capture")
        std::fprintf(stderr, "capture: step %d/%d at %.4g ms, %d frames written\n", s.step + 1, s.steps,
                     s.exposure_ms, s.frames_written);
    };
    std::optional<io::SweepCapture> capture;
    if (a->resume) {
      capture.emplace(io::SweepCapture::Resume(*camera, out));
      const io::CaptureRecord r = io::ReadCaptureRecord(out);
      std::printf("resuming %s: %d of %zu steps were captured\n", out.c_str(), r.steps_done,
                  r.plan.exposures_ms.size());
    } else {
      const io::SweepPlan plan = io::PlanSweep(*camera, a->plan, {}, &interrupt.flag());
      std::printf("plan: %zu exposures from %.4g to %.4g ms, %d frames each\n", plan.exposures_ms.size(),
                  plan.exposures_ms.front(), plan.exposures_ms.back(), plan.options.repeats);
      std::printf("levels covered by the preview: R %.0f %%, G %.0f %%, B %.0f %%\n", 100 * plan.coverage.share[0],
                  100 * plan.coverage.share[1], 100 * plan.coverage.share[2]);
      for (const std::string& w : plan.warnings) std::printf("warning: %s\n", Printable(w).c_str());
      capture.emplace(*camera, plan, out);
    }
    const io::CaptureResult r = capture->Run(show, &interrupt.flag());
    if (r.cancelled) {
      std::printf("cancelled: %d of %d steps (%d frames) kept in %s; complete it with --resume\n", r.steps_done,
                  r.steps, r.frames, out.c_str());
      return 130;
    }
    std::printf("captured %d steps, %d frames (%d steps taken again) to %s\n", r.steps_done, r.frames, r.recaptures,
                out.c_str());
    std::printf("next: hdrfusion calibrate %s --out sensor.json\n", out.c_str());
    return 0;
  }};
}

}  // namespace hdrf::cli
