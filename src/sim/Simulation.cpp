#include "sim/Simulation.hpp"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "core/Error.hpp"

namespace talus::sim {
namespace {

constexpr const char* kCsvHeader =
    "step,time_s,dt_s,volume_m3,outflow_m3,cumulative_outflow_m3,balance_error,kinetic_energy_J,max_wave_speed_m_s,"
    "wall_s";
constexpr double kWaterDensity = 1000.0;  // [kg/m^3] to report kinetic energy in joules

std::string jsonEscape(const std::string& s) {
  std::string o;
  for (char c : s) {
    if (c == '"' || c == '\\') o += '\\';
    if (static_cast<unsigned char>(c) < 0x20) continue;
    o += c;
  }
  return o;
}

}  // namespace

Simulation::Simulation(const Scene& scene, const io::RunConfig& config, const std::string& outDir, bool overwrite)
    : scene_(scene), config_(config) {
  out_ = std::make_unique<OutputWriter>(outDir.empty() ? scene.outputDir : outDir, scene.dem, scene.format, overwrite);
  out_->writeText("run.resolved.run", config.echo());
  ctx_ = compute::Context::create(scene.device, compute::parsePrecision(scene.precision));
  solver_ = std::make_unique<flow::FlowSolver>(*ctx_, scene.dem.grid, scene.settings);
  solver_->setInput(scene.flow, scene.startTime);
  for (uint8_t v : scene.dem.valid) domainCells_ += v;
}

void Simulation::checkHealth(long long step, double dt) {
  const flow::FlowDiagnostics& d = solver_->diagnostics();
  std::ostringstream why;
  if (!std::isfinite(d.volume) || !std::isfinite(d.maxSpeed) || !std::isfinite(d.kinetic)) {
    // Locate the first non-finite cell for the diagnosis (a full read-back only on failure).
    const std::vector<double> h = solver_->h(), qx = solver_->qx(), qy = solver_->qy();
    const Grid& g = scene_.dem.grid;
    for (int j = 0; j < g.ny && why.str().empty(); ++j)
      for (int i = 0; i < g.nx; ++i) {
        const std::size_t k = g.index(i, j);
        if (!std::isfinite(h[k]) || !std::isfinite(qx[k]) || !std::isfinite(qy[k])) {
          why << "non-finite state (h = " << h[k] << ", qx = " << qx[k] << ", qy = " << qy[k] << ") in cell (column "
              << i << ", row " << j << ") at x = " << g.cellX(i) << ", y = " << g.cellY(j);
          break;
        }
      }
    if (why.str().empty()) why << "non-finite diagnostics (volume " << d.volume << ")";
  } else if (d.minH < 0) {
    why << "negative thickness " << d.minH << " m";
  }
  if (why.str().empty()) return;
  std::ostringstream o;
  o << "simulation unstable at t = " << solver_->time() << " s (step " << step << ", dt = " << dt << " s): " << why.str();
  failure_ = o.str();
  throw SimulationError(failure_);
}

void Simulation::writeReport(int index) {
  if (!scene_.reportSeries) return;
  char hName[64], vName[64];
  std::snprintf(hName, sizeof hName, "series/hf_%04d", index);
  std::snprintf(vName, sizeof vName, "series/vf_%04d", index);
  const std::vector<double> h = solver_->h(), qx = solver_->qx(), qy = solver_->qy();
  std::vector<double> v(h.size(), 0.0);
  for (std::size_t k = 0; k < h.size(); ++k)
    if (h[k] > scene_.settings.hDry) v[k] = std::hypot(qx[k], qy[k]) / h[k];
  out_->writeMap(hName, h);
  out_->writeMap(vName, v);
  std::ostringstream line;
  line.precision(12);
  line << index << "," << solver_->time() << "," << hName << "," << vName << "\n";
  seriesIndex_ += line.str();
  out_->writeText("series/index.csv", seriesIndex_);
}

RunSummary Simulation::run(const std::function<void(const Progress&)>& onProgress) {
  using Clock = std::chrono::steady_clock;
  const auto start = Clock::now();
  auto wall = [&] { return std::chrono::duration<double>(Clock::now() - start).count(); };
  RunSummary s;
  s.initialVolume = solver_->diagnostics().volume;
  const double t0 = scene_.startTime, tEnd = scene_.endTime, interval = scene_.reportInterval;
  int reportIndex = 0;
  writeReport(reportIndex++);
  double nextReport = t0 + interval;
  try {
    while (solver_->time() < tEnd * (1 - 1e-15)) {
      const double t = solver_->time();
      const double target = std::min(nextReport, tEnd);
      double dt = solver_->stableDt();
      if (std::isnan(dt)) checkHealth(s.steps, dt);
      // Land exactly on report and end times (spec §4: dt clipped to output times).
      if (!(dt < target - t)) dt = target - t;
      solver_->step(dt);
      if (std::fabs(solver_->time() - target) <= 1e-12 * std::max(1.0, std::fabs(target))) solver_->setTime(target);
      ++s.steps;
      checkHealth(s.steps, dt);
      const flow::FlowDiagnostics& d = solver_->diagnostics();
      s.totalOutflow += d.outflow;
      const double balance = s.initialVolume > 0 ? (d.volume + s.totalOutflow - s.initialVolume) / s.initialVolume : 0;
      char line[400];
      std::snprintf(line, sizeof line, "%lld,%.9g,%.6g,%.12g,%.6g,%.12g,%.3e,%.6g,%.6g,%.4f", s.steps, solver_->time(), dt,
                    d.volume, d.outflow, s.totalOutflow, balance, kWaterDensity * d.kinetic, d.maxSpeed, wall());
      out_->appendDiagnostics(kCsvHeader, line);
      if (solver_->time() >= nextReport * (1 - 1e-15)) {
        writeReport(reportIndex++);
        nextReport = t0 + reportIndex * interval;
      }
      if (onProgress) onProgress({solver_->time(), t0, tEnd, s.steps, wall(), dt, &d});
    }
  } catch (const SimulationError&) {
    s.wallSeconds = wall();
    s.simulatedSeconds = solver_->time() - t0;
    writeFinal(s, true);
    throw;
  }
  s.wallSeconds = wall();
  s.simulatedSeconds = solver_->time() - t0;
  s.finalVolume = solver_->diagnostics().volume;
  s.cellUpdatesPerSecond = s.wallSeconds > 0 ? static_cast<double>(domainCells_) * s.steps / s.wallSeconds : 0;
  s.volumeBalanceError =
      s.initialVolume > 0 ? (s.finalVolume + s.totalOutflow - s.initialVolume) / s.initialVolume : 0.0;
  writeFinal(s, false);
  return s;
}

void Simulation::writeFinal(const RunSummary& s, bool failed) {
  // On failure the maxima and arrival so far are still written; the final state may hold NaN.
  const double never = -1.0;
  if (!failed) out_->writeMap("hffinal", solver_->h());
  out_->writeMap("hfmax", solver_->hMax());
  out_->writeMap("vfmax", solver_->vMax());
  out_->writeMap("tarrival", solver_->arrival(), &never);
  out_->writeText("summary.json", summaryJson(s, failed));
}

std::string Simulation::summaryJson(const RunSummary& s, bool failed) const {
  std::ostringstream o;
  o.precision(12);
  const compute::DeviceInfo& d = ctx_->device();
  const Grid& g = scene_.dem.grid;
  o << "{\n  \"talus_version\": \"0.1.0\",\n  \"run_file\": \"" << jsonEscape(scene_.runFile) << "\",\n"
    << "  \"status\": \"" << (failed ? "failed" : "completed") << "\",\n";
  if (failed) o << "  \"failure\": \"" << jsonEscape(failure_) << "\",\n";
  o << "  \"device\": \"" << jsonEscape(d.name) << "\",\n  \"platform\": \"" << jsonEscape(d.platformName) << "\",\n"
    << "  \"precision\": \"" << compute::precisionName(ctx_->precision()) << "\",\n"
    << "  \"grid\": {\"nx\": " << g.nx << ", \"ny\": " << g.ny << ", \"dx\": " << g.dx
    << ", \"domain_cells\": " << domainCells_ << "},\n"
    << "  \"start_time_s\": " << scene_.startTime << ",\n  \"end_time_s\": " << scene_.endTime << ",\n"
    << "  \"simulated_s\": " << s.simulatedSeconds << ",\n  \"steps\": " << s.steps << ",\n"
    << "  \"wall_time_s\": " << s.wallSeconds << ",\n  \"cell_updates_per_s\": " << s.cellUpdatesPerSecond << ",\n"
    << "  \"volume\": {\"initial_m3\": " << s.initialVolume << ", \"final_m3\": " << s.finalVolume
    << ", \"outflow_m3\": " << s.totalOutflow << ", \"balance_error\": " << s.volumeBalanceError << "}\n}\n";
  return o.str();
}

}  // namespace talus::sim
