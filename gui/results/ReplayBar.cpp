#include "results/ReplayBar.hpp"

#include <QHBoxLayout>

namespace talus::gui {

ReplayBar::ReplayBar(QWidget* parent) : QWidget(parent) {
  play_ = new QToolButton;
  play_->setText("Play");
  play_->setCheckable(true);
  play_->setToolTip("play the series of the opened results");
  slider_ = new QSlider(Qt::Horizontal);
  slider_->setMinimumWidth(140);
  slider_->setToolTip("report time of the series frame shown");
  time_ = new QLabel;
  time_->setMinimumWidth(110);
  auto* row = new QHBoxLayout(this);
  row->setContentsMargins(4, 0, 4, 0);
  row->addWidget(new QLabel("Results"));
  row->addWidget(play_);
  row->addWidget(slider_, 1);
  row->addWidget(time_);
  timer_.setInterval(500);
  connect(play_, &QToolButton::toggled, this, &ReplayBar::play);
  connect(slider_, &QSlider::valueChanged, this, [this](int k) {
    showTime();
    emit frameChanged(k);
  });
  connect(&timer_, &QTimer::timeout, this, [this] {
    if (frame() + 1 >= frameCount()) play(false);
    else setFrame(frame() + 1);
  });
  setFrames({});
}

void ReplayBar::setFrames(std::vector<double> times) {
  play(false);
  times_ = std::move(times);
  {
    const QSignalBlocker block(slider_);
    slider_->setRange(0, std::max(0, frameCount() - 1));
    slider_->setValue(0);
  }
  setEnabled(frameCount() > 1);
  showTime();
}

void ReplayBar::setFrame(int frame) { slider_->setValue(frame); }

void ReplayBar::play(bool on) {
  if (on && frame() + 1 >= frameCount()) setFrame(0);  // played to the end: from the start again
  if (on && frameCount() > 1) timer_.start();
  else timer_.stop();
  const QSignalBlocker block(play_);
  play_->setChecked(timer_.isActive());
  play_->setText(timer_.isActive() ? "Pause" : "Play");
}

void ReplayBar::showTime() {
  if (times_.empty()) {
    time_->setText("no series");
    return;
  }
  time_->setText(QString("t = %1 s (%2/%3)").arg(times_[std::size_t(frame())], 0, 'g', 6).arg(frame() + 1).arg(frameCount()));
}

}  // namespace talus::gui
