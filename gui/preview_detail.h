// The surface the 3-D view shows while a scan runs. Every voxel's surface (View -> "Full
// surface detail while scanning") or a preview: from every other voxel (a quarter of the
// triangles), and from every fourth (a sixteenth) once the display has redrawn the preview
// slowly kSlowInARow times running (a software OpenGL, or a model too large for the GPU):
// the redraws would otherwise take the processor the scan needs. Each scan starts afresh.
#pragma once

namespace hdrf::gui {

class PreviewDetail {
 public:
  static constexpr double kSlowRedrawMs = 30;  // wall time of one redraw of the preview
  static constexpr int kSlowInARow = 3;        // one slow redraw (a shader compiled) is not enough

  // A scan starts (or the choice changed): the lattice step of its surface while it runs.
  int Start(bool full_detail) {
    step_ = full_detail ? 1 : 2;
    slow_ = 0;
    return step_;
  }
  // The view redrew a preview in `wall_ms`: the step for the surfaces that follow.
  int Redrawn(double wall_ms) {
    if (step_ != 2) return step_;
    slow_ = wall_ms > kSlowRedrawMs ? slow_ + 1 : 0;
    if (slow_ >= kSlowInARow) step_ = 4;
    return step_;
  }
  int step() const { return step_; }
  // The 3-D view's rendered pixels on a side while scanning: half on a slow display.
  double render_scale() const { return step_ == 4 ? 0.5 : 1.0; }

 private:
  int step_ = 2, slow_ = 0;
};

}  // namespace hdrf::gui
