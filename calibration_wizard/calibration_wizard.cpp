#include "calibration_wizard/calibration_wizard.h"
#include "gui/language/language.h"

#include <QApplication>
#include <QDir>
#include <QMenu>
#include <QPushButton>
#include <QGuiApplication>
#include <QScreen>
#include <QThread>
#include <QTimer>
#include <cstdio>

#include "calibration_wizard/wizard_pages.h"
#include "gui/help/help.h"

namespace hdrf::wizard {

CalibrationWizard::CalibrationWizard(WizardSettings options, QWidget* parent)
    : QWizard(parent), options_(std::move(options)) {
  setObjectName("calibration_wizard");
  setWindowTitle(tr("Camera calibration"));
  setWizardStyle(QWizard::ClassicStyle);
  setOption(QWizard::NoBackButtonOnStartPage);
  // Help: the calibration guide, the documentation and About, as the studio's Help menu.
  setOption(QWizard::HaveHelpButton, true);
  setButtonText(QWizard::HelpButton, tr("Help"));
  if (auto* help_button = qobject_cast<QPushButton*>(button(QWizard::HelpButton))) {
    auto* menu = new QMenu(help_button);
    menu->setObjectName("menu_help");
    help::FillHelpMenu(menu, this, QApplication::applicationName(), tr("Calibrating a camera"),
                       "tutorials/calibrate.md");
    help_button->setMenu(menu);
  }
  setPage(kSource, new SourcePage(this));
  setPage(kSetup, new SetupPage(this));
  setPage(kCapture, new CapturePage(this));
  setPage(kFit, new FitPage(this));
  setPage(kValidate, new ValidatePage(this));
  setPage(kSave, new SavePage(this));
  setStartId(kSource);
  // 1180x820 where the screen has room, else its free area (a 1366x768 laptop).
  QSize size(1180, 820);
  if (const QScreen* screen = QGuiApplication::primaryScreen())
    size = size.boundedTo(screen->availableGeometry().size());
  resize(size);
}

CalibrationWizard::~CalibrationWizard() {
  cancel_ = true;
  if (worker_) {  // its finished signal will not be delivered now: wait and free it here
    worker_->wait();
    delete worker_;
  }
}

bool CalibrationWizard::RunTask(std::function<void()> work, std::function<void(const QString&)> done) {
  if (worker_) return false;
  cancel_ = false;
  auto error = std::make_shared<QString>();
  worker_ = QThread::create([work = std::move(work), error] {
    try {
      work();
    } catch (const std::exception& e) {
      *error = language::EngineText(std::string(e.what()));  // the engine's wordings translated
      if (error->isEmpty()) *error = tr("failed (no message)");
    }
  });
  connect(worker_, &QThread::finished, this, [this, done = std::move(done), error] {
    worker_->deleteLater();
    worker_ = nullptr;
    done(*error);
  });
  worker_->start();
  return true;
}

void CalibrationWizard::PageDone(const QString& name) {
  if (!options_.screenshots.isEmpty()) {
    QDir().mkpath(options_.screenshots);
    const QString file = QDir(options_.screenshots).filePath(QString("%1-%2.png").arg(currentId() + 1, 2, 10, QChar('0')).arg(name));
    // Painted as it is now (the page's results shown), at the window's size.
    grab().save(file);
  }
  if (!options_.automatic) return;
  QTimer::singleShot(0, this, [this] {
    if (currentId() == kSave)
      accept();
    else
      next();
  });
}

void CalibrationWizard::Fail(const QString& message) {
  if (!options_.automatic) return;
  std::fprintf(stderr, "calibration wizard: %s\n", message.toLocal8Bit().constData());
  exit_code_ = 1;
  emit failed(message);
  QTimer::singleShot(0, this, [this] { reject(); });
}

}  // namespace hdrf::wizard
