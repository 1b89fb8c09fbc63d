#include "form/ReleaseAreaDialog.hpp"

#include <QCheckBox>
#include <QComboBox>
#include <QDialogButtonBox>
#include <QDir>
#include <QDoubleSpinBox>
#include <QFileDialog>
#include <QFileInfo>
#include <QFormLayout>
#include <QHBoxLayout>
#include <QLabel>
#include <QLineEdit>
#include <QPushButton>
#include <QVBoxLayout>

namespace talus::gui {

ReleaseAreaDialog::ReleaseAreaDialog(const QString& folder, double polygonArea, QWidget* parent)
    : QDialog(parent), polygonArea_(polygonArea) {
  setWindowTitle("Release area");
  material_ = new QComboBox;
  material_->addItem("water (Initial Fluid Height)");
  material_->addItem("solids (Initial Solid Height, two-phase model)");
  thickness_ = new QDoubleSpinBox;
  thickness_->setRange(0.001, 1e4);
  thickness_->setDecimals(3);
  thickness_->setValue(1.0);
  thickness_->setSuffix(" m");
  thickness_->setToolTip("vertical thickness of the released material in every cell inside the polygon");
  // A name that does not overwrite an existing file.
  QString name = "release_area.tif";
  for (int n = 2; QFileInfo::exists(QDir(folder).filePath(name)); ++n) name = QString("release_area_%1.tif").arg(n);
  path_ = new QLineEdit(QDir(folder).filePath(name));
  auto* browse = new QPushButton("...");
  connect(browse, &QPushButton::clicked, this, &ReleaseAreaDialog::browse);
  auto* pathRow = new QHBoxLayout;
  pathRow->addWidget(path_, 1);
  pathRow->addWidget(browse);
  add_ = new QCheckBox("add to the key's current map (else replace it)");
  volume_ = new QLabel;
  auto* form = new QFormLayout;
  form->addRow("material", material_);
  form->addRow("thickness", thickness_);
  form->addRow("raster file", pathRow);
  form->addRow("", add_);
  form->addRow("drawn", volume_);
  auto* buttons = new QDialogButtonBox(QDialogButtonBox::Save | QDialogButtonBox::Cancel);
  connect(buttons, &QDialogButtonBox::accepted, this, &QDialog::accept);
  connect(buttons, &QDialogButtonBox::rejected, this, &QDialog::reject);
  auto* layout = new QVBoxLayout(this);
  layout->addLayout(form);
  layout->addWidget(buttons);
  connect(thickness_, qOverload<double>(&QDoubleSpinBox::valueChanged), this, &ReleaseAreaDialog::updateVolume);
  updateVolume();
}

ReleaseAreaDialog::Material ReleaseAreaDialog::material() const { return Material(material_->currentIndex()); }
void ReleaseAreaDialog::setMaterial(Material m) { material_->setCurrentIndex(int(m)); }
double ReleaseAreaDialog::thickness() const { return thickness_->value(); }
void ReleaseAreaDialog::setThickness(double metres) { thickness_->setValue(metres); }
QString ReleaseAreaDialog::path() const { return path_->text().trimmed(); }
void ReleaseAreaDialog::setPath(const QString& path) { path_->setText(path); }
bool ReleaseAreaDialog::addToCurrentMap() const { return add_->isChecked(); }
void ReleaseAreaDialog::setAddToCurrentMap(bool on) { add_->setChecked(on); }

void ReleaseAreaDialog::browse() {
  const QString p = QFileDialog::getSaveFileName(this, "Release area raster", path(),
                                                 "GeoTIFF (*.tif *.tiff);;PCRaster (*.map)");
  if (!p.isEmpty()) path_->setText(p);
}

void ReleaseAreaDialog::updateVolume() {
  volume_->setText(QString("polygon %1 m², about %2 m³ at this thickness")
                       .arg(polygonArea_, 0, 'f', 0)
                       .arg(polygonArea_ * thickness(), 0, 'f', 0));
}

}  // namespace talus::gui
