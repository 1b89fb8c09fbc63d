// The time slider of an opened output folder: one position per series frame, a play/pause button
// that steps through them (a frame every `interval` ms, stopping at the last) and the frame's time.
#pragma once
#include <QLabel>
#include <QSlider>
#include <QTimer>
#include <QToolButton>
#include <QWidget>
#include <vector>

namespace talus::gui {

class ReplayBar : public QWidget {
  Q_OBJECT

 public:
  explicit ReplayBar(QWidget* parent = nullptr);
  /// The frames' times (empty: nothing to replay, the bar is disabled). Goes to frame 0.
  void setFrames(std::vector<double> times);
  void setFrame(int frame);
  int frame() const { return slider_->value(); }
  int frameCount() const { return static_cast<int>(times_.size()); }
  void play(bool on);
  bool isPlaying() const { return timer_.isActive(); }
  QSlider& slider() { return *slider_; }
  QToolButton& playButton() { return *play_; }
  QString timeText() const { return time_->text(); }

 signals:
  void frameChanged(int frame);

 private:
  void showTime();

  std::vector<double> times_;
  QToolButton* play_;
  QSlider* slider_;
  QLabel* time_;
  QTimer timer_;
};

}  // namespace talus::gui
