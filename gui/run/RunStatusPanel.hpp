// The run's progress for the status bar: a progress bar over simulated time, the simulated time,
// steps per second and the estimated time to the end (both measured over the last seconds, so
// pauses do not distort them).
#pragma once
#include <QElapsedTimer>
#include <QLabel>
#include <QProgressBar>
#include <QWidget>
#include <deque>

#include "run/RunController.hpp"

namespace talus::gui {

class RunStatusPanel : public QWidget {
  Q_OBJECT

 public:
  explicit RunStatusPanel(QWidget* parent = nullptr);
  void showProgress(const RunProgress& p);
  void showState(RunController::State s);
  /// Opened results instead of a run: "results", or "partial results (STATUS)" for a run that did
  /// not complete.
  void showResults(const QString& status, bool partial);
  /// Forgets the rate history (a new run).
  void reset();
  QString text() const;

 private:
  struct Sample {
    double wall, time;
    long long steps;
  };
  QProgressBar* bar_;
  QLabel *time_, *rate_, *eta_, *state_;
  QElapsedTimer clock_;
  std::deque<Sample> history_;
};

}  // namespace talus::gui
