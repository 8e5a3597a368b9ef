// ScanWorker's exports of the scan: mesh (PLY), trajectory (TUM), render (OpenEXR) and the
// textured HDR asset, each cancellable.
#include "gui/scan_worker.h"

#include "gui/language/language.h"
#include "io/exr.h"
#include "io/ocio_display.h"
#include "io/ply.h"
#include "io/tum.h"

namespace hdrf::gui {

void ScanWorker::ExportMesh(const QString& path, const QString& tone) {
  cancel_export_ = false;
  if (!job_) {
    emit exportDone(false, tr("Nothing to export: no model"));
    return;
  }
  try {
    const mesh::Mesh m = job_->session().pipeline().ExtractMesh([this](double f) {
      emit exportProgress(0.9 * f);
      return !cancel_export_;
    });
    if (cancel_export_) throw Cancelled();
    const tonemap::Spec spec = tonemap::ParseSpec(tone.toStdString());
    const auto& decl = tonemap::FindOperator(spec.op);
    auto op = decl.make(tonemap::ResolveParams(decl, spec.values), Device::kCpu);
    Image<Float3> shown;
    op->Map(job_->session().pipeline().Render(job_->session().pipeline().pose()).radiance, shown, tonemap::FrameTime::Still());
    const std::vector<Rgb8> display = io::OcioDisplay().Encode(op->MapList(m.radiance));
    // Through a temporary file: nothing half-written.
    io::WritePly(path.toStdString(), m, display.size() == m.position.size() ? &display : nullptr);
    emit exportProgress(1.0);
    emit exportDone(true, tr("Wrote %1 (%2 vertices, %3 triangles)").arg(path).arg(m.position.size()).arg(m.triangles.size()));
  } catch (const Cancelled&) {
    emit exportDone(false, tr("Mesh export cancelled; nothing was written"));
  } catch (const std::exception& e) {
    emit exportDone(false, tr("Mesh export: %1").arg(QString::fromStdString(e.what())));
  }
}

void ScanWorker::ExportTrajectory(const QString& path) {
  try {
    if (!job_) throw Error("no scan");
    std::vector<io::TimedPose> t;
    for (const pipeline::FrameReport& r : job_->session().reports()) t.push_back({r.timestamp, r.T_world_camera});
    io::WriteTrajectory(path.toStdString(), t);
    emit exportDone(true, tr("Wrote %1 (%2 poses)").arg(path).arg(t.size()));
  } catch (const std::exception& e) {
    emit exportDone(false, tr("Trajectory export: %1").arg(QString::fromStdString(e.what())));
  }
}

void ScanWorker::ExportRender(const QString& path) {
  try {
    if (!job_) throw Error("no model");
    const auto r = job_->session().pipeline().Render(job_->session().pipeline().pose());
    io::WriteExr(path.toStdString(), r.radiance);
    emit exportDone(true, tr("Wrote %1").arg(path));
  } catch (const std::exception& e) {
    emit exportDone(false, tr("OpenEXR export: %1").arg(QString::fromStdString(e.what())));
  }
}

void ScanWorker::ExportAsset(const QString& folder, const io::AssetOptions& options) {
  if (!job_ || job_->session().frames() == 0) {
    emit assetDone(false, tr("Nothing to export: scan first"), {});
    return;
  }
  try {
    emit assetProgress(0, tr("mesh"));
    const io::ScanData scan = io::ScanDataFromSession(job_->session(), source_spec_, [this](double f) {
      emit assetProgress(0.1 * f, tr("mesh"));
      return !cancel_export_;
    });
    if (cancel_export_) throw Cancelled();
    const io::AssetResult r = io::ExportAsset(scan, options, folder.toStdString(), [this](const std::string& stage, double f) {
      emit assetProgress(0.1 + 0.9 * f, QString::fromStdString(stage));
      return !cancel_export_;
    });
    QImage preview;
    if (r.preview.width() > 0)
      preview = QImage(reinterpret_cast<const uchar*>(r.preview.data()), r.preview.width(), r.preview.height(),
                       3 * r.preview.width(), QImage::Format_RGB888)
                    .copy();
    QString msg = tr("Wrote %1 files into %2: %3").arg(r.files.size()).arg(folder, QString::fromStdString(r.Summary()));
    for (const std::string& w : r.warnings) msg += "\n" + tr("Note: %1").arg(language::EngineText(w));
    emit assetDone(true, msg, preview);
  } catch (const Cancelled&) {
    emit assetDone(false, tr("Export cancelled; the folder was left as it was"), {});
  } catch (const std::exception& e) {
    emit assetDone(false, tr("Export failed: %1").arg(QString::fromStdString(e.what())), {});
  }
}

}  // namespace hdrf::gui
