#include "form/ParameterForm.hpp"

#include <QDir>
#include <QFormLayout>
#include <QGroupBox>
#include <QVBoxLayout>
#include <vector>

namespace talus::gui {

namespace {
constexpr const char* kMapDirectory = "Map Directory";
}

ParameterForm::ParameterForm(const io::KeyRegistry& keys, QWidget* parent) : QScrollArea(parent), keys_(keys) {
  auto* body = new QWidget;
  auto* column = new QVBoxLayout(body);
  general_ = new QLabel;
  general_->setStyleSheet("color: #c0392b;");
  general_->setWordWrap(true);
  general_->setTextInteractionFlags(Qt::TextSelectableByMouse);
  general_->setVisible(false);
  column->addWidget(general_);
  std::vector<std::string> sections;
  for (const auto& k : keys.keys())
    if (std::find(sections.begin(), sections.end(), k.section) == sections.end()) sections.push_back(k.section);
  for (const std::string& section : sections) {
    // A section: a header that expands and collapses it, and its fields in a framed body.
    auto* header = new QToolButton;
    header->setText(QString::fromStdString(section.empty() ? "Other" : section));
    header->setCheckable(true);
    header->setChecked(true);
    header->setToolButtonStyle(Qt::ToolButtonTextBesideIcon);
    header->setArrowType(Qt::DownArrow);
    header->setAutoRaise(true);
    header->setStyleSheet("font-weight: bold;");
    auto* box = new QGroupBox;
    connect(header, &QToolButton::toggled, box, [header, box](bool on) {
      header->setArrowType(on ? Qt::DownArrow : Qt::RightArrow);
      box->setVisible(on);
    });
    sections_[section] = {header, box};
    auto* form = new QFormLayout(box);
    form->setFieldGrowthPolicy(QFormLayout::AllNonFixedFieldsGrow);
    for (const auto& spec : keys.keys()) {
      if (spec.section != section) continue;
      auto* f = new KeyField(spec);
      auto* label = new QLabel(QString::fromStdString(spec.name) + (spec.required ? " *" : ""));
      label->setToolTip(KeyField::describe(spec));
      form->addRow(label, f);
      fields_[io::normalizeKeyName(spec.name)] = f;
      labels_[io::normalizeKeyName(spec.name)] = label;
      connect(f, &KeyField::edited, this, [this, f, name = spec.name](const QString& v) {
        if (!doc_) return;
        doc_->setValue(name, v.toStdString());
        f->setError({});
        if (io::normalizeKeyName(name) == io::normalizeKeyName(kMapDirectory)) updateFolders();
        updateApplicable();
        emit edited();
      });
    }
    column->addWidget(header);
    column->addWidget(box);
  }
  rules_ = fieldRules(keys);
  column->addStretch(1);
  setWidget(body);
  setWidgetResizable(true);
  setMinimumWidth(380);
  setEnabled(false);
}

void ParameterForm::setDocument(RunFileDocument* doc) {
  doc_ = doc;
  setEnabled(doc != nullptr);
  clearErrors();
  if (!doc) return;
  for (const auto& spec : keys_.keys()) field(spec.name)->setValue(QString::fromStdString(doc->value(spec.name)));
  updateFolders();
  updateApplicable();
  expandActiveSections();
}

void ParameterForm::updateApplicable() {
  if (!doc_) return;
  const ValueOf value = [this](const std::string& key) { return doc_->value(key); };
  for (const FieldRule& rule : rules_) {
    const bool applies = rule.applies(value);
    field(rule.key)->setApplies(applies, QString::fromStdString(rule.reason));
    labels_.at(io::normalizeKeyName(rule.key))->setEnabled(applies);
  }
}

void ParameterForm::expandActiveSections() {
  for (auto& [name, section] : sections_) {
    const std::vector<std::string> processes = sectionProcesses(keys_, name);
    bool on = processes.empty() && !sectionUnread(keys_, name);
    for (const std::string& flag : processes) on = on || isOn(doc_->value(flag));
    section.header->setChecked(on);
  }
}

bool ParameterForm::sectionExpanded(const std::string& section) const {
  auto it = sections_.find(section);
  return it != sections_.end() && it->second.header->isChecked();
}

void ParameterForm::setSectionExpanded(const std::string& section, bool expanded) {
  if (auto it = sections_.find(section); it != sections_.end()) it->second.header->setChecked(expanded);
}

void ParameterForm::updateFolders() {
  if (!doc_) return;
  const QString base = QString::fromStdString(doc_->baseDir());
  QString mapDir = QString::fromStdString(doc_->value(kMapDirectory)).replace('\\', '/');
  mapDir = QDir::cleanPath(QDir::isAbsolutePath(mapDir) ? mapDir : QDir(base).filePath(mapDir));
  for (const auto& spec : keys_.keys())
    field(spec.name)->setFolder(spec.type == io::KeyType::Map ? mapDir : base);
}

void ParameterForm::clearErrors() {
  for (auto& [name, f] : fields_) f->setError({});
  general_->clear();
  general_->setVisible(false);
}

void ParameterForm::showErrors(const ValidationResult& result) {
  clearErrors();
  for (const auto& [name, text] : result.fieldErrors)
    if (KeyField* f = field(name)) f->setError(QString::fromStdString(text));
  QStringList general;
  for (const auto& g : result.generalErrors) general << QString::fromStdString(g);
  general_->setText(general.join("\n"));
  general_->setVisible(!general.isEmpty());
  // Open the sections with problems, and bring the first problem into view.
  for (const auto& [name, text] : result.fieldErrors)
    if (const io::KeySpec* spec = keys_.find(name)) setSectionExpanded(spec->section, true);
  for (const auto& spec : keys_.keys())
    if (KeyField* f = field(spec.name); f && !f->error().isEmpty()) {
      ensureWidgetVisible(f);
      break;
    }
}

KeyField* ParameterForm::field(const std::string& key) const {
  auto it = fields_.find(io::normalizeKeyName(key));
  return it == fields_.end() ? nullptr : it->second;
}

}  // namespace talus::gui
