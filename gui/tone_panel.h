// The tone-mapping panel, generated from the operators' declarations (core/tonemap): an
// operator list, its display presets where it has any, and one editor per declared
// parameter (range, default, unit and help from the declaration). Each operator keeps the
// values last set for it when the user switches away and back.
#pragma once

#include <QWidget>
#include <map>
#include <string>

#include "gui/tone_mapper.h"

class QComboBox;
class QFormLayout;
class QLabel;

namespace hdrf::gui {

class TonePanel : public QWidget {
  Q_OBJECT
 public:
  explicit TonePanel(QWidget* parent = nullptr);
  ToneChoice choice() const;
  // Shows `c` (unknown operators and parameters are ignored, values clamped to range).
  void SetChoice(const ToneChoice& c);

 signals:
  void changed(const hdrf::gui::ToneChoice& c);

 private:
  void Rebuild();
  QComboBox* op_ = nullptr;
  QComboBox* preset_ = nullptr;
  QLabel* help_ = nullptr;
  QFormLayout* form_ = nullptr;
  QFormLayout* top_ = nullptr;
  QWidget* editors_ = nullptr;
  std::map<std::string, tonemap::Params> values_;  // per operator key
  bool building_ = false;
};

}  // namespace hdrf::gui
