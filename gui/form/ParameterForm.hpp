// The run-file's parameters as a form generated from the key declarations: one group per section,
// one KeyField per key, a list of problems that name no key at the top. Edits go straight into the
// RunFileDocument.
#pragma once
#include <QLabel>
#include <QScrollArea>
#include <map>
#include <string>

#include "form/KeyField.hpp"
#include "form/RunFileDocument.hpp"
#include "form/RunValidation.hpp"

namespace talus::gui {

class ParameterForm : public QScrollArea {
  Q_OBJECT

 public:
  explicit ParameterForm(const io::KeyRegistry& keys, QWidget* parent = nullptr);

  /// Shows and from now on edits `doc` (not owned; nullptr: an empty, disabled form).
  void setDocument(RunFileDocument* doc);
  /// Shows the problems of a validation next to their fields (and clears older ones).
  void showErrors(const ValidationResult& result);
  void clearErrors();
  /// The field of a key (by any spelling of its name), or nullptr.
  KeyField* field(const std::string& key) const;
  /// The problems listed at the top of the form.
  QString generalErrors() const { return general_->text(); }

 signals:
  /// The user changed a value.
  void edited();

 private:
  void updateFolders();

  const io::KeyRegistry& keys_;
  RunFileDocument* doc_ = nullptr;
  std::map<std::string, KeyField*> fields_;  // normalised name -> field
  QLabel* general_;
};

}  // namespace talus::gui
