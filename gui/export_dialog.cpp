#include "gui/export_dialog.h"

#include <QCheckBox>
#include <QComboBox>
#include <QDir>
#include <QDoubleSpinBox>
#include <QFileDialog>
#include <QFormLayout>
#include <QHBoxLayout>
#include <QLabel>
#include <QLineEdit>
#include <QPixmap>
#include <QProgressBar>
#include <QPushButton>
#include <QSpinBox>
#include <QVBoxLayout>

namespace hdrf::gui {

ExportDialog::ExportDialog(const QString& tone, QWidget* parent) : QDialog(parent), tone_(tone) {
  setWindowTitle(tr("Export textured HDR asset"));
  auto* form = new QFormLayout;
  auto* row = new QHBoxLayout;
  folder_ = new QLineEdit(QDir::home().filePath(QStringLiteral("hdrfusion-export")));
  folder_->setObjectName("export_folder");
  auto* browse = new QPushButton(tr("Browse…"));
  connect(browse, &QPushButton::clicked, this, [this] {
    const QString d = QFileDialog::getExistingDirectory(this, tr("Export into"), folder_->text());
    if (!d.isEmpty()) folder_->setText(d);
  });
  row->addWidget(folder_, 1);
  row->addWidget(browse);
  form->addRow(tr("Folder"), row);
  auto* formats = new QHBoxLayout;
  ply_ = new QCheckBox(tr("PLY (per-vertex radiance)"));
  obj_ = new QCheckBox(tr("OBJ + MTL (EXR texture)"));
  glb_ = new QCheckBox(tr("glTF binary (PNG texture)"));
  for (auto* c : {ply_, obj_, glb_}) {
    c->setChecked(true);
    formats->addWidget(c);
  }
  ply_->setObjectName("export_ply");
  obj_->setObjectName("export_obj");
  glb_->setObjectName("export_gltf");
  form->addRow(tr("Formats"), formats);
  up_ = new QComboBox;
  up_->setObjectName("export_up");
  up_->addItem(tr("Z up (Blender)"), "z");
  up_->addItem(tr("Y up"), "y");
  form->addRow(tr("Up axis"), up_);
  texel_ = new QDoubleSpinBox;
  texel_->setObjectName("export_texel_mm");
  texel_->setRange(0.5, 50);
  texel_->setDecimals(1);
  texel_->setValue(2.0);
  texel_->setSuffix(tr(" mm per texel"));
  form->addRow(tr("Texture density"), texel_);
  triangles_ = new QSpinBox;
  triangles_->setObjectName("export_triangles");
  triangles_->setRange(0, 50000000);
  triangles_->setSingleStep(10000);
  triangles_->setSpecialValueText(tr("keep all"));
  form->addRow(tr("Triangle budget"), triangles_);
  auto* render_row = new QHBoxLayout;
  render_ = new QCheckBox(tr("Render (EXR with alpha and depth)"));
  render_->setObjectName("export_render");
  render_w_ = new QSpinBox;
  render_h_ = new QSpinBox;
  render_w_->setRange(16, 16384);
  render_h_->setRange(16, 16384);
  render_w_->setValue(1920);
  render_h_->setValue(1440);
  render_row->addWidget(render_);
  render_row->addWidget(render_w_);
  render_row->addWidget(new QLabel(QStringLiteral("×")));
  render_row->addWidget(render_h_);
  render_row->addStretch(1);
  form->addRow(tr("Render"), render_row);
  form->addRow(tr("Tone mapping"), new QLabel(tone_.isEmpty() ? QStringLiteral("mantiuk08") : tone_));

  progress_ = new QProgressBar;
  progress_->setObjectName("export_progress");
  progress_->setRange(0, 100);
  progress_->setValue(0);
  status_ = new QLabel(tr("The model is cleaned, levelled, unwrapped and textured from the scan's keyframes."));
  status_->setObjectName("export_status");
  status_->setWordWrap(true);
  preview_ = new QLabel;
  preview_->setObjectName("export_preview");
  preview_->setMinimumSize(480, 360);
  preview_->setAlignment(Qt::AlignCenter);
  preview_->setText(tr("The preview appears here when the export is done."));
  preview_->setStyleSheet("QLabel { background: #202020; color: #c0c0c0; }");

  export_ = new QPushButton(tr("Export"));
  export_->setObjectName("export_start");
  export_->setDefault(true);
  cancel_ = new QPushButton(tr("Cancel export"));
  cancel_->setObjectName("export_cancel");
  cancel_->setEnabled(false);
  close_ = new QPushButton(tr("Close"));
  connect(export_, &QPushButton::clicked, this, &ExportDialog::Start);
  connect(cancel_, &QPushButton::clicked, this, [this] {
    status_->setText(tr("Cancelling…"));
    emit cancelRequested();
  });
  connect(close_, &QPushButton::clicked, this, &QDialog::close);
  auto* buttons = new QHBoxLayout;
  buttons->addStretch(1);
  buttons->addWidget(export_);
  buttons->addWidget(cancel_);
  buttons->addWidget(close_);

  auto* top = new QVBoxLayout(this);
  top->addLayout(form);
  top->addWidget(progress_);
  top->addWidget(status_);
  top->addWidget(preview_, 1);
  top->addLayout(buttons);
}

io::AssetOptions ExportDialog::Options() const {
  io::AssetOptions o;
  o.ply = ply_->isChecked();
  o.obj = obj_->isChecked();
  o.glb = glb_->isChecked();
  o.texture = o.obj || o.glb;
  o.up = up_->currentData().toString() == "y" ? mesh::UpAxis::kY : mesh::UpAxis::kZ;
  o.atlas.texel_m = texel_->value() / 1000.0;
  o.triangles = std::size_t(triangles_->value());
  if (render_->isChecked()) o.render_width = render_w_->value(), o.render_height = render_h_->value();
  if (!tone_.isEmpty()) o.tone = tone_.toStdString();
  return o;
}

QString ExportDialog::Folder() const { return folder_->text(); }
QString ExportDialog::status_text() const { return status_->text(); }

void ExportDialog::Start() {
  const io::AssetOptions o = Options();
  try {
    o.Check();
  } catch (const std::exception& e) {
    status_->setText(tr("Cannot export: %1").arg(QString::fromStdString(e.what())));
    return;
  }
  if (Folder().trimmed().isEmpty()) {
    status_->setText(tr("Choose a folder to export into."));
    return;
  }
  SetBusy(true);
  progress_->setValue(0);
  status_->setText(tr("Exporting…"));
  emit exportRequested(Folder(), o);
}

void ExportDialog::SetBusy(bool busy) {
  busy_ = busy;
  for (QWidget* w : std::initializer_list<QWidget*>{folder_, ply_, obj_, glb_, up_, texel_, triangles_, render_, render_w_,
                                                    render_h_, export_, close_})
    w->setEnabled(!busy);
  cancel_->setEnabled(busy);
}

void ExportDialog::OnProgress(double fraction, const QString& stage) {
  progress_->setValue(int(100 * fraction));
  status_->setText(tr("Exporting: %1").arg(stage));
}

void ExportDialog::OnDone(bool ok, const QString& message, const QImage& preview) {
  SetBusy(false);
  if (ok) progress_->setValue(100);
  status_->setText(message);
  if (!preview.isNull()) {
    preview_image_ = preview;
    preview_->setPixmap(QPixmap::fromImage(preview).scaled(preview_->size(), Qt::KeepAspectRatio, Qt::SmoothTransformation));
  }
}

}  // namespace hdrf::gui
