// The Help menu both programs share: the documentation in a window of the program's own
// (Markdown rendered, links followed, images shown; no browser or network needed), and About.
#pragma once

#include <QString>

class QMenu;
class QWidget;

namespace hdrf::help {

// The folder holding the documentation's index.md: $HDRF_DOCS_DIR where set, else the
// installed copy beside the program (PREFIX/share/doc/hdrfusion-studio), else
// /usr/share/doc/hdrfusion-studio, else the source's docs/ (a program run from its build
// folder). Empty where none holds index.md.
QString DocsFolder();

// Shows `page` (a path under the documentation folder, e.g. "tutorials/calibrate.md") in the
// documentation window, opening it if needed (one window per program). Where the
// documentation is not found, says so in a message box naming the folders looked in.
void ShowDocumentation(QWidget* parent, const QString& page = "index.md");

// Adds the Help menu's entries to `menu`: the program's own guide (`guide_page`, with its
// title), the documentation's index, the command-line reference, messages and what to do,
// and About `program`.
void FillHelpMenu(QMenu* menu, QWidget* parent, const QString& program, const QString& guide_title,
                  const QString& guide_page);

}  // namespace hdrf::help
