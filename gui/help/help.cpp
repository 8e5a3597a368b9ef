#include "gui/help/help.h"

#include <QApplication>
#include <QDialog>
#include <QDir>
#include <QFileInfo>
#include <QHBoxLayout>
#include <QMenu>
#include <QMessageBox>
#include <QPointer>
#include <QPushButton>
#include <QStringList>
#include <QTextBrowser>
#include <QUrl>
#include <QVBoxLayout>

namespace hdrf::help {

namespace {

QStringList Candidates() {
  QStringList c;
  const QString env = qEnvironmentVariable("HDRF_DOCS_DIR");
  if (!env.isEmpty()) c << env;
  c << QDir(QCoreApplication::applicationDirPath()).absoluteFilePath("../share/doc/hdrfusion-studio")
    << "/usr/share/doc/hdrfusion-studio" << QStringLiteral(HDRF_SOURCE_DOCS_DIR);
  return c;
}

// The documentation window: a Markdown browser with Back, Forward and Contents. Links to
// other pages open in it; links to the web open in the system's browser.
class DocsWindow : public QDialog {
 public:
  DocsWindow(QWidget* parent, const QString& folder) : QDialog(parent), folder_(folder) {
    setObjectName("documentation_window");
    setWindowTitle(QApplication::translate("hdrf::help", "Documentation"));
    setAttribute(Qt::WA_DeleteOnClose);
    browser_ = new QTextBrowser(this);
    browser_->setObjectName("documentation_browser");
    browser_->setOpenExternalLinks(true);
    browser_->setSearchPaths({folder_});
    auto* back = new QPushButton(QApplication::translate("hdrf::help", "Back"), this);
    auto* forward = new QPushButton(QApplication::translate("hdrf::help", "Forward"), this);
    auto* home = new QPushButton(QApplication::translate("hdrf::help", "Contents"), this);
    back->setEnabled(false);
    forward->setEnabled(false);
    connect(back, &QPushButton::clicked, browser_, &QTextBrowser::backward);
    connect(forward, &QPushButton::clicked, browser_, &QTextBrowser::forward);
    connect(home, &QPushButton::clicked, this, [this] { Show("index.md"); });
    connect(browser_, &QTextBrowser::backwardAvailable, back, &QWidget::setEnabled);
    connect(browser_, &QTextBrowser::forwardAvailable, forward, &QWidget::setEnabled);
    connect(browser_, &QTextBrowser::sourceChanged, this, [this](const QUrl& u) {
      setWindowTitle(QApplication::translate("hdrf::help", "Documentation") + " — " +
                     QDir(folder_).relativeFilePath(u.toLocalFile()));
    });
    auto* buttons = new QHBoxLayout;
    buttons->addWidget(back);
    buttons->addWidget(forward);
    buttons->addWidget(home);
    buttons->addStretch();
    auto* layout = new QVBoxLayout(this);
    layout->addLayout(buttons);
    layout->addWidget(browser_);
    resize(900, 700);
  }
  void Show(const QString& page) {
    browser_->setSource(QUrl::fromLocalFile(QDir(folder_).absoluteFilePath(page)), QTextDocument::MarkdownResource);
    show();
    raise();
    activateWindow();
  }

 private:
  QString folder_;
  QTextBrowser* browser_ = nullptr;
};

QPointer<DocsWindow> g_window;

}  // namespace

QString DocsFolder() {
  for (const QString& c : Candidates())
    if (QFileInfo(QDir(c).absoluteFilePath("index.md")).isFile()) return QDir(c).absolutePath();
  return {};
}

void ShowDocumentation(QWidget* parent, const QString& page) {
  const QString folder = DocsFolder();
  if (folder.isEmpty()) {
    QMessageBox::warning(parent, QApplication::translate("hdrf::help", "Documentation"),
                         QApplication::translate("hdrf::help", "The documentation was not found. Looked in:\n%1")
                             .arg(Candidates().join("\n")));
    return;
  }
  if (!g_window) g_window = new DocsWindow(parent, folder);
  g_window->Show(page);
}

void FillHelpMenu(QMenu* menu, QWidget* parent, const QString& program, const QString& guide_title,
                  const QString& guide_page) {
  QAction* guide = menu->addAction(guide_title, parent, [parent, guide_page] { ShowDocumentation(parent, guide_page); });
  guide->setObjectName("action_help_guide");
  guide->setShortcut(QKeySequence::HelpContents);
  QAction* contents = menu->addAction(QApplication::translate("hdrf::help", "Documentation"), parent,
                                      [parent] { ShowDocumentation(parent, "index.md"); });
  contents->setObjectName("action_help_contents");
  menu->addAction(QApplication::translate("hdrf::help", "Messages and what to do"), parent,
                  [parent] { ShowDocumentation(parent, "faq.md"); });
  menu->addAction(QApplication::translate("hdrf::help", "Command-line reference"), parent,
                  [parent] { ShowDocumentation(parent, "reference/cli.md"); });
  menu->addSeparator();
  QAction* about = menu->addAction(QApplication::translate("hdrf::help", "About %1").arg(program), parent, [parent, program] {
    QMessageBox::about(parent, QApplication::translate("hdrf::help", "About %1").arg(program),
                       QApplication::translate("hdrf::help",
                                               "<b>%1</b> %2<p>3-D scanning with true high-dynamic-range colour for "
                                               "auto-exposure RGB-D cameras.</p><p>It implements S. Li, A. Handa, "
                                               "Y. Zhang, A. Calway, <i>HDRFusion: HDR SLAM using a low-cost "
                                               "auto-exposure RGB-D sensor</i>, 3DV 2016.</p><p>MIT licence. "
                                               "Documentation: %3</p>")
                           .arg(program, QCoreApplication::applicationVersion(), DocsFolder().toHtmlEscaped()));
  });
  about->setObjectName("action_help_about");
}

}  // namespace hdrf::help
