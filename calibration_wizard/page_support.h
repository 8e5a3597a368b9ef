// What the calibration wizard's pages share (page_support.cpp).
#pragma once

#include <QImage>
#include <QString>
#include <filesystem>
#include <string>

#include "common/image.h"
#include "radiometry/validation.h"

class QLabel;

namespace hdrf::wizard::page {

QString Q(const std::string& s);
// A hidden red line that names a problem (ShowProblem shows it, or hides it for "").
QLabel* ProblemLabel(const char* name);
void ShowProblem(QLabel* l, const QString& text);
// "R 98 %, G 100 %, B 97 %"
QString CoverageText(const radiometry::LevelCoverage& c);
// A capture in `folder` that stopped before its last step (Resume can complete it).
bool UnfinishedCapture(const std::filesystem::path& folder);
// ~/HDRFusion/<sub>
QString HomePath(const QString& sub);
// The colour frame with saturated pixels shown red and black ones blue (io::IsSaturated,
// io::IsBlack: what the plan meters), for the Set-up page's preview; the shares of each.
QImage Highlighted(const ColorImage& im, double* high, double* low);

}  // namespace hdrf::wizard::page
