#include "form/DevicePicker.hpp"

#include <QMenu>

#include "compute/Device.hpp"

namespace talus::gui {

DevicePicker::DevicePicker(std::function<void(const QString&)> choose, QWidget* parent)
    : QToolButton(parent), choose_(std::move(choose)) {
  setText("...");
  setToolTip("choose an OpenCL device of this machine");
  setPopupMode(QToolButton::InstantPopup);
  setMenu(new QMenu(this));
  connect(menu(), &QMenu::aboutToShow, this, &DevicePicker::refresh);
}

void DevicePicker::refresh() {
  menu()->clear();
  menu()->addAction("automatic (first GPU, else the first device)", this, [this] { choose_({}); });
  std::vector<compute::DeviceInfo> devices;
  try {
    devices = compute::listDevices();
  } catch (const std::exception& e) {
    menu()->addAction(QString("cannot list the devices: %1").arg(e.what()))->setEnabled(false);
    return;
  }
  if (devices.empty()) menu()->addAction("no OpenCL device found")->setEnabled(false);
  for (const compute::DeviceInfo& d : devices) {
    const QString name = QString::fromStdString(d.name);
    menu()->addAction(QString::fromStdString(d.describe()), this, [this, name] { choose_(name); });
  }
}

}  // namespace talus::gui
