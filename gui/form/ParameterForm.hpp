// The run-file's parameters as a form generated from the key declarations: one collapsible section
// per registry section, one KeyField per key, a list of problems that name no key at the top. Edits
// go straight into the RunFileDocument. Opening a document expands the sections of the processes it
// switches on (Solids only with Include Initial Solids=1, ...) and those without a process, and
// collapses the rest; fields that do not matter for the values now (FieldRules) are disabled.
#pragma once
#include <QLabel>
#include <QScrollArea>
#include <QToolButton>
#include <map>
#include <string>
#include <vector>

#include "form/FieldRules.hpp"
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
  /// Whether a section ("Solids", ...) is expanded; false for an unknown one.
  bool sectionExpanded(const std::string& section) const;
  void setSectionExpanded(const std::string& section, bool expanded);

 signals:
  /// The user changed a value.
  void edited();

 private:
  void updateFolders();
  /// Enables the fields that matter for the document's values, disables the others.
  void updateApplicable();
  /// Expands the sections of processes that are on (and those without a process).
  void expandActiveSections();
  struct Section {
    QToolButton* header;
    QWidget* body;
  };

  const io::KeyRegistry& keys_;
  RunFileDocument* doc_ = nullptr;
  std::map<std::string, KeyField*> fields_;  // normalised name -> field
  std::map<std::string, QLabel*> labels_;    // normalised name -> its label
  std::map<std::string, Section> sections_;  // section name -> its header and body
  std::vector<FieldRule> rules_;
  QLabel* general_;
};

}  // namespace talus::gui
