#include "gui/settings_form.h"

#include <QCheckBox>
#include <QComboBox>
#include <QDoubleSpinBox>
#include <QFormLayout>
#include <QGroupBox>
#include <QCoreApplication>
#include <QLabel>
#include <QLineEdit>
#include <QSettings>
#include <QSpinBox>
#include <QVBoxLayout>
#include <cmath>
#include <cstdio>

#include "common/cuda_runtime.h"
#include "common/error.h"
#include "gui/registry_words.h"

namespace hdrf::gui {

namespace {

// A setting's unit as shown: degrees as a sign, counted things in the user's language.
QString UnitText(const std::string& unit) {
  if (unit == "deg") return QStringLiteral("°");
  if (unit == "frames") return QObject::tr("frames");
  if (unit == "voxels") return QObject::tr("voxels");
  return QString::fromStdString(unit);
}

// The allowed values, in the user's language.
QString RangeText(const pipeline::Setting& s) {
  switch (s.kind) {
    case pipeline::SettingKind::kBool:
      return QObject::tr("on or off");
    case pipeline::SettingKind::kChoice: {
      QStringList c;
      for (const auto& x : s.choices) c << QString::fromStdString(x);
      return QObject::tr("one of %1").arg(c.join(QStringLiteral(", ")));
    }
    case pipeline::SettingKind::kIntList:
      return QObject::tr("1 to %1 whole numbers, each %2 .. %3").arg(s.max_items).arg(s.min).arg(s.max);
    default:
      return QStringLiteral("%1 .. %2 %3").arg(s.min).arg(s.max).arg(UnitText(s.unit)).trimmed();
  }
}

QString SectionTitle(const std::string& section) {
  if (section.empty()) return QObject::tr("Engine");
  if (section == "volume") return QObject::tr("Volume");
  if (section == "tracker") return QObject::tr("Tracking");
  if (section == "exposure") return QObject::tr("Exposure compensation");
  if (section == "nr") return QObject::tr("Normalized radiance");
  if (section == "depth") return QObject::tr("Depth");
  if (section == "reloc") return QObject::tr("Relocalisation");
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
            w->setItemData(1, tr("not available: “%1”").arg(QString::fromStdString(why)), Qt::ToolTipRole);
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
        if (!s.unit.empty()) w->setSuffix(QStringLiteral(" ") + UnitText(s.unit));
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
        if (!s.unit.empty()) w->setSuffix(QStringLiteral(" ") + UnitText(s.unit));
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
    // The tooltip: what it does, when to change it, then its key, range and default as a
    // settings file and the CLI spell them.
    const QString tip = QStringLiteral("<p><b>%1</b></p><p>%2.</p><p>%3: %4.</p><p><tt>%5</tt> · %6 · %7</p>")
                            .arg(SettingWords(s.label).toHtmlEscaped(), SettingWords(s.help).toHtmlEscaped(),
                                 tr("When to change it"), SettingWords(s.advice).toHtmlEscaped(),
                                 QString::fromStdString(s.key).toHtmlEscaped(),
                                 RangeText(s).toHtmlEscaped(),
                                 tr("default %1").arg(QString::fromStdString(s.Default())).toHtmlEscaped());
    e.widget->setToolTip(tip);
    auto* label = new QLabel(SettingWords(s.label));
    label->setToolTip(tip);
    label->setBuddy(e.widget);
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
