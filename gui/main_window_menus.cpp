// The studio window's menus and what they open: the project files (open, save, the offer of
// an autosave a crash left), the export dialog and the calibration wizard.
#include "gui/main_window.h"

#include <QAction>
#include <QActionGroup>
#include <QApplication>
#include <QComboBox>
#include <QDateTime>
#include <QDockWidget>
#include <QFileDialog>
#include <QFileInfo>
#include <QLocale>
#include <QMenu>
#include <QMenuBar>
#include <QMessageBox>
#include <QProgressDialog>
#include <QPushButton>
#include <QSettings>
#include <QStatusBar>
#include <filesystem>

#include "calibration_wizard/calibration_wizard.h"
#include "common/error.h"
#include "gui/export_dialog.h"
#include "gui/help/help.h"
#include "gui/language/language.h"
#include "gui/sensor_panel.h"
#include "gui/settings_form.h"
#include "gui/status_panel.h"
#include "gui/tone_panel.h"
#include "gui/vtk_view.h"
#include "io/project.h"
#include "tonemap/display.h"

namespace hdrf::gui {

ExportDialog* MainWindow::OpenExportDialog() {
  if (!export_dialog_) {
    const ToneChoice tc = tone_panel_->choice();
    auto* dlg = new ExportDialog(QString::fromStdString(tonemap::FormatSpec({tc.op, tc.values})), this);
    dlg->setAttribute(Qt::WA_DeleteOnClose);
    connect(dlg, &ExportDialog::exportRequested, this, [this](const QString& folder, const io::AssetOptions& o) {
      worker_->ArmExport();
      QMetaObject::invokeMethod(worker_, [w = worker_, folder, o] { w->ExportAsset(folder, o); }, Qt::QueuedConnection);
    });
    connect(dlg, &ExportDialog::cancelRequested, this, [this] { worker_->CancelExport(); });
    connect(worker_, &ScanWorker::assetProgress, dlg, &ExportDialog::OnProgress);
    connect(worker_, &ScanWorker::assetDone, dlg, &ExportDialog::OnDone);
    export_dialog_ = dlg;
  }
  export_dialog_->show();
  export_dialog_->raise();
  return export_dialog_;
}

QString MainWindow::source_text() const { return source_->currentText(); }
bool MainWindow::start_enabled() const { return start_->isEnabled(); }

void MainWindow::BuildMenus() {
  QMenu* file = menuBar()->addMenu(tr("&File"));
  QMenu* exp = file->addMenu(tr("&Export"));
  exp->addAction(tr("Textured HDR asset (OBJ, glTF, OpenEXR)…"), this, [this] { OpenExportDialog(); });
  exp->addAction(tr("HDR mesh (PLY)…"), this, [this] {
    const QString p = QFileDialog::getSaveFileName(this, tr("Export HDR mesh"), "mesh.ply", tr("PLY (*.ply)"));
    if (p.isEmpty()) return;
    auto* dlg = new QProgressDialog(tr("Extracting and writing the mesh…"), tr("Cancel"), 0, 100, this);
    dlg->setAttribute(Qt::WA_DeleteOnClose);
    dlg->setMinimumDuration(300);
    connect(dlg, &QProgressDialog::canceled, this, [this] { worker_->CancelExport(); });
    connect(worker_, &ScanWorker::exportProgress, dlg, [dlg](double f) { dlg->setValue(int(100 * f)); });
    connect(worker_, &ScanWorker::exportDone, dlg, [dlg](bool, const QString&) { dlg->close(); });
    const ToneChoice tc = tone_panel_->choice();
    emit exportMesh(p, QString::fromStdString(tonemap::FormatSpec({tc.op, tc.values})));
  });
  exp->addAction(tr("Trajectory (TUM)…"), this, [this] {
    const QString p = QFileDialog::getSaveFileName(this, tr("Export trajectory"), "trajectory.txt");
    if (!p.isEmpty()) emit exportTrajectory(p);
  });
  exp->addAction(tr("Model render (OpenEXR)…"), this, [this] {
    const QString p = QFileDialog::getSaveFileName(this, tr("Export model render"), "render.exr", tr("OpenEXR (*.exr)"));
    if (!p.isEmpty()) emit exportRender(p);
  });
  file->addAction(tr("&Open project…"), QKeySequence::Open, this, [this] {
    const QString path = QFileDialog::getOpenFileName(this, tr("Open a scan project"), project_path_,
                                                      tr("HDRFusion projects (*.hdrproj)"));
    if (!path.isEmpty()) OpenProject(path);
  });
  file->addAction(tr("&Save project"), QKeySequence::Save, this, [this] { SaveProject(project_path_); });
  file->addAction(tr("Save project &as…"), QKeySequence::SaveAs, this, [this] { SaveProject(QString()); });
  file->addSeparator();
  file->addAction(tr("Save window screenshot…"), this, [this] {
    const QString p = QFileDialog::getSaveFileName(this, tr("Screenshot"), "studio.png", tr("PNG (*.png)"));
    if (!p.isEmpty()) SaveScreenshot(p);
  });
  file->addSeparator();
  file->addAction(tr("&Quit"), QKeySequence::Quit, this, &QWidget::close);
  QMenu* scan = menuBar()->addMenu(tr("&Scan"));
  scan->addAction(tr("Start"), this, &MainWindow::StartScan);
  scan->addAction(tr("Pause"), this, &MainWindow::PauseScan);
  scan->addAction(tr("Stop"), this, &MainWindow::StopScan);
  scan->addAction(tr("Reset (apply engine settings)"), this, &MainWindow::ResetScan);
  QMenu* tools = menuBar()->addMenu(tr("&Tools"));
  QAction* calibrate = tools->addAction(tr("Calibrate camera…"), this, &MainWindow::OpenCalibrationWizard);
  calibrate->setObjectName("action_calibrate");
  QMenu* view = menuBar()->addMenu(tr("&View"));
  for (auto it = docks_.begin(); it != docks_.end(); ++it) view->addAction(it.value()->toggleViewAction());
  view->addSeparator();
  view->addAction(tr("Reset 3-D view"), this, [this] { view3d_->ResetView(); });
  // The 3-D view's surface while scanning: a coarse preview (the default) or every voxel.
  QAction* full_detail = full_detail_ = view->addAction(tr("Full surface detail while scanning"));
  full_detail->setObjectName("action_full_detail");
  full_detail->setCheckable(true);
  full_detail->setToolTip(tr("Off: while a scan runs the 3-D view shows a coarser surface (from every other voxel, "
                             "a quarter of the triangles; every fourth where the display cannot draw that quickly), "
                             "which leaves more of the processor to the scan; the whole surface follows when the scan "
                             "stops"));
  full_detail->setChecked(QSettings().value("view/full_detail_while_scanning", false).toBool());
  connect(full_detail, &QAction::toggled, this, [this](bool on) {
    worker_->SetPreviewStep(preview_.Start(on));
    QSettings().setValue("view/full_detail_while_scanning", on);
  });
  view->addAction(tr("Restore default layout"), this, [this] {
    restoreState(default_state_);
    for (QDockWidget* d : docks_) d->show();
  });
  // Language: the system's or one chosen here, for the studio and the wizard; it takes
  // effect when the studio starts again (every window is made in its language).
  view->addSeparator();
  QMenu* language = view->addMenu(tr("&Language"));
  language->setObjectName("menu_language");
  auto* languages = new QActionGroup(language);
  const QString saved = language::SavedLanguage();
  QStringList codes{QString()};
  codes << language::AvailableLanguages();
  for (const QString& code : codes) {
    QAction* a = language->addAction(code.isEmpty() ? tr("As the system") : language::LanguageName(code));
    a->setData(code);
    a->setCheckable(true);
    a->setChecked(code == saved);
    languages->addAction(a);
    connect(a, &QAction::triggered, this, [this, code] {
      if (code == language::SavedLanguage()) return;
      language::SaveLanguage(code);
      statusBar()->showMessage(tr("The language changes when the studio starts again."), 15000);
    });
  }
  // Help: the documentation in a window of the studio's own, the operator's guide first.
  QMenu* help = menuBar()->addMenu(tr("&Help"));
  help->setObjectName("menu_help");
  help::FillHelpMenu(help, this, QApplication::applicationName(), tr("Scanning a room"),
                     "tutorials/scan-a-room.md");
}

void MainWindow::OpenCalibrationWizard() {
  if (wizard_) {
    wizard_->raise();
    wizard_->activateWindow();
    return;
  }
  // The wizard opens its camera itself: a camera the studio has open shows as in use there
  // until the studio's preview or scan is stopped.
  wizard_ = new wizard::CalibrationWizard(wizard::WizardSettings{}, this);
  wizard_->setAttribute(Qt::WA_DeleteOnClose);
  connect(wizard_, &wizard::CalibrationWizard::saved, this, [this](const QString& profile, const QString&) {
    statusBar()->showMessage(tr("Calibration saved: %1 (used from now on for that camera)").arg(profile), 15000);
    QMetaObject::invokeMethod(worker_, &ScanWorker::ListSensors, Qt::QueuedConnection);
  });
  wizard_->show();
}

void MainWindow::OpenProject(const QString& path) {
  status_->HideError();
  latest_.reset();
  shown_.reset();
  QMetaObject::invokeMethod(worker_, [w = worker_, path] { w->OpenProject(path); }, Qt::QueuedConnection);
}

void MainWindow::SaveProject(const QString& path) {
  QString file = path;
  if (file.isEmpty()) {
    file = QFileDialog::getSaveFileName(this, tr("Save the scan as a project"),
                                        project_path_.isEmpty() ? QStringLiteral("scan.hdrproj") : project_path_,
                                        tr("HDRFusion projects (*.hdrproj)"));
    if (file.isEmpty()) return;
    if (!file.endsWith(QStringLiteral(".hdrproj"))) file += QStringLiteral(".hdrproj");
  }
  QMetaObject::invokeMethod(worker_, [w = worker_, file] { w->SaveProject(file); }, Qt::QueuedConnection);
}

QMessageBox* MainWindow::recovery_offer() const { return recovery_offer_.data(); }

// A scan that did not end normally left its last autosave: offered once, without blocking
// (open it, keep it for later, or delete it).
void MainWindow::OfferRecovery() {
  const std::vector<std::filesystem::path> found = io::FindRecoveryFiles();
  if (found.empty()) return;
  const QString file = QString::fromStdString(found.front().string());
  const QDateTime when = QFileInfo(file).lastModified();
  auto* box = new QMessageBox(QMessageBox::Question, tr("Recover a scan"),
                              tr("A scan that did not finish was autosaved on %1:\n%2\n\nOpen it to continue or export "
                                 "it?")
                                  .arg(QLocale().toString(when, QLocale::ShortFormat), file),
                              QMessageBox::NoButton, this);
  QPushButton* open = box->addButton(tr("Open"), QMessageBox::AcceptRole);
  QPushButton* discard = box->addButton(tr("Delete it"), QMessageBox::DestructiveRole);
  box->addButton(tr("Later"), QMessageBox::RejectRole);
  box->setAttribute(Qt::WA_DeleteOnClose);
  connect(box, &QMessageBox::buttonClicked, this, [this, box, open, discard, file](QAbstractButton* b) {
    if (b == open) {
      OpenProject(file);
    } else if (b == discard) {
      std::error_code ec;
      std::filesystem::remove(file.toStdString(), ec);
    }
    box->close();
  });
  recovery_offer_ = box;
  box->setWindowModality(Qt::NonModal);
  box->show();
}

}  // namespace hdrf::gui
