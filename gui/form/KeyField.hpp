// The editor of one run-file key, generated from its declaration: a check box (flag), a list
// (choice), a text line (numbers, text), a folder or file picker (directory, map, with a preview of
// the map), the unit, a tooltip with help, range and default, and the key's errors under it.
// Angles are shown and typed in degrees and cohesion in Pa (the unit of the layers and the other
// stresses), while value() and setValue() keep the run-file's units (rad, kPa as OpenLISEM).
#pragma once
#include <QString>
#include <QWidget>
#include <utility>

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
  /// The unit the form shows a key's numbers in and the factor from the file's unit to it (rad:
  /// deg, 180/pi; kPa: Pa, 1000; else the file's unit and 1).
  static std::pair<QString, double> shownUnit(const io::KeySpec& spec);
  /// The text the editor shows (numbers in the shown unit).
  QString shownText() const;
  /// Types `text` (numbers in the shown unit) into the editor, as the user would, emitting edited().
  void typeText(const QString& text);
  /// The unit next to the editor ("" when none).
  QString unitText() const;
  /// Enables the field or disables it, saying why in its tooltip (a field that does not matter for
  /// the values the form holds now: a map of a process that is off).
  void setApplies(bool applies, const QString& reason);

 signals:
  void edited(const QString& value);

 private:
  void browse();
  void refreshPreview();
  void refreshUnit();

  io::KeySpec spec_;
  QString folder_;
  QCheckBox* check_ = nullptr;
  QComboBox* combo_ = nullptr;
  QLineEdit* line_ = nullptr;
  QLabel* error_ = nullptr;
  QLabel* unit_ = nullptr;
  QString shown_;        ///< the unit numbers are shown in
  double toShown_ = 1;   ///< file unit -> shown unit
  MapPreview* preview_ = nullptr;
};

}  // namespace talus::gui
