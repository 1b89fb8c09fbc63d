#include "form/KeyField.hpp"

#include "form/DevicePicker.hpp"

#include <QCheckBox>
#include <QComboBox>
#include <QDir>
#include <QFileDialog>
#include <QHBoxLayout>
#include <QLabel>
#include <QLineEdit>
#include <QToolButton>
#include <QVBoxLayout>
#include <tuple>

#include "form/DevicePicker.hpp"
#include "form/MapPreview.hpp"

namespace talus::gui {

namespace {

bool isNumber(const QString& s) {
  bool ok = false;
  s.toDouble(&ok);
  return ok;
}

constexpr double kPi = 3.14159265358979323846;

/// A number text converted by `factor` (6 significant digits); any other text as it is.
QString convert(const QString& text, double factor) {
  bool ok = false;
  const double v = text.trimmed().toDouble(&ok);
  return ok && factor != 1 ? QString::number(v * factor, 'g', 6) : text;
}

}  // namespace

QString KeyField::describe(const io::KeySpec& spec) {
  QString t = "<b>" + QString::fromStdString(spec.name).toHtmlEscaped() + "</b> (" +
              QString::fromStdString(io::keyTypeName(spec.type)) + ")<br>" +
              QString::fromStdString(spec.help).toHtmlEscaped();
  if (!spec.unit.empty()) t += "<br>unit: " + QString::fromStdString(spec.unit == "-" ? "dimensionless" : spec.unit);
  if (const auto [shown, factor] = shownUnit(spec); factor != 1)
    t += " (the run-file's; typed and shown here in " + shown + (spec.type == io::KeyType::Map ? ", a map file holds " + QString::fromStdString(spec.unit) : "") + ")";
  const std::string range = io::rangeText(spec);
  if (!range.empty()) t += "<br>valid range: " + QString::fromStdString(range);
  if (!spec.choices.empty()) {
    QStringList c;
    for (const auto& s : spec.choices) c << QString::fromStdString(s);
    t += "<br>one of: " + c.join(", ");
  }
  t += spec.required ? "<br>required" : "<br>default: " + (spec.defaultValue.empty() ? "(empty)" : QString::fromStdString(spec.defaultValue));
  if (spec.type == io::KeyType::Map) t += "<br>a raster file, or a number for a uniform map; may end in =multiplier";
  return t;
}

std::pair<QString, double> KeyField::shownUnit(const io::KeySpec& spec) {
  if (spec.unit == "rad") return {"deg", 180 / kPi};
  if (spec.unit == "kPa") return {"Pa", 1000};
  return {QString::fromStdString(spec.unit), 1};
}

KeyField::KeyField(const io::KeySpec& spec, QWidget* parent) : QWidget(parent), spec_(spec) {
  std::tie(shown_, toShown_) = shownUnit(spec);
  auto* column = new QVBoxLayout(this);
  column->setContentsMargins(0, 0, 0, 0);
  column->setSpacing(2);
  auto* row = new QHBoxLayout;
  column->addLayout(row);
  setToolTip(describe(spec));
  switch (spec.type) {
    case io::KeyType::Flag:
      check_ = new QCheckBox;
      row->addWidget(check_);
      connect(check_, &QCheckBox::toggled, this, [this] { emit edited(value()); });
      break;
    case io::KeyType::Choice:
      combo_ = new QComboBox;
      for (const auto& c : spec.choices) combo_->addItem(QString::fromStdString(c));
      row->addWidget(combo_, 1);
      connect(combo_, QOverload<int>::of(&QComboBox::activated), this, [this] { emit edited(value()); });
      break;
    default:
      line_ = new QLineEdit;
      line_->setPlaceholderText(spec.required ? "required" : convert(QString::fromStdString(spec.defaultValue), toShown_));
      row->addWidget(line_, 1);
      connect(line_, &QLineEdit::textEdited, this, [this] {
        refreshPreview();
        refreshUnit();
        emit edited(value());
      });
      break;
  }
  if (!spec.unit.empty() && spec.unit != "-") {
    unit_ = new QLabel(shown_);
    row->addWidget(unit_);
  }
  if (spec.name == "Device") {
    row->addWidget(new DevicePicker([this](const QString& selector) {
      line_->setText(selector);
      emit edited(value());
    }));
  }
  if (spec.type == io::KeyType::Directory || spec.type == io::KeyType::Map) {
    auto* pick = new QToolButton;
    pick->setText("...");
    pick->setToolTip(spec.type == io::KeyType::Map ? "choose a raster file" : "choose a folder");
    row->addWidget(pick);
    connect(pick, &QToolButton::clicked, this, [this] { browse(); });
  }
  error_ = new QLabel;
  error_->setStyleSheet("color: #c0392b;");
  error_->setWordWrap(true);
  error_->setTextInteractionFlags(Qt::TextSelectableByMouse);
  error_->setVisible(false);
  column->addWidget(error_);
  if (spec.type == io::KeyType::Map) {
    preview_ = new MapPreview;
    column->addWidget(preview_);
  }
}

void KeyField::setValue(const QString& value) {
  const QSignalBlocker block(this);
  if (check_) {
    const QString v = value.trimmed().toLower();
    const QSignalBlocker b(check_);
    check_->setChecked(v == "1" || v == "true" || v == "yes" || v == "on");
  } else if (combo_) {
    const QSignalBlocker b(combo_);
    const QString v = value.trimmed().toLower();
    if (combo_->findText(v) < 0) combo_->addItem(v);  // an invalid value stays visible next to its error
    combo_->setCurrentText(v);
  } else {
    line_->setText(convert(value, toShown_));
    refreshPreview();
    refreshUnit();
  }
}

QString KeyField::value() const {
  if (check_) return check_->isChecked() ? "1" : "0";
  if (combo_) return combo_->currentText();
  return convert(line_->text(), 1 / toShown_);
}

QString KeyField::shownText() const { return line_ ? line_->text() : value(); }

void KeyField::typeText(const QString& text) {
  if (!line_) return;
  line_->setText(text);
  emit line_->textEdited(text);
}

QString KeyField::unitText() const { return unit_ ? unit_->text() : QString(); }

void KeyField::refreshUnit() {
  // A map file keeps the file's unit; numbers are shown converted.
  if (unit_ && line_)
    unit_->setText(line_->text().trimmed().isEmpty() || isNumber(line_->text().trimmed()) ? shown_ : QString::fromStdString(spec_.unit));
}

void KeyField::setApplies(bool applies, const QString& reason) {
  setEnabled(applies);
  setToolTip(applies ? describe(spec_) : describe(spec_) + "<br><i>not used now: " + reason.toHtmlEscaped() + "</i>");
}

void KeyField::setError(const QString& error) {
  error_->setText(error);
  error_->setVisible(!error.isEmpty());
  QWidget* editor = check_ ? static_cast<QWidget*>(check_) : combo_ ? static_cast<QWidget*>(combo_) : line_;
  editor->setStyleSheet(error.isEmpty() ? "" : "border: 1px solid #c0392b;");
}

QString KeyField::error() const { return error_->text(); }

void KeyField::setFolder(const QString& folder) {
  folder_ = folder;
  refreshPreview();
}

void KeyField::browse() {
  QString chosen;
  if (spec_.type == io::KeyType::Directory) {
    chosen = QFileDialog::getExistingDirectory(this, QString::fromStdString(spec_.name), folder_);
  } else {
    chosen = QFileDialog::getOpenFileName(this, QString::fromStdString(spec_.name), folder_,
                                          "Rasters (*.tif *.tiff *.map *.asc);;All files (*)");
  }
  if (chosen.isEmpty()) return;
  // Keep paths relative to the folder they resolve against when the file lies below it.
  const QString rel = QDir(folder_).relativeFilePath(chosen);
  line_->setText(rel.startsWith("..") ? chosen : rel);
  refreshPreview();
  emit edited(value());
}

void KeyField::refreshPreview() {
  if (!preview_ || !line_) return;
  QString v = line_->text().section('=', 0, 0).trimmed();
  if (v.isEmpty() || isNumber(v)) {
    preview_->showRaster({});
    return;
  }
  v.replace('\\', '/');
  preview_->showRaster(QDir::isAbsolutePath(v) ? v : QDir(folder_).filePath(v));
}

}  // namespace talus::gui
