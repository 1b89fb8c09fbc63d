// The run's outputs at report times and at its end: the series maps of each phase, the final
// maps and maxima, the particle layers and summary.json (the step loop is in Simulation.cpp).
#include "sim/Simulation.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "core/Error.hpp"

namespace talus::sim {
namespace {

std::string jsonEscape(const std::string& s) {
  std::string o;
  for (char c : s) {
    if (c == '"' || c == '\\') o += '\\';
    if (static_cast<unsigned char>(c) < 0x20) continue;
    o += c;
  }
  return o;
}

/// A number of summary.json: JSON has no NaN or infinity, so a non-finite value (a run that went
/// unstable) is written as null, and the file stays readable beside its "failure".
struct JsonNum {
  double v;
};
std::ostream& operator<<(std::ostream& o, JsonNum n) {
  if (std::isfinite(n.v)) return o << n.v;
  return o << "null";
}

/// Speed maps of one phase: |q| / h where the layer is thicker than the dry threshold, else 0.
std::vector<double> speedMap(const std::vector<double>& h, const std::vector<double>& qx, const std::vector<double>& qy,
                             double hDry) {
  std::vector<double> v(h.size(), 0.0);
  for (std::size_t k = 0; k < h.size(); ++k)
    if (h[k] > hDry) v[k] = std::hypot(qx[k], qy[k]) / h[k];
  return v;
}

/// Solid speed maps with the solids' own desingularised velocity (solid_velocity in
/// kernels/flow/debris_closures.cl): below the film thickness e the speed is
/// sqrt(2) h |q| / sqrt(h^4 + max(h^4, e^4)), as the solver and the vsmax map use it.
std::vector<double> solidSpeedMap(const std::vector<double>& h, const std::vector<double>& qx,
                                  const std::vector<double>& qy, double hDry, double film) {
  std::vector<double> v(h.size(), 0.0);
  const double e = std::max(hDry, film), e4 = e * e * e * e;
  for (std::size_t k = 0; k < h.size(); ++k) {
    if (!(h[k] > hDry)) continue;
    const double q = std::hypot(qx[k], qy[k]);
    if (h[k] >= e) {
      v[k] = q / h[k];
    } else {
      const double h4 = h[k] * h[k] * h[k] * h[k];
      v[k] = std::sqrt(2.0) * h[k] * q / std::sqrt(h4 + std::max(h4, e4));
    }
  }
  return v;
}

}  // namespace

double Simulation::speedThickness() const {
  // The rule of the maxima maps (kernels/flow/track.cl, debris_track_maxima): speeds of water above
  // Minimum Flow Height; in the two-phase model, of layers thicker than the Arrival Threshold.
  return solver_->twoPhase() ? std::max(scene_.settings.arrivalH, scene_.settings.hDry) : scene_.settings.hDry;
}

void Simulation::writeReport() {
  const int index = reportIndex_++;
  const SeriesSelection& sel = scene_.series;
  if (!sel.any) return;
  // Series of each phase the scene can hold: a dry granular run writes no all-zero fluid series
  // (fluid appears only from the initial water or from particles releasing what they hold).
  std::vector<std::string> names;
  auto write = [&](const char* prefix, const std::vector<double>& values) {
    const std::string name = seriesName(sel, prefix, index);
    if (sel.lisemNames) out_->writeMapAs(name, values);
    else out_->writeMap(name, values);
    names.push_back(name);
  };
  const double hDry = speedThickness();
  const bool twoPhase = solver_->twoPhase();
  std::vector<double> h, hs;
  if (fluidSeries_ || sel.ht || sel.vt || sel.sf) h = solver_->h();
  if (twoPhase) hs = solver_->hs();
  if (fluidSeries_ && sel.hf) write("hf", h);
  if (fluidSeries_ && sel.vf) write("vf", speedMap(h, solver_->qx(), solver_->qy(), hDry));
  if (twoPhase && sel.hs) write("hs", hs);
  if (twoPhase && sel.vs)
    write("vs", solidSpeedMap(hs, solver_->qsx(), solver_->qsy(), hDry, scene_.settings.debris.filmThickness));
  if (twoPhase && (sel.sf || sel.ht || sel.vt)) {
    std::vector<double> total(h.size()), fraction(h.size(), 0.0), speed(h.size(), 0.0);
    const std::vector<double> vf = speedMap(h, solver_->qx(), solver_->qy(), hDry);
    const std::vector<double> vs =
        solidSpeedMap(hs, solver_->qsx(), solver_->qsy(), hDry, scene_.settings.debris.filmThickness);
    for (std::size_t k = 0; k < h.size(); ++k) {
      total[k] = h[k] + hs[k];
      if (total[k] > 0) {
        fraction[k] = hs[k] / total[k];
        // The thickness-averaged speed its label names (OpenLISEM's code writes h_s v_s + h_f v_f,
        // modelreport.cpp line 459, which is a discharge, not a velocity).
        speed[k] = (hs[k] * vs[k] + h[k] * vf[k]) / total[k];
      }
    }
    if (sel.sf) write("sf", fraction);
    if (sel.ht) write("ht", total);
    if (sel.vt) write("vt", speed);
  }
  if (particles_) {
    char pName[64];
    std::snprintf(pName, sizeof pName, "particles/particles_%04d.gpkg", index);
    particles_->writeLayer(out_->claim(pName));
  }
  // index.csv: index, time, then every series map written at this time.
  std::ostringstream line;
  line.precision(12);
  line << index << "," << solver_->time();
  for (const std::string& n : names) line << "," << n;
  line << "\n";
  seriesIndex_ += line.str();
  out_->writeText("series/index.csv", seriesIndex_);
}

void Simulation::attemptWrite(const std::function<void()>& write, std::string& firstError) {
  try {
    write();
  } catch (const IoError& e) {
    if (firstError.empty()) firstError = e.what();
  }
}

void Simulation::writeFinal(const RunSummary& s, Ending ending) {
  const bool failed = ending == Ending::Failed;
  // Each map is attempted even when one before it failed (a full disk may still take a small
  // file); the summary then reports the run as failed with the first reason.
  std::string ioError;
  auto attempt = [&](const std::function<void()>& write) { attemptWrite(write, ioError); };
  // On failure the maxima and arrival so far are still written; the final state may hold NaN.
  const double never = -1.0;
  if (!failed) {
    const std::vector<double> h = solver_->h();
    attempt([&] { out_->writeMap("hffinal", h); });
    attempt([&] { out_->writeMap("vffinal", speedMap(h, solver_->qx(), solver_->qy(), speedThickness())); });
  }
  attempt([&] { out_->writeMap("tarrival", solver_->arrival(), &never); });
  if (!solver_->twoPhase()) {
    attempt([&] { out_->writeMap("hfmax", solver_->hMax()); });
    attempt([&] { out_->writeMap("vfmax", solver_->vMax()); });
  } else {
    const flow::DebrisMaxima m = solver_->debrisMaxima();
    attempt([&] { out_->writeMap("hfmax", m.hf); });
    attempt([&] { out_->writeMap("vfmax", m.vf); });
    attempt([&] { out_->writeMap("hsmax", m.hs); });
    attempt([&] { out_->writeMap("vsmax", m.vs); });
    attempt([&] { out_->writeMap("htmax", m.h); });
    attempt([&] { out_->writeMap("sfracmax", m.solidFraction); });
    attempt([&] { out_->writeMap("pimpactmax", m.impactPressure); });
    if (!failed) {
      const std::vector<double> hs = solver_->hs(), qsx = solver_->qsx(), qsy = solver_->qsy(), hf = solver_->h();
      std::vector<double> total(hs.size()), deposit(hs.size(), 0.0);
      for (std::size_t k = 0; k < hs.size(); ++k) {
        total[k] = hs[k] + hf[k];
        // Deposit: solids that have come to rest (friction stopped them exactly).
        if (qsx[k] == 0.0 && qsy[k] == 0.0) deposit[k] = hs[k];
      }
      attempt([&] { out_->writeMap("hsfinal", hs); });
      attempt([&] {
        out_->writeMap("vsfinal", solidSpeedMap(hs, qsx, qsy, speedThickness(), scene_.settings.debris.filmThickness));
      });
      attempt([&] { out_->writeMap("htfinal", total); });
      attempt([&] { out_->writeMap("deposit", deposit); });
      if (solver_->entrainment()) {  // docs/entrainment.md
        attempt([&] { out_->writeMap("basechange", solver_->bedChange()); });
        attempt([&] { out_->writeMap("erodiblefinal", solver_->erodibleDepth()); });
      }
    }
  }
  if (particles_) {
    attempt([&] { particles_->writeLayer(out_->claim("particles_final.gpkg")); });
    // The particle phase's peak maps; not after resuming a checkpoint that predates them (they would
    // miss the run before it: summary.json's warnings say so).
    if (particles_->solver().maxMapsRestored()) {
      attempt([&] { out_->writeMap("hcmax", particles_->solver().thicknessMax()); });
      attempt([&] { out_->writeMap("vcmax", particles_->solver().speedMax()); });
    }
    if (!failed) {
      const particles::ParticleGridFields pf = particles_->gridFields();
      const double none = -1.0;
      attempt([&] { out_->writeMap("hcfinal", pf.thickness); });
      attempt([&] { out_->writeMap("cfracfinal", pf.cohesionFraction, &none); });
      attempt([&] { out_->writeMap("releasedfluid", pf.releasedFluid); });
    }
  }
  if (!ioError.empty()) {
    if (failure_.empty()) failure_ = "output failed: " + ioError;
    ending = Ending::Failed;
  }
  try {
    out_->writeText("summary.json", summaryJson(s, ending));
  } catch (const IoError& e) {
    throw IoError((failure_.empty() ? std::string() : failure_ + "; ") + "summary.json could not be written: " +
                  e.what());
  }
  if (!ioError.empty()) throw IoError(failure_ + "; summary.json records the failure");
}

std::string Simulation::summaryJson(const RunSummary& s, Ending ending) const {
  const bool failed = ending == Ending::Failed;
  const char* status = failed ? "failed" : ending == Ending::Stopped ? "stopped" : "completed";
  std::ostringstream o;
  o.precision(12);
  const compute::DeviceInfo& d = ctx_->device();
  const Grid& g = scene_.dem.grid;
  o << "{\n  \"talus_version\": \"0.1.0\",\n  \"run_file\": \"" << jsonEscape(scene_.runFile) << "\",\n"
    << "  \"status\": \"" << status << "\",\n";
  if (failed) o << "  \"failure\": \"" << jsonEscape(failure_) << "\",\n";
  // What the scene's loading warned about (dropped material, bands, ...), and what the run did.
  std::vector<std::string> warnings = scene_.warnings;
  if (particles_ && !particles_->solver().maxMapsRestored())
    warnings.push_back("hcmax and vcmax are not written: the checkpoint this run resumed from predates the particles' "
                       "peak maps, which would miss the run before it");
  if (!warnings.empty()) {
    o << "  \"warnings\": [";
    for (std::size_t w = 0; w < warnings.size(); ++w) o << (w ? ", " : "") << "\"" << jsonEscape(warnings[w]) << "\"";
    o << "],\n";
  }
  if (atRest_)
    o << "  \"ended_at_rest\": \"kinetic energy below " << scene_.restFraction << " of its peak "
      << peakKinetic_ << " J\",\n";
  o << "  \"device\": \"" << jsonEscape(d.name) << "\",\n  \"platform\": \"" << jsonEscape(d.platformName) << "\",\n"
    << "  \"precision\": \"" << compute::precisionName(ctx_->precision()) << "\",\n"
    << "  \"grid\": {\"nx\": " << g.nx << ", \"ny\": " << g.ny << ", \"dx\": " << JsonNum{g.dx}
    << ", \"domain_cells\": " << domainCells_ << "},\n"
    << "  \"start_time_s\": " << JsonNum{scene_.startTime} << ",\n  \"end_time_s\": " << JsonNum{scene_.endTime} << ",\n"
    << "  \"simulated_s\": " << JsonNum{s.simulatedSeconds} << ",\n  \"steps\": " << s.steps << ",\n"
    << "  \"wall_time_s\": " << JsonNum{s.wallSeconds} << ",\n  \"cell_updates_per_s\": " << JsonNum{s.cellUpdatesPerSecond} << ",\n"
    << "  \"volume\": {\"initial_m3\": " << JsonNum{s.initialVolume} << ", \"final_m3\": " << JsonNum{s.finalVolume}
    << ", \"outflow_m3\": " << JsonNum{s.totalOutflow} << ", \"rain_m3\": " << JsonNum{s.totalRain}
    << ", \"infiltrated_m3\": " << JsonNum{s.totalInfiltrated} << ", \"entrained_m3\": " << JsonNum{s.totalEntrained}
    << ", \"balance_error\": " << JsonNum{s.volumeBalanceError} << "}";
  if (solver_->twoPhase()) {
    const flow::FlowDiagnostics& dg = solver_->diagnostics();
    o << ",\n  \"energy\": {\"kinetic_J\": " << JsonNum{dg.kinetic} << ", \"vertical_kinetic_J\": " << JsonNum{dg.kineticVertical}
      << ", \"potential_J\": " << JsonNum{dg.potential} << ", \"potential_released_J\": " << JsonNum{lastReleased_}
      << ", \"mechanical_lost_J\": " << JsonNum{lastLost_} << ", \"friction_drag_work_J\": " << JsonNum{totalSourceWork_}
      << ", \"other_loss_J\": " << JsonNum{lastLost_ - totalSourceWork_} << "}";
  }
  if (particles_)
    o << ",\n  \"particles\": {\"count\": " << particles_->count() << ", \"initial_mass_kg\": " << JsonNum{particles_->initialMass()}
      << ", \"final_mass_kg\": " << JsonNum{particles_->mass()} << ", \"outflow_kg\": " << JsonNum{particles_->cumulativeOutflow()}
      << ", \"balance_error\": " << JsonNum{particles_->balanceError()}
      << ", \"viscous_dissipation_J\": " << JsonNum{particles_->solver().diagnostics().viscousDissipation}
      << ", \"art_stress_work_J\": " << JsonNum{particles_->solver().diagnostics().artificialStressWork}
      << ", \"friction_work_J\": " << JsonNum{particles_->solver().diagnostics().frictionWork}
      << ", \"potential_released_J\": " << JsonNum{particles_->solver().diagnostics().potentialReleased} << "}";
  o << "\n}\n";
  return o.str();
}

}  // namespace talus::sim
