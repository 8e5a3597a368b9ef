#include "gui/vtk_view.h"

#include <algorithm>
#include <chrono>

#include <vtkActor.h>
#include <vtkCallbackCommand.h>
#include <vtkCamera.h>
#include <vtkCellData.h>
#include <vtkCellArray.h>
#include <vtkCommand.h>
#include <vtkFloatArray.h>
#include <vtkGenericOpenGLRenderWindow.h>
#include <vtkIdTypeArray.h>
#include <vtkGenericRenderWindowInteractor.h>
#include <vtkInteractorStyleTrackballCamera.h>
#include <vtkNew.h>
#include <vtkOpenGLState.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkRenderer.h>
#include <vtkUnsignedCharArray.h>

#include <Eigen/Dense>
#include <cmath>

#include "mesh/world_frame.h"

#include <QDateTime>
#include <QLabel>
#include <QMouseEvent>
#include <QOffscreenSurface>
#include <QOpenGLContext>
#include <QOpenGLFramebufferObject>
#include <QOpenGLFunctions>
#include <QPainter>
#include <QSurfaceFormat>
#include <QTimer>
#include <QWheelEvent>

namespace hdrf::gui {

struct VtkView::Impl {
  vtkNew<vtkGenericOpenGLRenderWindow> window;
  vtkNew<vtkRenderer> renderer;
  vtkNew<vtkGenericRenderWindowInteractor> interactor;
  vtkNew<vtkInteractorStyleTrackballCamera> style;
  vtkNew<vtkPolyData> mesh, path, frustum, region, grid, axes;
  vtkNew<vtkPolyDataMapper> mesh_mapper, path_mapper, frustum_mapper, region_mapper, grid_mapper, axes_mapper;
  vtkNew<vtkActor> mesh_actor, path_actor, frustum_actor, region_actor, grid_actor, axes_actor;
  vtkNew<vtkCallbackCommand> make_current, is_current, frame;
};

void VtkView::SetDefaultSurfaceFormat() {
  QSurfaceFormat f;
  f.setRenderableType(QSurfaceFormat::OpenGL);
  f.setVersion(3, 2);
  f.setProfile(QSurfaceFormat::CoreProfile);
  f.setRedBufferSize(8);
  f.setGreenBufferSize(8);
  f.setBlueBufferSize(8);
  f.setAlphaBufferSize(8);
  f.setDepthBufferSize(24);
  f.setStencilBufferSize(0);
  f.setSamples(0);
  QSurfaceFormat::setDefaultFormat(f);
}

VtkView::VtkView(QWidget* parent) : QWidget(parent), d_(std::make_unique<Impl>()) {
  setMinimumSize(200, 150);
  setFocusPolicy(Qt::StrongFocus);
  setAttribute(Qt::WA_OpaquePaintEvent);  // paintEvent covers every pixel
  d_->window->SetReadyForRendering(false);
  d_->window->SetMultiSamples(0);  // software GL: no multisampling
  d_->window->AddRenderer(d_->renderer);
  d_->renderer->SetBackground(0.12, 0.12, 0.14);
  d_->interactor->SetRenderWindow(d_->window);
  d_->interactor->SetInteractorStyle(d_->style);
  // The render window asks the view to make its context current, whether it is, and
  // announces finished frames (the interactor draws on its own: that frame is read back).
  d_->make_current->SetClientData(this);
  d_->make_current->SetCallback([](vtkObject*, unsigned long, void* self, void*) {
    static_cast<VtkView*>(self)->MakeCurrent();
  });
  d_->is_current->SetClientData(this);
  d_->is_current->SetCallback([](vtkObject*, unsigned long, void* self, void* call) {
    auto* w = static_cast<VtkView*>(self);
    *static_cast<bool*>(call) = w->context_ && QOpenGLContext::currentContext() == w->context_.get();
  });
  d_->frame->SetClientData(this);
  d_->frame->SetCallback([](vtkObject*, unsigned long, void* self, void*) {
    auto* w = static_cast<VtkView*>(self);
    if (w->drawing_) return;
    w->read_pending_ = true;
    w->update();
  });
  d_->window->AddObserver(vtkCommand::WindowMakeCurrentEvent, d_->make_current);
  d_->window->AddObserver(vtkCommand::WindowIsCurrentEvent, d_->is_current);
  d_->window->AddObserver(vtkCommand::WindowFrameEvent, d_->frame);
  // Actors: mesh (vertex colours), trajectory (yellow), frustum (red), the region the
  // volume has allocated (a light blue box).
  d_->mesh_mapper->SetInputData(d_->mesh);
  d_->mesh_mapper->SetScalarModeToUsePointData();
  d_->mesh_actor->SetMapper(d_->mesh_mapper);
  d_->renderer->AddActor(d_->mesh_actor);
  const auto lines = [this](vtkPolyData* data, vtkPolyDataMapper* mapper, vtkActor* actor, double r, double g, double b,
                            float width) {
    mapper->SetInputData(data);
    mapper->ScalarVisibilityOff();
    actor->SetMapper(mapper);
    actor->GetProperty()->SetColor(r, g, b);
    actor->GetProperty()->SetLineWidth(width);
    d_->renderer->AddActor(actor);
  };
  lines(d_->path, d_->path_mapper, d_->path_actor, 1.0, 0.85, 0.2, 2);
  lines(d_->frustum, d_->frustum_mapper, d_->frustum_actor, 1.0, 0.3, 0.25, 2);
  lines(d_->region, d_->region_mapper, d_->region_actor, 0.45, 0.7, 1.0, 1);
  lines(d_->grid, d_->grid_mapper, d_->grid_actor, 0.42, 0.42, 0.46, 1);
  lines(d_->axes, d_->axes_mapper, d_->axes_actor, 1, 1, 1, 3);
  d_->axes_mapper->ScalarVisibilityOn();  // one colour per axis
  d_->axes_mapper->SetScalarModeToUseCellData();
  // Surfaces read by their shading as well as their colour: some ambient light keeps faces
  // turned away from the headlight from going black.
  d_->mesh_actor->GetProperty()->SetAmbient(0.3);
  d_->mesh_actor->GetProperty()->SetDiffuse(0.7);
  d_->renderer->TwoSidedLightingOn();
  // What the lines mean, over the view's corner.
  legend_ = new QLabel(this);
  legend_->setObjectName("view3d_legend");
  legend_->setTextFormat(Qt::RichText);
  legend_->setAttribute(Qt::WA_TransparentForMouseEvents);
  legend_->setStyleSheet("QLabel { background: rgba(0,0,0,150); color: #dddddd; padding: 3px; }");
  legend_->setText(tr("<span style='color:#6b6b75'>&#9632;</span> floor grid, %1 m squares &nbsp; "
                      "axes: <span style='color:#ff5050'>x</span> <span style='color:#50e050'>y</span> "
                      "<span style='color:#6090ff'>up</span>, %2 m<br>"
                      "<span style='color:#ffd933'>&#9632;</span> camera path &nbsp; "
                      "<span style='color:#ff4d40'>&#9632;</span> camera now &nbsp; "
                      "<span style='color:#73b3ff'>&#9632;</span> region the volume holds")
                       .arg(kGridStep)
                       .arg(kAxisLength));
  legend_->adjustSize();
  legend_->move(6, 6);
}

// The floor grid and the axes of the world frame: the floor's plane (or, before a floor is
// seen, the plane 1.5 m below the first camera) seen from the model's frame.
void VtkView::UpdateGround(const mesh::Mesh& m) {
  const mesh::WorldFrame wf = mesh::EstimateWorldFrame(m);
  floor_found_ = wf.floor_found;
  ground_triangles_ = m.triangles.size();
  Eigen::Matrix4d to_model = wf.transform.inverse();  // model <- world (Z up, floor at 0)
  if (!wf.floor_found) {
    Eigen::Matrix4d down = Eigen::Matrix4d::Identity();
    down(2, 3) = -1.5;
    to_model = to_model * down;
  }
  const Eigen::Matrix3d r = to_model.topLeftCorner<3, 3>();
  up_ = r.col(2);
  // The mesh's extent in the floor's plane, rounded out to whole squares plus one.
  const Eigen::Matrix4d to_world = to_model.inverse();
  double lo[2] = {-1, -1}, hi[2] = {1, 1};
  for (const Float3& p : m.position) {
    const Eigen::Vector4d w = to_world * Eigen::Vector4d(p.x, p.y, p.z, 1);
    for (int k = 0; k < 2; ++k) lo[k] = std::min(lo[k], w[k]), hi[k] = std::max(hi[k], w[k]);
  }
  for (int k = 0; k < 2; ++k) {
    lo[k] = (std::floor(lo[k] / kGridStep) - 1) * kGridStep;
    hi[k] = (std::ceil(hi[k] / kGridStep) + 1) * kGridStep;
  }
  const auto model = [&](double x, double y, double z) {
    const Eigen::Vector4d q = to_model * Eigen::Vector4d(x, y, z, 1);
    return Eigen::Vector3d(q.head<3>());
  };
  vtkNew<vtkPoints> pts;
  vtkNew<vtkCellArray> lines;
  const auto segment = [&](vtkPoints* into, vtkCellArray* cells, const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
    const vtkIdType i = into->InsertNextPoint(a.x(), a.y(), a.z());
    into->InsertNextPoint(b.x(), b.y(), b.z());
    const vtkIdType e[2] = {i, i + 1};
    cells->InsertNextCell(2, e);
  };
  const int nx = int(std::lround((hi[0] - lo[0]) / kGridStep)), ny = int(std::lround((hi[1] - lo[1]) / kGridStep));
  for (int i = 0; i <= nx && nx < 400; ++i)
    segment(pts, lines, model(lo[0] + i * kGridStep, lo[1], 0), model(lo[0] + i * kGridStep, hi[1], 0));
  for (int j = 0; j <= ny && ny < 400; ++j)
    segment(pts, lines, model(lo[0], lo[1] + j * kGridStep, 0), model(hi[0], lo[1] + j * kGridStep, 0));
  d_->grid->SetPoints(pts);
  d_->grid->SetLines(lines);
  d_->grid->Modified();
  vtkNew<vtkPoints> apts;
  vtkNew<vtkCellArray> alines;
  vtkNew<vtkUnsignedCharArray> colours;
  colours->SetNumberOfComponents(3);
  const Eigen::Vector3d o = model(0, 0, 0.002);
  segment(apts, alines, o, model(kAxisLength, 0, 0.002));
  colours->InsertNextTuple3(255, 80, 80);
  segment(apts, alines, o, model(0, kAxisLength, 0.002));
  colours->InsertNextTuple3(80, 224, 80);
  segment(apts, alines, o, model(0, 0, kAxisLength));
  colours->InsertNextTuple3(96, 144, 255);
  d_->axes->SetPoints(apts);
  d_->axes->SetLines(alines);
  d_->axes->GetCellData()->SetScalars(colours);
  d_->axes->Modified();
}

void VtkView::SetRegion(const Float3& lo, const Float3& hi) {
  vtkNew<vtkPoints> pts;
  vtkNew<vtkCellArray> lines;
  region_ = {lo, hi};
  if (hi.x > lo.x && hi.y > lo.y && hi.z > lo.z) {
    for (int i = 0; i < 8; ++i)
      pts->InsertNextPoint(i & 1 ? hi.x : lo.x, i & 2 ? hi.y : lo.y, i & 4 ? hi.z : lo.z);
    // The 12 edges: corners differing in one coordinate bit.
    for (int i = 0; i < 8; ++i)
      for (int bit : {1, 2, 4})
        if (!(i & bit)) {
          const vtkIdType e[2] = {i, i | bit};
          lines->InsertNextCell(2, e);
        }
  }
  d_->region->SetPoints(pts);
  d_->region->SetLines(lines);
  d_->region->Modified();
  ChangedByScan();
}

void VtkView::ChangedByScan() {
  dirty_ = true;
  if (redraw_pending_) return;
  const qint64 wait = last_redraw_ms_ + trajectory_refresh_ms_ - QDateTime::currentMSecsSinceEpoch();
  if (wait <= 0) {
    update();
    return;
  }
  redraw_pending_ = true;
  QTimer::singleShot(int(wait), this, [this] {
    redraw_pending_ = false;
    update();
  });
}

VtkView::~VtkView() {
  if (context_ && MakeCurrent()) {
    Cleanup();
    fbo_.reset();
    context_->doneCurrent();
  }
}

bool VtkView::MakeCurrent() {
  if (!context_ && gl_error_.isEmpty()) {
    // The default format (SetDefaultSurfaceFormat): OpenGL 3.2 core, as VTK needs.
    auto ctx = std::make_unique<QOpenGLContext>();
    auto surface = std::make_unique<QOffscreenSurface>();
    if (!ctx->create()) {
      gl_error_ = tr("The 3-D view needs OpenGL 3.2, which this display does not offer");
      return false;
    }
    surface->setFormat(ctx->format());
    surface->create();
    if (!surface->isValid() || !ctx->makeCurrent(surface.get())) {
      gl_error_ = tr("The 3-D view cannot draw: no offscreen OpenGL surface on this display");
      return false;
    }
    context_ = std::move(ctx);
    surface_ = std::move(surface);
    d_->window->SetOwnContext(false);
    d_->window->SetFrameBlitModeToNoBlit();
    d_->window->SetReadyForRendering(true);
    d_->window->OpenGLInitContext();
    d_->interactor->Initialize();
    resizeEvent(nullptr);
    return true;
  }
  if (!context_) return false;
  if (QOpenGLContext::currentContext() != context_.get() && !context_->makeCurrent(surface_.get())) return false;
  return true;
}

void VtkView::Cleanup() {
  if (d_->window->GetReadyForRendering()) {
    d_->window->Finalize();
    d_->window->SetReadyForRendering(false);
  }
}

void VtkView::resizeEvent(QResizeEvent*) {
  if (!context_) return;
  const qreal r = RenderRatio();
  const int w = std::max(1, int(width() * r)), h = std::max(1, int(height() * r));
  d_->window->SetSize(w, h);
  d_->interactor->UpdateSize(w, h);
  dirty_ = true;
}

void VtkView::Draw() {
  if (!MakeCurrent()) return;
  const auto t0 = std::chrono::steady_clock::now();
  drawing_ = true;
  d_->window->Render();
  drawing_ = false;
  ReadBack();
  last_redraw_wall_ms_ = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  redraw_ms_ += last_redraw_wall_ms_;
  ++redraws_;
  last_redraw_ms_ = QDateTime::currentMSecsSinceEpoch();
  dirty_ = false;
}

void VtkView::ReadBack() {
  if (!MakeCurrent()) return;
  const int* s = d_->window->GetSize();
  if (!fbo_ || fbo_->width() != s[0] || fbo_->height() != s[1])
    fbo_ = std::make_unique<QOpenGLFramebufferObject>(s[0], s[1]);
  // VTK's last frame into the view's framebuffer, made opaque, then to host memory.
  vtkOpenGLState* st = d_->window->GetState();
  st->vtkglBindFramebuffer(GL_DRAW_FRAMEBUFFER, fbo_->handle());
  d_->window->BlitDisplayFramebuffer(0, 0, 0, s[0], s[1], 0, 0, s[0], s[1], GL_COLOR_BUFFER_BIT, GL_NEAREST);
  st->vtkglBindFramebuffer(GL_FRAMEBUFFER, fbo_->handle());
  st->vtkglColorMask(false, false, false, true);
  st->vtkglClearColor(0, 0, 0, 1);
  st->vtkglClear(GL_COLOR_BUFFER_BIT);
  st->vtkglColorMask(true, true, true, true);
  // OpenGL's rows run bottom to top; a QImage's top to bottom: flipped, the view is upright.
  image_ = fbo_->toImage(true);
  st->vtkglBindFramebuffer(GL_FRAMEBUFFER, 0);
  image_.setDevicePixelRatio(RenderRatio());
  read_pending_ = false;
}

void VtkView::paintEvent(QPaintEvent*) {
  if (dirty_) Draw();
  else if (read_pending_) ReadBack();
  QPainter p(this);
  if (!gl_error_.isEmpty()) {
    p.fillRect(rect(), QColor(30, 30, 36));
    p.setPen(QColor(230, 200, 120));
    p.drawText(rect().adjusted(12, 12, -12, -12), Qt::AlignCenter | Qt::TextWordWrap, gl_error_);
    return;
  }
  if (image_.isNull()) {
    p.fillRect(rect(), QColor(31, 31, 36));
    return;
  }
  if (scale_ < 1) p.setRenderHint(QPainter::SmoothPixmapTransform);
  p.drawImage(QPoint(0, 0), image_);
}

void VtkView::SetMesh(const mesh::Mesh& m, const std::vector<Rgb8>& colours) {
  vtkNew<vtkPoints> pts;
  pts->SetDataTypeToFloat();
  pts->SetNumberOfPoints(vtkIdType(m.position.size()));
  vtkNew<vtkFloatArray> normals;
  normals->SetNumberOfComponents(3);
  normals->SetNumberOfTuples(vtkIdType(m.position.size()));
  vtkNew<vtkUnsignedCharArray> rgb;
  rgb->SetName("Colors");
  rgb->SetNumberOfComponents(3);
  rgb->SetNumberOfTuples(vtkIdType(m.position.size()));
  for (std::size_t i = 0; i < m.position.size(); ++i) {
    pts->SetPoint(vtkIdType(i), m.position[i].x, m.position[i].y, m.position[i].z);
    normals->SetTuple3(vtkIdType(i), m.normal[i].x, m.normal[i].y, m.normal[i].z);
    const Rgb8 c = i < colours.size() ? colours[i] : Rgb8{180, 180, 180};
    rgb->SetTuple3(vtkIdType(i), c.r, c.g, c.b);
  }
  // Triangles as one offsets array and one connectivity array (no per-cell insertion).
  vtkNew<vtkIdTypeArray> offsets, conn;
  offsets->SetNumberOfValues(vtkIdType(m.triangles.size()) + 1);
  conn->SetNumberOfValues(3 * vtkIdType(m.triangles.size()));
  for (std::size_t i = 0; i < m.triangles.size(); ++i) {
    offsets->SetValue(vtkIdType(i), 3 * vtkIdType(i));
    for (int k = 0; k < 3; ++k) conn->SetValue(3 * vtkIdType(i) + k, m.triangles[i][std::size_t(k)]);
  }
  offsets->SetValue(vtkIdType(m.triangles.size()), 3 * vtkIdType(m.triangles.size()));
  vtkNew<vtkCellArray> tris;
  tris->SetData(offsets, conn);
  d_->mesh->SetPoints(pts);
  d_->mesh->SetPolys(tris);
  d_->mesh->GetPointData()->SetScalars(rgb);
  d_->mesh->GetPointData()->SetNormals(normals);
  d_->mesh->Modified();
  triangles_ = m.triangles.size();
  // The ground follows the model until a floor is seen (then it stays put), re-estimated
  // as the mesh grows by half.
  if (triangles_ > 0 && (ground_triangles_ == 0 || (!floor_found_ && triangles_ > ground_triangles_ * 3 / 2)))
    UpdateGround(m);
  if (first_mesh_ && triangles_ > 0) {
    first_mesh_ = false;
    ResetView();
  }
  dirty_ = true;
  update();
}

void VtkView::SetTrajectory(std::span<const Pose> poses, const PinholeCamera& cam) {
  vtkNew<vtkPoints> pts;
  vtkNew<vtkCellArray> line;
  if (!poses.empty()) {
    line->InsertNextCell(vtkIdType(poses.size()));
    for (std::size_t i = 0; i < poses.size(); ++i) {
      const Vec3 t = poses[i].translation();
      pts->InsertNextPoint(t.x(), t.y(), t.z());
      line->InsertCellPoint(vtkIdType(i));
    }
  }
  d_->path->SetPoints(pts);
  d_->path->SetLines(line);
  d_->path->Modified();
  // Frustum of the current pose: the image corners at 0.3 m.
  vtkNew<vtkPoints> fp;
  vtkNew<vtkCellArray> fl;
  if (!poses.empty()) {
    last_pose_ = poses.back();
    has_pose_ = true;
  }
  if (!poses.empty() && cam.Valid()) {
    const Pose& T = poses.back();
    const double z = 0.3;
    const double u[4] = {0, double(cam.width - 1), double(cam.width - 1), 0};
    const double v[4] = {0, 0, double(cam.height - 1), double(cam.height - 1)};
    const Vec3 o = T.translation();
    fp->InsertNextPoint(o.x(), o.y(), o.z());
    for (int k = 0; k < 4; ++k) {
      const Vec3 p = T * Vec3((u[k] - cam.cx) / cam.fx * z, (v[k] - cam.cy) / cam.fy * z, z);
      fp->InsertNextPoint(p.x(), p.y(), p.z());
    }
    for (int k = 1; k <= 4; ++k) {
      const vtkIdType a[2] = {0, k}, b[2] = {k, k % 4 + 1};
      fl->InsertNextCell(2, a);
      fl->InsertNextCell(2, b);
    }
  }
  d_->frustum->SetPoints(fp);
  d_->frustum->SetLines(fl);
  d_->frustum->Modified();
  ChangedByScan();
}

void VtkView::ResetView() {
  vtkCamera* c = d_->renderer->GetActiveCamera();
  if (has_pose_) {
    // Where the operator stands: a step behind and above the scanning camera, looking where
    // it looks, upright.
    const Vec3 eye = last_pose_.translation();
    Vec3 forward = last_pose_ * Vec3(0, 0, 1) - eye;
    const Vec3 up(up_.x(), up_.y(), up_.z());
    const Vec3 from = eye - 0.8 * forward + 0.4 * up, at = eye + 1.5 * forward;
    c->SetPosition(from.x(), from.y(), from.z());
    c->SetFocalPoint(at.x(), at.y(), at.z());
    c->SetViewUp(up.x(), up.y(), up.z());
    c->SetViewAngle(60);
    d_->renderer->ResetCameraClippingRange();
  } else {
    // Looking along the first camera's axis (y down in camera coordinates: up is -y).
    c->SetPosition(0, 0, -1);
    c->SetFocalPoint(0, 0, 1);
    c->SetViewUp(0, -1, 0);
    d_->renderer->ResetCamera();
  }
  dirty_ = true;
  update();
}

QImage VtkView::Capture() {
  Draw();
  QImage shot = image_;
  shot.setDevicePixelRatio(1);
  return shot;
}

void VtkView::SetRenderScale(double scale) {
  scale = std::clamp(scale, 0.25, 1.0);
  if (scale == scale_) return;
  scale_ = scale;
  resizeEvent(nullptr);
  update();
}

qreal VtkView::RenderRatio() const { return devicePixelRatioF() * scale_; }

void VtkView::SetEventInfo(QMouseEvent* e) {
  const qreal r = RenderRatio();
  d_->interactor->SetEventInformationFlipY(int(e->position().x() * r), int(e->position().y() * r),
                                           (e->modifiers() & Qt::ControlModifier) ? 1 : 0,
                                           (e->modifiers() & Qt::ShiftModifier) ? 1 : 0);
}

void VtkView::mousePressEvent(QMouseEvent* e) {
  SetEventInfo(e);
  switch (e->button()) {
    case Qt::LeftButton: d_->interactor->InvokeEvent(vtkCommand::LeftButtonPressEvent); break;
    case Qt::MiddleButton: d_->interactor->InvokeEvent(vtkCommand::MiddleButtonPressEvent); break;
    case Qt::RightButton: d_->interactor->InvokeEvent(vtkCommand::RightButtonPressEvent); break;
    default: break;
  }
}
void VtkView::mouseReleaseEvent(QMouseEvent* e) {
  SetEventInfo(e);
  switch (e->button()) {
    case Qt::LeftButton: d_->interactor->InvokeEvent(vtkCommand::LeftButtonReleaseEvent); break;
    case Qt::MiddleButton: d_->interactor->InvokeEvent(vtkCommand::MiddleButtonReleaseEvent); break;
    case Qt::RightButton: d_->interactor->InvokeEvent(vtkCommand::RightButtonReleaseEvent); break;
    default: break;
  }
}
void VtkView::mouseMoveEvent(QMouseEvent* e) {
  SetEventInfo(e);
  d_->interactor->InvokeEvent(vtkCommand::MouseMoveEvent);
}
void VtkView::wheelEvent(QWheelEvent* e) {
  const qreal r = RenderRatio();
  d_->interactor->SetEventInformationFlipY(int(e->position().x() * r), int(e->position().y() * r));
  d_->interactor->InvokeEvent(e->angleDelta().y() > 0 ? vtkCommand::MouseWheelForwardEvent
                                                       : vtkCommand::MouseWheelBackwardEvent);
}

}  // namespace hdrf::gui
