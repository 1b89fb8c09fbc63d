// The button beside the Device key's field: a menu of the OpenCL devices this machine has (listed
// when it opens, as `talus devices` lists them), and "automatic". Choosing one writes the device's
// name into the field; the run-file keeps a name, not an index, so it picks the same device on
// another machine whose device list is ordered differently.
#pragma once
#include <QToolButton>
#include <functional>

namespace talus::gui {

class DevicePicker : public QToolButton {
  Q_OBJECT

 public:
  /// `choose` receives the chosen selector ("" for automatic).
  explicit DevicePicker(std::function<void(const QString&)> choose, QWidget* parent = nullptr);

  /// Fills the menu with the devices found now (called when the menu opens).
  void refresh();

 private:
  std::function<void(const QString&)> choose_;
};

}  // namespace talus::gui
