// The editor of one run-file key, generated from its declaration: a check box (flag), a list
// (choice), a text line (numbers, text), a folder or file picker (directory, map, with a preview of
// the map), the unit, a tooltip with help, range and default, and the key's errors under it.
#pragma once
#include <QString>
#include <QWidget>

#include "io/KeyRegistry.hpp"

class QCheckBox;
class QComboBox;
class QLabel;
class QLineEdit;

namespace talus::gui {

class MapPreview;

class KeyField : public QWidget {
  Q_OBJECT

 public:
  KeyField(const io::KeySpec& spec, QWidget* parent = nullptr);

  const io::KeySpec& spec() const { return spec_; }
  /// Shows a value text (as the run-file has it) without emitting edited().
  void setValue(const QString& value);
  QString value() const;
  /// Shows the key's problems under the editor (empty: none).
  void setError(const QString& error);
  QString error() const;
  /// The folder file pickers start in and relative map paths resolve against.
  void setFolder(const QString& folder);
  /// A tooltip-style description: help, unit, range, default.
  static QString describe(const io::KeySpec& spec);

 signals:
  void edited(const QString& value);

 private:
  void browse();
  void refreshPreview();

  io::KeySpec spec_;
  QString folder_;
  QCheckBox* check_ = nullptr;
  QComboBox* combo_ = nullptr;
  QLineEdit* line_ = nullptr;
  QLabel* error_ = nullptr;
  MapPreview* preview_ = nullptr;
};

}  // namespace talus::gui
