// The 3-D inspection view: VTK rendering through vtkGenericOpenGLRenderWindow in an OpenGL
// context of the view's own on an offscreen surface (Debian's VTK Qt module is built for
// Qt 5 and is never linked); each redraw is read back into an image the widget paints. The
// window thus stays an ordinary raster window: an OpenGL widget in it would make Qt compose
// the whole window with OpenGL on every repaint of any view, which on software OpenGL costs
// more than the scan can spare. Shows the growing mesh with tone-mapped HDR colour, the
// camera trajectory and the current frustum; trackball orbit (left), pan (middle or
// shift+left), zoom (wheel).
#pragma once

#include <Eigen/Core>
#include <QImage>
#include <QWidget>
#include <array>
#include <memory>
#include <span>
#include <vector>

#include "common/camera.h"
#include "common/image.h"
#include "common/se3.h"
#include "mesh/mesh.h"

class QLabel;
class QOffscreenSurface;
class QOpenGLContext;
class QOpenGLFramebufferObject;

namespace hdrf::gui {

class VtkView : public QWidget {
  Q_OBJECT
 public:
  explicit VtkView(QWidget* parent = nullptr);
  ~VtkView() override;

  // The mesh with one display colour per vertex.
  void SetMesh(const mesh::Mesh& m, const std::vector<Rgb8>& colours);
  void SetTrajectory(std::span<const Pose> poses, const PinholeCamera& cam);
  // The region the volume has allocated (world box); an empty box hides it.
  void SetRegion(const Float3& lo, const Float3& hi);
  std::array<Float3, 2> region() const { return region_; }
  void ResetView();
  std::size_t mesh_triangles() const { return triangles_; }
  // The trajectory and region move with every frame of a scan; the view draws them again at
  // most this often (a redraw of a large surface is the costliest thing the window does;
  // a new surface, a reset view and the mouse redraw at once).
  void SetTrajectoryRefreshMs(int ms) { trajectory_refresh_ms_ = ms; }
  // Renders at this share of the widget's pixels on a side (0.25 .. 1), the image scaled up
  // when painted: a software OpenGL's pixel work drops with its square.
  void SetRenderScale(double scale);
  double render_scale() const { return scale_; }
  int redraws() const { return redraws_; }  // scene redraws so far
  double redraw_ms() const { return redraw_ms_; }  // their wall time in all (software GL's threads included)
  double last_redraw_ms() const { return last_redraw_wall_ms_; }  // the latest one's
  // The scene drawn now (for tests and screenshots).
  QImage Capture();
  // Why the view cannot draw (no usable OpenGL 3.2), or empty.
  QString gl_error() const { return gl_error_; }

  // Sets the default OpenGL surface format VTK needs; call before QApplication exists.
  static void SetDefaultSurfaceFormat();

 protected:
  void paintEvent(QPaintEvent* e) override;
  void resizeEvent(QResizeEvent* e) override;
  void mousePressEvent(QMouseEvent* e) override;
  void mouseReleaseEvent(QMouseEvent* e) override;
  void mouseMoveEvent(QMouseEvent* e) override;
  void wheelEvent(QWheelEvent* e) override;

 private:
  bool MakeCurrent();  // the view's context current (created on first use); false: none
  void Cleanup();
  void Draw();         // the scene rendered and read back into image_
  void ReadBack();     // VTK's last frame into image_
  void ChangedByScan();  // dirty; redrawn now or when trajectory_refresh_ms_ has passed
  void SetEventInfo(QMouseEvent* e);
  void UpdateGround(const mesh::Mesh& m);
  static constexpr double kGridStep = 0.5;    // m
  static constexpr double kAxisLength = 0.5;  // m
  struct Impl;
  std::unique_ptr<Impl> d_;
  std::unique_ptr<QOpenGLContext> context_;
  std::unique_ptr<QOffscreenSurface> surface_;
  std::unique_ptr<QOpenGLFramebufferObject> fbo_;
  QImage image_;
  QString gl_error_;
  bool drawing_ = false;      // inside Draw (VTK's frame events are its own)
  bool read_pending_ = false;  // VTK drew a frame (the interactor) not yet read back
  bool dirty_ = true;
  int trajectory_refresh_ms_ = 1000, redraws_ = 0;
  double redraw_ms_ = 0, last_redraw_wall_ms_ = 0;
  double scale_ = 1;
  qreal RenderRatio() const;  // rendered pixels per logical pixel
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
