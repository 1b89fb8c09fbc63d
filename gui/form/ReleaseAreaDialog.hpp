// Asks what a drawn release area holds: water or solids, how thick, the raster file it is saved to,
// and whether it adds to the key's current map or replaces it.
#pragma once
#include <QDialog>

class QCheckBox;
class QComboBox;
class QDoubleSpinBox;
class QLineEdit;
class QLabel;

namespace talus::gui {

class ReleaseAreaDialog : public QDialog {
  Q_OBJECT

 public:
  enum class Material { Water = 0, Solids = 1 };

  /// `folder`: where the file goes by default (the run-file's folder). `polygonArea` [m^2] is
  /// shown so the user sees what was drawn.
  ReleaseAreaDialog(const QString& folder, double polygonArea, QWidget* parent = nullptr);

  Material material() const;
  void setMaterial(Material m);
  double thickness() const;
  void setThickness(double metres);
  QString path() const;
  void setPath(const QString& path);
  /// Add to the key's current map (cells outside the polygon keep its values) instead of replacing it.
  bool addToCurrentMap() const;
  void setAddToCurrentMap(bool on);

 private:
  void browse();
  void updateVolume();

  double polygonArea_;
  QComboBox* material_;
  QDoubleSpinBox* thickness_;
  QLineEdit* path_;
  QCheckBox* add_;
  QLabel* volume_;
};

}  // namespace talus::gui
