// The 3-D inspection view: VTK rendering hosted in a Qt 6 QOpenGLWidget through
// vtkGenericOpenGLRenderWindow (Debian's VTK Qt module is built for Qt 5 and is never
// linked). Shows the growing mesh with tone-mapped HDR colour, the camera trajectory and
// the current frustum; trackball orbit (left), pan (middle or shift+left), zoom (wheel).
#pragma once

#include <Eigen/Core>
#include <QOpenGLWidget>
#include <array>
#include <memory>
#include <vector>

#include "common/camera.h"
#include "common/image.h"
#include "common/se3.h"
#include "mesh/mesh.h"

class QLabel;

namespace hdrf::gui {

class VtkView : public QOpenGLWidget {
  Q_OBJECT
 public:
  explicit VtkView(QWidget* parent = nullptr);
  ~VtkView() override;

  // The mesh with one display colour per vertex.
  void SetMesh(const mesh::Mesh& m, const std::vector<Rgb8>& colours);
  void SetTrajectory(const std::vector<Pose>& poses, const PinholeCamera& cam);
  // The region the volume has allocated (world box); an empty box hides it.
  void SetRegion(const Float3& lo, const Float3& hi);
  std::array<Float3, 2> region() const { return region_; }
  void ResetView();
  std::size_t mesh_triangles() const { return triangles_; }
  // The trajectory and region move with every frame of a scan; the view draws them again at
  // most this often (a redraw of a large surface is the costliest thing the window does;
  // a new surface, a reset view and the mouse redraw at once).
  void SetTrajectoryRefreshMs(int ms) { trajectory_refresh_ms_ = ms; }
  int redraws() const { return redraws_; }  // scene redraws so far
  // The last rendered frame (for tests and screenshots).
  QImage Capture();

  // Sets the default OpenGL surface format VTK needs; call before QApplication exists.
  static void SetDefaultSurfaceFormat();

 protected:
  void initializeGL() override;
  void resizeGL(int w, int h) override;
  void paintGL() override;
  void mousePressEvent(QMouseEvent* e) override;
  void mouseReleaseEvent(QMouseEvent* e) override;
  void mouseMoveEvent(QMouseEvent* e) override;
  void wheelEvent(QWheelEvent* e) override;

 private:
  void Cleanup();
  void ChangedByScan();  // dirty; redrawn now or when trajectory_refresh_ms_ has passed
  void SetEventInfo(QMouseEvent* e);
  void UpdateGround(const mesh::Mesh& m);
  static constexpr double kGridStep = 0.5;    // m
  static constexpr double kAxisLength = 0.5;  // m
  struct Impl;
  std::unique_ptr<Impl> d_;
  bool dirty_ = true;
  int trajectory_refresh_ms_ = 500, redraws_ = 0;
  bool redraw_pending_ = false;
  qint64 last_redraw_ms_ = 0;
  bool first_mesh_ = true;
  std::size_t triangles_ = 0;
  std::array<Float3, 2> region_{};
  Pose last_pose_ = Pose::Identity();
  bool has_pose_ = false;
  Eigen::Vector3d up_{0, -1, 0};  // the world's up in the model's frame
  bool floor_found_ = false;
  std::size_t ground_triangles_ = 0;  // mesh size at the last ground estimate
  QLabel* legend_ = nullptr;
};

}  // namespace hdrf::gui
