// What the wizard's pages share: a red problem line, a coverage text, the preview with clipped
// pixels marked, where captures go by default.
#include "calibration_wizard/page_support.h"

#include <QDir>
#include <QLabel>
#include <algorithm>

#include "io/sweep.h"
#include "io/sweep_capture.h"
#include "radiometry/validation.h"

namespace hdrf::wizard::page {

namespace fs = std::filesystem;

QString Q(const std::string& s) { return QString::fromStdString(s); }

QLabel* ProblemLabel(const char* name) {
  auto* l = new QLabel;
  l->setObjectName(name);
  l->setWordWrap(true);
  l->setStyleSheet("color: #b00000; font-weight: bold");
  l->setTextInteractionFlags(Qt::TextSelectableByMouse);
  l->hide();
  return l;
}

void ShowProblem(QLabel* l, const QString& text) {
  l->setText(text);
  l->setVisible(!text.isEmpty());
}

// "R 98 %, G 100 %, B 97 %"
QString CoverageText(const radiometry::LevelCoverage& c) {
  return QString("R %1 %, G %2 %, B %3 %")
      .arg(int(100 * c.share[0] + 0.5))
      .arg(int(100 * c.share[1] + 0.5))
      .arg(int(100 * c.share[2] + 0.5));
}

// A capture in `folder` that stopped before its last step (Resume can complete it).
bool UnfinishedCapture(const fs::path& folder) {
  try {
    if (folder.empty() || !fs::exists(folder / "capture.json")) return false;
    const io::CaptureRecord r = io::ReadCaptureRecord(folder);
    return r.steps_done < int(r.plan.exposures_ms.size());
  } catch (const std::exception&) {
    return false;  // not a record this tool can resume: Start says what is wrong with the folder
  }
}

QString HomePath(const QString& sub) { return QDir::home().filePath("HDRFusion/" + sub); }

// The colour frame with saturated pixels shown red and black ones blue (io::IsSaturated,
// io::IsBlack: what the plan meters), for the Set-up page's preview.
QImage Highlighted(const ColorImage& im, double* high, double* low) {
  QImage q(im.width(), im.height(), QImage::Format_RGB888);
  long h = 0, l = 0;
  for (int y = 0; y < im.height(); ++y) {
    uchar* row = q.scanLine(y);
    for (int x = 0; x < im.width(); ++x) {
      const Rgb8 v = im(x, y);
      uchar* o = row + 3 * x;
      if (io::IsSaturated(v)) {
        o[0] = 255, o[1] = 0, o[2] = 0, ++h;
      } else if (io::IsBlack(v)) {
        o[0] = 0, o[1] = 80, o[2] = 255, ++l;
      } else {
        o[0] = v.r, o[1] = v.g, o[2] = v.b;
      }
    }
  }
  const double n = double(std::max<std::size_t>(im.size(), 1));
  *high = double(h) / n;
  *low = double(l) / n;
  return q;
}

}  // namespace hdrf::wizard::page
