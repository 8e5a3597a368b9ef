// What the studio's screenshots and benchmark record beside the picture (PATH.json): each
// view's size and content, the 3-D view's, the scan's rate as the window saw it, where the
// window's time went, every thread's CPU, the status text, and whether the panels fit.
#pragma once

#include <QJsonObject>
#include <QSize>

namespace hdrf::gui {

class MainWindow;

QJsonObject DescribeWindow(MainWindow& w, QSize window);

}  // namespace hdrf::gui
