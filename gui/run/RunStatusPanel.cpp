#include "run/RunStatusPanel.hpp"

#include <QHBoxLayout>
#include <cmath>

namespace talus::gui {

namespace {
constexpr double kWindow = 3.0;  ///< [s] of wall time the rates are measured over

QString duration(double s) {
  if (!std::isfinite(s) || s < 0) return "-";
  if (s < 60) return QString::number(s, 'f', 0) + " s";
  if (s < 3600) return QString("%1 min %2 s").arg(int(s / 60)).arg(int(std::fmod(s, 60)));
  return QString("%1 h %2 min").arg(int(s / 3600)).arg(int(std::fmod(s, 3600) / 60));
}
}  // namespace

RunStatusPanel::RunStatusPanel(QWidget* parent) : QWidget(parent) {
  auto* row = new QHBoxLayout(this);
  row->setContentsMargins(0, 0, 0, 0);
  state_ = new QLabel("idle");
  bar_ = new QProgressBar;
  bar_->setRange(0, 1000);
  bar_->setMinimumWidth(200);
  time_ = new QLabel;
  rate_ = new QLabel;
  eta_ = new QLabel;
  for (QWidget* w : {static_cast<QWidget*>(state_), static_cast<QWidget*>(bar_), static_cast<QWidget*>(time_),
                     static_cast<QWidget*>(rate_), static_cast<QWidget*>(eta_)})
    row->addWidget(w);
  clock_.start();
}

void RunStatusPanel::reset() {
  history_.clear();
  bar_->reset();  // no value, so no text (the format holds the last run's percentage)
  time_->clear();
  rate_->clear();
  eta_->clear();
}

void RunStatusPanel::showState(RunController::State s) {
  static const char* names[] = {"idle", "loading", "running", "paused", "ended"};
  state_->setText(names[static_cast<int>(s)]);
  if (s == RunController::State::Preparing) reset();
}

void RunStatusPanel::showResults(const QString& status, bool partial) {
  reset();
  state_->setText(partial ? "partial results (" + status + ")" : "results");
}

void RunStatusPanel::showProgress(const RunProgress& p) {
  const double span = p.endTime - p.startTime;
  const double frac = span > 0 ? std::clamp((p.time - p.startTime) / span, 0.0, 1.0) : 1.0;
  bar_->setValue(int(std::lround(1000 * frac)));
  bar_->setFormat(QString::number(100 * frac, 'f', 1) + " %");
  time_->setText(QString("t = %1 / %2 s").arg(p.time, 0, 'f', 2).arg(p.endTime, 0, 'f', 2));
  const double now = clock_.elapsed() / 1000.0;
  history_.push_back({now, p.time, p.steps});
  while (history_.size() > 2 && now - history_.front().wall > kWindow) history_.pop_front();
  const Sample& a = history_.front();
  const double dw = now - a.wall;
  if (dw > 0.05 && p.steps > a.steps) {
    const double stepsPerSecond = (p.steps - a.steps) / dw;
    const double simPerWall = (p.time - a.time) / dw;
    rate_->setText(QString("%1 steps/s").arg(stepsPerSecond, 0, 'f', 1));
    eta_->setText("ETA " + duration(simPerWall > 0 ? (p.endTime - p.time) / simPerWall : NAN));
  }
  if (frac >= 1.0) eta_->setText("done");
}

QString RunStatusPanel::text() const {
  return state_->text() + " " + time_->text() + " " + rate_->text() + " " + eta_->text();
}

}  // namespace talus::gui
