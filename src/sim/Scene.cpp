#include "sim/Scene.hpp"

#include <cmath>
#include <sstream>

#include "core/Error.hpp"

namespace talus::sim {
namespace {

std::string cellText(const Grid& g, int i, int j) {
  std::ostringstream o;
  o << "cell (column " << i << ", row " << j << ") at x = " << g.cellX(i) << ", y = " << g.cellY(j);
  return o.str();
}

/// Reads a map key (a raster on the DEM's grid, or a number) as values times the multiplier.
/// Cells inside the DEM's domain must hold finite data within the key's declared range.
std::vector<double> loadMap(const io::RunConfig& cfg, const std::string& key, const Raster& dem,
                            const std::string& demPath) {
  const io::KeySpec* spec = cfg.registry().find(key);
  const double lo = spec ? spec->min : -HUGE_VAL, hi = spec ? spec->max : HUGE_VAL;
  const std::string unit = spec && !spec->unit.empty() ? " " + spec->unit : "";
  auto range = [&] {
    std::ostringstream o;
    o << "[" << lo << ", " << hi << "]" << unit;
    return o.str();
  };
  const io::MapValue mv = cfg.map(key);
  const std::size_t n = dem.grid.cells();
  if (!mv.isFile) {
    const double v = mv.constant * mv.multiplier;
    if (!std::isfinite(v) || v < lo || v > hi)
      throw InputError(cfg.origin(key) + ": key '" + key + "': value " + std::to_string(v) + " is outside " + range());
    return std::vector<double>(n, v);
  }
  const Raster r = io::readRaster(mv.file);
  io::requireSameGrid(dem, demPath, r, mv.file);
  std::vector<double> out(n, 0.0);
  for (int j = 0; j < dem.grid.ny; ++j)
    for (int i = 0; i < dem.grid.nx; ++i) {
      const std::size_t k = dem.grid.index(i, j);
      if (!dem.valid[k]) continue;
      if (!r.valid[k])
        throw InputError("map '" + mv.file + "' (key '" + key + "') has no data at " + cellText(dem.grid, i, j) +
                         ", which is inside the DEM's domain");
      const double v = r.values[k] * mv.multiplier;
      if (v < lo || v > hi)
        throw InputError("map '" + mv.file + "' (key '" + key + "') has value " + std::to_string(v) + " at " +
                         cellText(dem.grid, i, j) + ", outside the valid range " + range());
      out[k] = v;
    }
  return out;
}

}  // namespace

Scene loadScene(const io::RunConfig& cfg) {
  Scene s;
  s.runFile = cfg.sourceName();
  const io::MapValue demKey = cfg.map("DEM");
  if (!demKey.isFile) throw InputError(cfg.origin("DEM") + ": key 'DEM': the DEM must be a raster file, not a number");
  s.dem = io::readRaster(demKey.file);
  if (demKey.multiplier != 1.0)
    for (double& v : s.dem.values) v *= demKey.multiplier;
  // Elevations must be finite and representable in single precision (the kernels may run in float).
  for (int j = 0; j < s.dem.grid.ny; ++j)
    for (int i = 0; i < s.dem.grid.nx; ++i) {
      const double z = s.dem.at(i, j);
      if (s.dem.isValid(i, j) && !(std::fabs(z) < 1e30))
        throw InputError("DEM '" + demKey.file + "' (times its multiplier " + std::to_string(demKey.multiplier) +
                         ") has elevation " + std::to_string(z) + " at " + cellText(s.dem.grid, i, j));
    }
  std::size_t inside = 0;
  for (uint8_t v : s.dem.valid) inside += v;
  if (inside == 0) throw InputError("DEM '" + demKey.file + "' has no valid cells");

  const Grid& g = s.dem.grid;
  s.flow.mask = s.dem.valid;
  s.flow.bed = s.dem.values;
  s.flow.manning = loadMap(cfg, "Manning", s.dem, demKey.file);
  if (cfg.flag("Include Initial Water"))
    s.flow.h = loadMap(cfg, "Initial Fluid Height", s.dem, demKey.file);
  else
    s.flow.h.assign(g.cells(), 0.0);

  flow::FlowSettings& f = s.settings;
  s.particles.enabled = cfg.flag("Use Material Point Method");
  if (cfg.flag("Include Initial Solids")) {
    std::vector<double> hs = loadMap(cfg, "Initial Solid Height", s.dem, demKey.file);
    std::vector<double> rhoS = loadMap(cfg, "Initial Solid Density", s.dem, demKey.file);
    std::vector<double> phi = loadMap(cfg, "Initial Solid IFA", s.dem, demKey.file);
    std::vector<double> cohesion = loadMap(cfg, "Initial Cohesion", s.dem, demKey.file);
    for (double& c : cohesion) c *= 1000.0;  // kPa (OpenLISEM Hazard) -> Pa
    std::vector<double> delta = loadMap(cfg, "Bed Friction Angle", s.dem, demKey.file);
    if (s.particles.enabled) {
      // Hybrid mode: the structured solids (with the fluid they hold) become particles; the grid
      // keeps the unstructured solids and the free fluid.
      InitialMaterial m;
      m.mask = s.dem.valid;
      m.bed = s.dem.values;
      m.hs = hs;
      m.hf = s.flow.h;
      m.rhoS = rhoS;
      m.rhoF = cfg.real("Fluid Density");
      m.phi = phi;
      m.delta = cfg.flag("Bed Friction Equals IFA") ? phi : delta;
      m.cohesion = cohesion;
      m.structured = loadMap(cfg, "Structured Fraction", s.dem, demKey.file);
      m.confined = loadMap(cfg, "Confined Fluid Fraction", s.dem, demKey.file);
      m.grain = loadMap(cfg, "Initial Solid Rocksize", s.dem, demKey.file);
      s.particles.spacing.volume = cfg.real("Particle Fractional Dimension");
      s.particles.spacing.perCell = cfg.real("Particles Per Cell");
      try {
        splitStructured(s.dem.grid, m, s.particles);
      } catch (const InputError& e) {  // name the keys that set the particle count
        throw InputError(cfg.origin("Particles Per Cell") + ": keys 'Particle Fractional Dimension' (" +
                         io::formatNumber(s.particles.spacing.volume) + " m^3) / 'Particles Per Cell' (" +
                         io::formatNumber(s.particles.spacing.perCell) + "): " + e.what());
      }
      hs = m.hs;
      s.flow.h = m.hf;
      s.particles.terrain.slopeCorrection = cfg.flag("Slope Correction");
      s.particles.terrain.curvature = cfg.flag("Curvature Acceleration");
    }
    bool any = false;
    for (std::size_t k = 0; k < hs.size(); ++k) any = any || (s.dem.valid[k] && hs[k] > 0.0);
    // A scene with no solids on the grid runs exactly the single-phase path (spec §3, grid mode).
    // In hybrid mode the grid always runs the two-phase model: the particles are part of its bed.
    if (any || s.particles.enabled) {
      f.twoPhase = true;
      f.particleBed = s.particles.enabled;
      s.flow.hs = std::move(hs);
      s.flow.rhoS = std::move(rhoS);
      s.flow.phi = std::move(phi);
      s.flow.grain = loadMap(cfg, "Initial Solid Rocksize", s.dem, demKey.file);
      s.flow.cohesion = std::move(cohesion);
      s.flow.delta = std::move(delta);
    }
  }
  if (s.particles.enabled) {
    particles::ParticleSettings& ps = s.particles.settings;
    ps.youngModulus = cfg.real("Elastic Modulus");
    const double G = cfg.real("Shear Modulus");
    ps.poisson = G > 0 ? ps.youngModulus / (2 * G) - 1 : cfg.real("Poisson Ratio");
    if (!(ps.poisson > -1 && ps.poisson < 0.5))
      throw InputError(cfg.origin("Shear Modulus") + ": key 'Shear Modulus': " + io::formatNumber(G) +
                       " Pa with Elastic Modulus " + io::formatNumber(ps.youngModulus) + " Pa gives Poisson ratio " +
                       io::formatNumber(ps.poisson) + ", not below 0.5: the shear modulus must exceed E/3");
    ps.soundSpeed = cfg.real("Sound Speed");
    ps.smoothingFactor = cfg.real("Smoothing Length Factor");
    ps.cfl = cfg.real("Particle CFL");
    ps.alphaPi = cfg.real("Artificial Viscosity Alpha");
    ps.betaPi = cfg.real("Artificial Viscosity Beta");
    ps.epsArt = cfg.real("Artificial Stress Epsilon");
    ps.nArt = cfg.real("Artificial Stress Exponent");
    ps.dilatancy = cfg.real("Dilatancy Angle");
    ps.epsCrit = cfg.real("Critical Strain");
    ps.poreB = cfg.real("Pore Pressure Factor");
    ps.fluidDensity = cfg.real("Fluid Density");
    ps.earthPressure = cfg.choice("Earth Pressure") == "constant" ? particles::ParticleEarthPressure::Constant
                                                                  : particles::ParticleEarthPressure::SavageHutter;
    ps.kConst = cfg.real("Earth Pressure Coefficient");
    if (s.particles.terrain.mask.empty()) {  // no solids at all: a run without particles
      s.particles.terrain.mask = s.dem.valid;
      s.particles.terrain.bed = s.dem.values;
    }
  }
  flow::DebrisSettings& d = f.debris;
  d.earthPressure = flow::parseEarthPressure(cfg.choice("Earth Pressure"));
  d.kConst = cfg.real("Earth Pressure Coefficient");
  d.poreB = cfg.real("Pore Pressure Factor");
  d.fluidDensity = cfg.real("Fluid Density");
  d.drag = flow::parseDragLaw(cfg.choice("Drag Law"));
  d.dragMultiplier = cfg.real("Drag coefficient multiplier");
  d.dragPExponent = cfg.real("Drag P Exponent");
  d.dragM = cfg.real("Drag M");
  d.dragKappa = cfg.real("Drag Smoothing Velocity");
  d.viscA = cfg.real("Viscosity Coefficient");
  d.viscB = cfg.real("Viscosity Exponent");
  d.virtualMass = cfg.flag("Virtual Mass");
  d.deltaFromPhi = cfg.flag("Bed Friction Equals IFA");
  d.reynolds = cfg.real("Viscous Reynolds Number");
  d.reynoldsInterfacial = cfg.real("Interfacial Reynolds Number");
  d.chi = cfg.real("Viscous Shear Factor");
  d.xi = cfg.real("Viscous Profile Factor");
  s.particles.fluid = d;  // the particles' drag with the free fluid uses the grid model's closure
  f.limiter = flow::parseLimiter(cfg.choice("Limiter"));
  f.riemann = flow::parseRiemann(cfg.choice("Riemann Solver"));
  f.cfl = cfg.real("CFL");
  f.hDry = cfg.real("Minimum Flow Height");
  f.arrivalH = cfg.real("Arrival Threshold");
  f.edge = flow::parseBoundary(cfg.choice("Boundary Type"));
  f.nodata = flow::parseBoundary(cfg.choice("Nodata Boundary Type"));
  f.slopeCorrection = cfg.flag("Slope Correction");
  f.curvature = cfg.flag("Curvature Acceleration");
  f.skipDryTiles = cfg.flag("Skip Dry Tiles");
  f.depthPressure = flow::parseDepthPressure(cfg.choice("Depth Pressure"));

  s.startTime = 60.0 * cfg.real("Start Time");
  s.endTime = 60.0 * cfg.real("End Time");
  s.reportInterval = cfg.real("Timestep");
  s.restFraction = cfg.real("Stop At Rest Fraction");
  s.precision = cfg.choice("Precision");
  s.device = cfg.text("Device");
  s.outputDir = cfg.directory("Output Directory");
  s.format = cfg.choice("Output Format") == "pcraster" ? io::RasterFormat::PCRaster : io::RasterFormat::GeoTiff;
  s.reportSeries = cfg.flag("Report Series");
  s.checkpointInterval = 60.0 * cfg.real("Checkpoint Interval");
  s.checkpointWallInterval = 60.0 * cfg.real("Checkpoint Wall Interval");
  return s;
}

}  // namespace talus::sim
