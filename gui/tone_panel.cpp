#include "gui/tone_panel.h"

#include <QCheckBox>
#include <QComboBox>
#include <QDoubleSpinBox>
#include <QFormLayout>
#include <QLabel>
#include <QSpinBox>
#include <QVBoxLayout>
#include <algorithm>
#include <cmath>

#include "gui/registry_words.h"

namespace hdrf::gui {

namespace {
const tonemap::OperatorDecl& Current(const QComboBox* op) {
  return tonemap::Operators()[std::size_t(std::max(0, op->currentIndex()))];
}
}  // namespace

TonePanel::TonePanel(QWidget* parent) : QWidget(parent) {
  auto* layout = new QVBoxLayout(this);
  layout->setContentsMargins(0, 0, 0, 0);
  auto* top = top_ = new QFormLayout;
  op_ = new QComboBox;
  op_->setObjectName("tone_operator");
  for (const auto& d : tonemap::Operators()) op_->addItem(ToneWords(d.label), QString::fromStdString(d.key));
  top->addRow(tr("Operator"), op_);
  preset_ = new QComboBox;
  preset_->setObjectName("tone_preset");
  top->addRow(tr("Display"), preset_);
  layout->addLayout(top);
  help_ = new QLabel;
  help_->setWordWrap(true);
  help_->setStyleSheet("font-style: italic;");
  layout->addWidget(help_);
  editors_ = new QWidget;
  form_ = new QFormLayout(editors_);
  form_->setContentsMargins(0, 0, 0, 0);
  layout->addWidget(editors_);
  connect(op_, &QComboBox::currentIndexChanged, this, [this] {
    if (building_) return;
    Rebuild();
    emit changed(choice());
  });
  connect(preset_, &QComboBox::currentIndexChanged, this, [this](int i) {
    if (building_ || i <= 0) return;
    const auto& d = Current(op_);
    values_[d.key] = tonemap::ApplyPreset(d, preset_->itemData(i).toString().toStdString(), values_[d.key]);
    Rebuild();
    emit changed(choice());
  });
  Rebuild();
}

ToneChoice TonePanel::choice() const {
  ToneChoice c;
  c.op = Current(op_).key;
  auto it = values_.find(c.op);
  if (it != values_.end()) c.values = it->second;
  return c;
}

void TonePanel::SetChoice(const ToneChoice& c) {
  int index = -1;
  const auto& ops = tonemap::Operators();
  for (std::size_t i = 0; i < ops.size(); ++i)
    if (ops[i].key == c.op) index = int(i);
  if (index < 0) return;
  tonemap::Params kept;
  for (const auto& p : ops[std::size_t(index)].params) {
    auto it = c.values.find(p.key);
    if (it != c.values.end()) kept[p.key] = std::clamp(it->second, p.min, p.max);
  }
  values_[c.op] = kept;
  building_ = true;
  op_->setCurrentIndex(index);
  building_ = false;
  Rebuild();
}

void TonePanel::Rebuild() {
  building_ = true;
  const auto& d = Current(op_);
  tonemap::Params& v = values_[d.key];
  help_->setText(ToneWords(d.help));
  // Presets: "Custom" unless the values match one.
  preset_->clear();
  preset_->addItem(tr("Custom"), QString());
  int match = 0;
  for (const auto& p : d.presets) {
    preset_->addItem(ToneWords(p.label), QString::fromStdString(p.key));
    bool same = true;
    for (const auto& [k, x] : p.values) {
      auto it = v.find(k);
      const double cur = it != v.end() ? it->second : [&] {
        for (const auto& pd : d.params)
          if (pd.key == k) return pd.def;
        return 0.0;
      }();
      same &= std::abs(cur - x) < 1e-9;
    }
    if (same && match == 0) match = preset_->count() - 1;
  }
  preset_->setCurrentIndex(match);
  top_->setRowVisible(preset_, !d.presets.empty());
  while (form_->rowCount() > 0) form_->removeRow(0);
  for (const auto& p : d.params) {
    const double value = v.count(p.key) ? v.at(p.key) : p.def;
    const QString key = QString::fromStdString(p.key);
    const QString tip = ToneWords(p.help) + QStringLiteral(" (") + key + QStringLiteral(")");
    QWidget* editor = nullptr;
    if (p.kind == tonemap::ParamDecl::Kind::kBool) {
      auto* b = new QCheckBox;
      b->setChecked(value != 0);
      connect(b, &QCheckBox::toggled, this, [this, k = p.key, op = d.key](bool on) {
        values_[op][k] = on ? 1 : 0;
        emit changed(choice());
      });
      editor = b;
    } else if (p.kind == tonemap::ParamDecl::Kind::kInt) {
      auto* s = new QSpinBox;
      s->setRange(int(p.min), int(p.max));
      s->setValue(int(value));
      connect(s, &QSpinBox::valueChanged, this, [this, k = p.key, op = d.key](int x) {
        values_[op][k] = x;
        emit changed(choice());
      });
      editor = s;
    } else {
      auto* s = new QDoubleSpinBox;
      const double span = p.max - p.min;
      const double step = std::pow(10.0, std::floor(std::log10(span)) - 2);
      int decimals = int(-std::floor(std::log10(step)));
      if (p.min > 0) decimals = std::max(decimals, int(-std::floor(std::log10(p.min))));
      s->setDecimals(std::clamp(decimals, 0, 4));
      s->setRange(p.min, p.max);
      s->setSingleStep(span > 1000 ? std::pow(10.0, std::floor(std::log10(std::max(1.0, value)))) : step * 5);
      s->setValue(value);
      if (!p.unit.empty()) s->setSuffix(QStringLiteral(" ") + QString::fromStdString(p.unit));
      s->setKeyboardTracking(false);
      connect(s, &QDoubleSpinBox::valueChanged, this, [this, k = p.key, op = d.key](double x) {
        values_[op][k] = x;
        emit changed(choice());
      });
      editor = s;
    }
    editor->setObjectName(QStringLiteral("tone_") + key);
    editor->setToolTip(tip);
    auto* label = new QLabel(ToneWords(p.label));
    label->setToolTip(tip);
    form_->addRow(label, editor);
  }
  building_ = false;
}

}  // namespace hdrf::gui
