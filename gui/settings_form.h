// The engine's settings as a form, generated from the settings registry
// (pipeline/settings.h): one editor per setting, by its kind and range, grouped by section,
// expert settings behind a switch; the help line as tooltip. Values are kept in QSettings
// under "engine/<key>" as the registry's text, so a new setting needs no code here.
#pragma once

#include <QWidget>
#include <functional>
#include <map>
#include <string>

#include "pipeline/settings.h"

class QSettings;

namespace hdrf::gui {

class SettingsForm : public QWidget {
  Q_OBJECT
 public:
  explicit SettingsForm(QWidget* parent = nullptr);

  // The options the form shows; throws hdrf::SettingError naming the key of a bad value.
  pipeline::PipelineOptions Options() const;
  void SetOptions(const pipeline::PipelineOptions& o);
  // One setting, as the registry's text ("" for an unknown key).
  std::string Value(const std::string& key) const;
  void SetValue(const std::string& key, const std::string& text);

  void Save(QSettings& s) const;
  // Values saved earlier; a saved value the registry refuses now keeps the default.
  void Load(const QSettings& s);

 signals:
  void changed();

 private:
  struct Editor {
    const pipeline::Setting* setting;
    QWidget* widget;
    std::function<std::string()> get;
    std::function<void(const std::string&)> set;
  };
  std::map<std::string, Editor> editors_;
};

}  // namespace hdrf::gui
