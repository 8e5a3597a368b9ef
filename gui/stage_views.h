// The studio's 2-D views of a frame's stages (colour and depth as delivered, radiance,
// normalized radiance, confidence, the model's ray-cast radiance and normals), each in a dock
// of the main window: made and laid out once, then filled from each scan snapshot. Hidden
// views are skipped (they cost nothing).
#pragma once

#include <QCoreApplication>
#include <QMap>
#include <QString>
#include <memory>

#include "gui/scan_worker.h"

class QDockWidget;
class QMainWindow;

namespace hdrf::gui {

class ImageView;
class ToneMapper;

class StageViews {
  Q_DECLARE_TR_FUNCTIONS(hdrf::gui::StageViews)

 public:
  // The views by key ("colour", "depth", "radiance", "nr", "confidence", "model_radiance",
  // "model_normals") go into `views`, their docks into `docks` (which may hold other docks).
  StageViews(QMap<QString, ImageView*>& views, QMap<QString, QDockWidget*>& docks) : views_(views), docks_(docks) {}

  // Makes the views as docks of `window`: two columns right of its central widget, what the
  // camera delivers and the radiance made of it, then what the engine derives and the model.
  void Build(QMainWindow* window);
  // The camera's own images: the colour as delivered and the depth (also the live preview).
  void ShowCamera(const std::shared_ptr<const Snapshot>& s);
  // Every view of a scan snapshot (a project just opened has a model but no live frame: the
  // live views keep what they showed).
  void ShowStages(const std::shared_ptr<const Snapshot>& s, ToneMapper& tone);
  // The stage images the views on screen need (not hidden, not behind another tab).
  pipeline::ViewSet Shown() const;

 private:
  QMap<QString, ImageView*>& views_;
  QMap<QString, QDockWidget*>& docks_;
};

}  // namespace hdrf::gui
