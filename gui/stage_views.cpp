#include "gui/stage_views.h"

#include <QDockWidget>
#include <QMainWindow>
#include <algorithm>
#include <cstring>

#include "gui/image_view.h"
#include "gui/stage_images.h"
#include "gui/tone_mapper.h"
#include "io/exr.h"
#include "tonemap/display.h"

namespace hdrf::gui {

void StageViews::Build(QMainWindow* window) {
  struct V {
    const char* key;
    QString title;
    Qt::DockWidgetArea area;
  };
  // Two columns of views right of the 3-D view: what the camera delivers and the radiance
  // made of it, then what the engine derives and the model.
  const V defs[] = {{"colour", tr("Colour (as delivered)"), Qt::RightDockWidgetArea},
                    {"depth", tr("Depth"), Qt::RightDockWidgetArea},
                    {"radiance", tr("Radiance (tone-mapped)"), Qt::RightDockWidgetArea},
                    {"nr", tr("Normalized radiance"), Qt::RightDockWidgetArea},
                    {"confidence", tr("Confidence (PCF)"), Qt::RightDockWidgetArea},
                    {"model_radiance", tr("Model radiance (ray cast)"), Qt::RightDockWidgetArea},
                    {"model_normals", tr("Model normals (ray cast)"), Qt::RightDockWidgetArea}};
  for (const V& d : defs) {
    auto* v = new ImageView(d.title, window);
    auto* dock = new QDockWidget(d.title, window);
    dock->setObjectName(QString("dock_") + d.key);
    dock->setWidget(v);
    dock->setFeatures(QDockWidget::DockWidgetMovable | QDockWidget::DockWidgetFloatable |
                      QDockWidget::DockWidgetClosable);
    window->addDockWidget(d.area, dock);
    views_[d.key] = v;
    docks_[d.key] = dock;
  }
  window->splitDockWidget(docks_["colour"], docks_["confidence"], Qt::Horizontal);
  window->splitDockWidget(docks_["colour"], docks_["depth"], Qt::Vertical);
  window->splitDockWidget(docks_["depth"], docks_["radiance"], Qt::Vertical);
  window->splitDockWidget(docks_["radiance"], docks_["nr"], Qt::Vertical);
  window->splitDockWidget(docks_["confidence"], docks_["model_radiance"], Qt::Vertical);
  window->splitDockWidget(docks_["model_radiance"], docks_["model_normals"], Qt::Vertical);
}

// The camera's own images: the colour as delivered and the depth (also the live preview).
void StageViews::ShowCamera(const std::shared_ptr<const Snapshot>& s) {
  auto visible = [this](const char* k) { return docks_[k]->isVisible(); };
  if (visible("colour")) {
    views_["colour"]->SetImage(FromColor(s->color), [s](int x, int y) {
      const Rgb8 c = s->color(x, y);
      return QStringLiteral("RGB %1 %2 %3 (8-bit)").arg(c.r).arg(c.g).arg(c.b);
    });
  }
  if (visible("depth") && !s->images.depth.empty()) {
    const float hi = std::min(LargestValue(s->images.depth, 0.5f), 8.f);
    const ColorImage cd = tonemap::ColorizeDepth(s->images.depth, 0.f, hi);
    views_["depth"]->SetScaleBar(DepthBar(hi), 0, hi, "m");
    views_["depth"]->SetImage(FromColor(cd), [s](int x, int y) {
      const float z = s->images.depth(x, y);
      return z > 0 ? tr("depth %L1 m").arg(z, 0, 'f', 3) : tr("no depth");
    });
  }
}

pipeline::ViewSet StageViews::Shown() const {
  const auto on = [this](const char* k) { return docks_.value(k)->isVisible() && !views_.value(k)->visibleRegion().isEmpty(); };
  pipeline::ViewSet v;
  v.radiance = on("radiance");
  v.confidence = on("confidence");
  v.nr = on("nr");
  v.depth = on("depth");
  v.render = on("model_radiance") || on("model_normals");
  return v;
}

void StageViews::ShowStages(const std::shared_ptr<const Snapshot>& s, ToneMapper& tone) {
  const auto& im = s->images;
  const double t = s->report.timestamp;  // the frame's own time: the curve filters at the real frame rate
  // 2-D views (hidden docks are skipped: they cost nothing).
  // A project just opened has a model but no live frame: its views keep what they showed.
  auto visible = [this, &im](const char* k) {
    const bool live_view = std::strcmp(k, "model_radiance") != 0 && std::strcmp(k, "model_normals") != 0;
    return docks_[k]->isVisible() && (!live_view || !im.radiance.empty());
  };
  if (!s->color.empty()) ShowCamera(s);
  if (visible("radiance")) {
    views_["radiance"]->SetImage(tone.Map(im.radiance, ToneView::kLive, t), [s](int x, int y) { return RadianceText(s->images.radiance(x, y)); },
                                 [s](const QString& p) { io::WriteExr(p.toStdString(), s->images.radiance); });
  }
  if (visible("nr")) {
    // Normalized radiance: deviations from the local mean in local standard deviations.
    views_["nr"]->SetScaleBar(GreyBar(), -3, 3, tr("std"));
    views_["nr"]->SetImage(Grey(im.nr, -3.f, 3.f, [](float v) { return v != 0.f; }), [s](int x, int y) {
      return QStringLiteral("NR %L1").arg(s->images.nr(x, y), 0, 'f', 3);
    });
  }
  if (visible("confidence")) {
    const float mx = LargestValue(im.confidence, 1e-6f);
    views_["confidence"]->SetScaleBar(GreyBar(), 0, mx, tr("PCF"));
    views_["confidence"]->SetImage(Grey(im.confidence, 0.f, mx, [](float) { return true; }), [s](int x, int y) {
      return tr("PCF %L1 (max channel %L2)")
          .arg(s->images.confidence(x, y), 0, 'f', 3)
          .arg(s->images.max_confidence(x, y), 0, 'f', 3);
    });
  }
  if (visible("model_radiance") && !im.render.radiance.empty()) {
    views_["model_radiance"]->SetImage(
        tone.Map(im.render.radiance, ToneView::kModel, t), [s](int x, int y) { return RadianceText(s->images.render.radiance(x, y)); },
        [s](const QString& p) { io::WriteExr(p.toStdString(), s->images.render.radiance); });
  }
  if (visible("model_normals") && !im.render.normal.empty()) {
    views_["model_normals"]->SetImage(NormalsImage(im.render.normal), [s](int x, int y) {
      const Float3 v = s->images.render.normal(x, y);
      const float d = s->images.render.depth(x, y);
      return d > 0 ? tr("normal %L1 %L2 %L3, depth %L4 m").arg(v.x, 0, 'f', 2).arg(v.y, 0, 'f', 2).arg(v.z, 0, 'f', 2).arg(d, 0, 'f', 3)
                   : tr("no surface");
    });
  }
}

}  // namespace hdrf::gui
