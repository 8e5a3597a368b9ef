#include "gui/settings_form.h"

#include <QCheckBox>
#include <QComboBox>
#include <QDoubleSpinBox>
#include <QFormLayout>
#include <QGroupBox>
#include <QLineEdit>
#include <QSettings>
#include <QSpinBox>
#include <QVBoxLayout>
#include <cmath>
#include <cstdio>

#include "common/cuda_runtime.h"
#include "common/error.h"

namespace hdrf::gui {

namespace {

// "volume.tau1_deg" -> "tau1", "tracker.max_jump_m" -> "max jump": the field, its unit dropped.
QString Label(const pipeline::Setting& s) {
  std::string f = s.key.substr(s.key.find('.') == std::string::npos ? 0 : s.key.find('.') + 1);
  for (const char* suffix : {"_deg", "_px", "_mb", "_m"}) {
    const std::string x = suffix;
    if (f.size() > x.size() && f.compare(f.size() - x.size(), x.size(), x) == 0)
      f.resize(f.size() - x.size());
  }
  for (char& c : f)
    if (c == '_') c = ' ';
  return QString::fromStdString(f);
}

QString SectionTitle(const std::string& section) {
  if (section.empty()) return QObject::tr("Engine");
  if (section == "volume") return QObject::tr("Volume");
  if (section == "tracker") return QObject::tr("Tracking");
  if (section == "exposure") return QObject::tr("Exposure compensation");
  if (section == "nr") return QObject::tr("Normalized radiance");
  if (section == "depth") return QObject::tr("Depth");
  return QString::fromStdString(section);
}

std::string Text(double v) {
  char b[64];
  std::snprintf(b, sizeof b, "%.9g", v);
  return b;
}

// The fewest decimals (2 to 6) that show the default exactly.
int Decimals(const pipeline::Setting& s) {
  const double d = std::stod(s.Default());
  for (int k = 2; k < 6; ++k) {
    const double scale = std::pow(10.0, k);
    if (std::abs(std::round(d * scale) / scale - d) <= 1e-9 * std::max(1.0, std::abs(d))) return k;
  }
  return 6;
}

}  // namespace

SettingsForm::SettingsForm(QWidget* parent) : QWidget(parent) {
  auto* outer = new QVBoxLayout(this);
  outer->setContentsMargins(0, 0, 0, 0);
  auto* expert_switch = new QCheckBox(tr("Show expert settings"));
  std::map<std::string, QFormLayout*> forms, expert_forms;
  std::vector<QWidget*> expert_boxes;
  auto form_for = [&](const std::string& section, bool expert) {
    auto& m = expert ? expert_forms : forms;
    auto it = m.find(section);
    if (it != m.end()) return it->second;
    auto* box = new QGroupBox(expert ? tr("%1 (expert)").arg(SectionTitle(section))
                                     : SectionTitle(section));
    auto* f = new QFormLayout(box);
    f->setFieldGrowthPolicy(QFormLayout::AllNonFixedFieldsGrow);
    outer->addWidget(box);
    if (expert) {
      expert_boxes.push_back(box);
      box->setVisible(false);
    }
    return m[section] = f;
  };
  for (const pipeline::Setting& s : pipeline::Settings()) {
    const std::size_t dot = s.key.find('.');
    const std::string section = dot == std::string::npos ? "" : s.key.substr(0, dot);
    QFormLayout* f = form_for(section, s.expert);
    Editor e{&s, nullptr, {}, {}};
    switch (s.kind) {
      case pipeline::SettingKind::kBool: {
        auto* w = new QCheckBox;
        e.widget = w;
        e.get = [w] { return std::string(w->isChecked() ? "true" : "false"); };
        e.set = [w](const std::string& t) { w->setChecked(t == "true"); };
        connect(w, &QCheckBox::toggled, this, &SettingsForm::changed);
        break;
      }
      case pipeline::SettingKind::kChoice: {
        auto* w = new QComboBox;
        for (const auto& c : s.choices) w->addItem(QString::fromStdString(c));
        if (s.key == "device") {
          std::string why;
          if (!CudaAvailable(&why))
            w->setItemData(1, QString::fromStdString("not available: " + why), Qt::ToolTipRole);
        }
        e.widget = w;
        e.get = [w] { return w->currentText().toStdString(); };
        e.set = [w](const std::string& t) { w->setCurrentText(QString::fromStdString(t)); };
        connect(w, &QComboBox::currentIndexChanged, this, &SettingsForm::changed);
        break;
      }
      case pipeline::SettingKind::kInt: {
        auto* w = new QSpinBox;
        w->setRange(int(std::max(s.min, -2e9)), int(std::min(s.max, 2e9)));
        if (!s.unit.empty()) w->setSuffix(QString::fromStdString(" " + s.unit));
        e.widget = w;
        e.get = [w] { return std::to_string(w->value()); };
        e.set = [w](const std::string& t) { w->setValue(int(std::stod(t))); };
        connect(w, &QSpinBox::valueChanged, this, &SettingsForm::changed);
        break;
      }
      case pipeline::SettingKind::kReal: {
        auto* w = new QDoubleSpinBox;
        const int decimals = Decimals(s);
        w->setDecimals(decimals);
        w->setRange(s.min, s.max);
        w->setSingleStep(std::pow(10.0, 1 - decimals));
        if (!s.unit.empty()) w->setSuffix(QString::fromStdString(" " + s.unit));
        e.widget = w;
        e.get = [w, &s] {
          // The registry's own spelling of the value (1e+08, 0.1), as Default() gives it.
          pipeline::PipelineOptions probe;
          try {
            s.set(probe, Text(w->value()));
            return s.get(probe);
          } catch (const Error&) {
            return Text(w->value());
          }
        };
        e.set = [w](const std::string& t) { w->setValue(std::stod(t)); };
        connect(w, &QDoubleSpinBox::valueChanged, this, &SettingsForm::changed);
        break;
      }
      case pipeline::SettingKind::kIntList: {
        auto* w = new QLineEdit;
        e.widget = w;
        e.get = [w] { return w->text().toStdString(); };
        e.set = [w](const std::string& t) { w->setText(QString::fromStdString(t)); };
        connect(w, &QLineEdit::editingFinished, this, &SettingsForm::changed);
        break;
      }
    }
    e.widget->setObjectName(QString::fromStdString("setting_" + s.key));
    // Two fields that differ only by unit ("max jump" in m and in deg) keep the unit.
    QString label = Label(s);
    for (const pipeline::Setting& other : pipeline::Settings())
      if (&other != &s && other.key.substr(0, dot + 1) == s.key.substr(0, dot + 1) &&
          Label(other) == label && !s.unit.empty())
        label += QString::fromStdString(" (" + s.unit + ")");
    e.widget->setToolTip(QString::fromStdString(s.key + ": " + s.help + " [" + s.Range() +
                                                "; default " + s.Default() + "]"));
    f->addRow(label, e.widget);
    e.set(s.Default());
    editors_[s.key] = e;
  }
  outer->addWidget(expert_switch);
  connect(expert_switch, &QCheckBox::toggled, this, [expert_boxes](bool on) {
    for (QWidget* b : expert_boxes) b->setVisible(on);
  });
  // The studio runs on the GPU where this build has CUDA and one answers.
  if (CudaAvailable()) SetValue("device", "cuda");
}

pipeline::PipelineOptions SettingsForm::Options() const {
  pipeline::PipelineOptions o;
  for (const auto& [key, e] : editors_) e.setting->set(o, e.get());
  o.Check();
  return o;
}

void SettingsForm::SetOptions(const pipeline::PipelineOptions& o) {
  for (auto& [key, e] : editors_) e.set(e.setting->get(o));
}

std::string SettingsForm::Value(const std::string& key) const {
  const auto it = editors_.find(key);
  return it == editors_.end() ? std::string() : it->second.get();
}

void SettingsForm::SetValue(const std::string& key, const std::string& text) {
  const auto it = editors_.find(key);
  if (it == editors_.end()) return;
  pipeline::PipelineOptions probe;
  it->second.setting->set(probe, text);  // throws for a value the registry refuses
  it->second.set(it->second.setting->get(probe));
}

void SettingsForm::Save(QSettings& s) const {
  for (const auto& [key, e] : editors_)
    s.setValue(QString::fromStdString("engine/" + key), QString::fromStdString(e.get()));
}

void SettingsForm::Load(const QSettings& s) {
  for (auto& [key, e] : editors_) {
    const QString k = QString::fromStdString("engine/" + key);
    if (!s.contains(k)) continue;
    try {
      SetValue(key, s.value(k).toString().toStdString());
    } catch (const Error&) {
      // A value saved by another version that this one refuses: the default stays.
    }
  }
}

}  // namespace hdrf::gui
