#include "sim/Scene.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <utility>

#include "core/Error.hpp"
#include "core/Memory.hpp"
#include "flow/FlowParams.hpp"
#include "sim/RunMemory.hpp"
#include "sim/RunTimes.hpp"

namespace talus::sim {
namespace {

std::string cellText(const Grid& g, int i, int j) {
  std::ostringstream o;
  o << "cell (column " << i << ", row " << j << ") at x = " << g.cellX(i) << ", y = " << g.cellY(j);
  return o.str();
}

/// Reads the map keys of a scene on the DEM's grid, collecting the warnings of their rasters.
class MapLoader {
 public:
  MapLoader(const io::RunConfig& cfg, const Raster& dem, std::string demPath, std::vector<std::string>& warnings)
      : cfg_(cfg), dem_(dem), demPath_(std::move(demPath)), warnings_(warnings) {}

  /// A map key (a raster on the DEM's grid, or a number) as values times the multiplier. Cells
  /// inside the DEM's domain must hold finite data within the key's declared range. With a
  /// material name ("initial water"), what the raster holds on the DEM's nodata cells (and is
  /// therefore dropped) is reported as a warning with its cell count and volume.
  std::vector<double> operator()(const std::string& key, const char* material = nullptr) const;

 private:
  const io::RunConfig& cfg_;
  const Raster& dem_;
  std::string demPath_;
  std::vector<std::string>& warnings_;
};

std::vector<double> MapLoader::operator()(const std::string& key, const char* material) const {
  const io::KeySpec* spec = cfg_.registry().find(key);
  const double lo = spec ? spec->min : -HUGE_VAL, hi = spec ? spec->max : HUGE_VAL;
  const std::string unit = spec && !spec->unit.empty() ? " " + spec->unit : "";
  auto range = [&] {
    std::ostringstream o;
    o << "[" << lo << ", " << hi << "]" << unit;
    return o.str();
  };
  const io::MapValue mv = cfg_.map(key);
  const std::size_t n = dem_.grid.cells();
  if (!mv.isFile) {
    const double v = mv.constant * mv.multiplier;
    if (!std::isfinite(v) || v < lo || v > hi)
      throw InputError(cfg_.origin(key) + ": key '" + key + "': value " + std::to_string(v) + " is outside " + range());
    return std::vector<double>(n, v);
  }
  io::RasterReadOptions options;
  options.convertLinearUnits = cfg_.flag("Convert Raster Units");
  options.valuesAreLengths = spec && spec->unit == "m";
  const Raster r = io::readRaster(mv.file, options, &warnings_);
  io::requireSameGrid(dem_, demPath_, r, mv.file);
  std::vector<double> out(n, 0.0);
  std::size_t droppedCells = 0;
  double droppedVolume = 0;
  for (int j = 0; j < dem_.grid.ny; ++j)
    for (int i = 0; i < dem_.grid.nx; ++i) {
      const std::size_t k = dem_.grid.index(i, j);
      if (!dem_.valid[k]) {
        const double v = r.values[k] * mv.multiplier;
        if (material != nullptr && r.valid[k] && v > 0) {
          ++droppedCells;
          droppedVolume += v * dem_.grid.dx * dem_.grid.dx;
        }
        continue;
      }
      if (!r.valid[k])
        throw InputError("map '" + mv.file + "' (key '" + key + "') has no data at " + cellText(dem_.grid, i, j) +
                         ", which is inside the DEM's domain");
      const double v = r.values[k] * mv.multiplier;
      if (v < lo || v > hi)
        throw InputError("map '" + mv.file + "' (key '" + key + "') has value " + std::to_string(v) + " at " +
                         cellText(dem_.grid, i, j) + ", outside the valid range " + range());
      out[k] = v;
    }
  if (droppedCells > 0) {
    std::ostringstream o;
    o.precision(6);
    o << droppedVolume << " m^3 of " << material << " in '" << mv.file << "' (key '" << key << "') lie on "
      << droppedCells << " cells where the DEM '" << demPath_ << "' has no data, and are dropped";
    warnings_.push_back(o.str());
  }
  return out;
}

/// Young's modulus and Poisson ratio of the particles from the run-file. OpenLISEM Hazard's
/// "Elastic Modulus" is the bulk modulus K of its stress update (particles.cl: dsigma = G eps_dev
/// + K tr(eps) I), with "Shear Modulus" G; Talus's own "Young Modulus" E applies when it is 0.
void setElasticity(const io::RunConfig& cfg, particles::ParticleSettings& ps) {
  const double K = cfg.real("Elastic Modulus"), G = cfg.real("Shear Modulus"), nu = cfg.real("Poisson Ratio");
  if (K > 0) {
    ps.youngModulus = G > 0 ? 9 * K * G / (3 * K + G) : 3 * K * (1 - 2 * nu);
    ps.poisson = G > 0 ? (3 * K - 2 * G) / (2 * (3 * K + G)) : nu;
    return;  // K > 0 and G > 0 always give a Poisson ratio in (-1, 0.5)
  }
  ps.youngModulus = cfg.real("Young Modulus");
  ps.poisson = G > 0 ? ps.youngModulus / (2 * G) - 1 : nu;
  if (!(ps.poisson > -1 && ps.poisson < 0.5))
    throw InputError(cfg.origin("Shear Modulus") + ": key 'Shear Modulus': " + io::formatNumber(G) +
                     " Pa with Young Modulus " + io::formatNumber(ps.youngModulus) + " Pa gives Poisson ratio " +
                     io::formatNumber(ps.poisson) + ", not below 0.5: the shear modulus must exceed E/3 "
                     "(or give the bulk modulus as Elastic Modulus, OpenLISEM's meaning)");
}

/// Rainfall and infiltration (docs/sources.md), read only while their switches are on, as OpenLISEM
/// does (modelruninit.cpp lines 24, 252, 382). Both act on the water of the single-phase model.
/// The solids' basal law (flow/Rheology.hpp) and its parameters. The particles have Coulomb
/// friction only, so another law in hybrid mode is refused rather than silently half applied.
void setRheology(const io::RunConfig& cfg, Scene& s) {
  const std::string name = cfg.choice("Solid Rheology");
  const flow::RheologyLaw& law = flow::rheologyLaw(name);
  if (s.particles.enabled && law.id != flow::Rheology::Coulomb)
    throw InputError(cfg.origin("Solid Rheology") + ": key 'Solid Rheology': '" + name +
                     "' applies to the grid's solids only; with Use Material Point Method=1 the particles "
                     "have Coulomb friction (use Solid Rheology=coulomb or switch the particles off)");
  std::vector<double> values;
  for (const flow::RheologyKey& key : law.keys) values.push_back(cfg.real(key.name));
  s.settings.debris.rheology = law.id;
  s.settings.debris.rheologyParams = law.params(values);
}

/// Solids lighter than the fluid (snow, say, with water) would float: the buoyancy ratio gamma =
/// rho_f / rho_s >= 1 turns their lateral pressure and basal stress negative (spec §4). Dry runs
/// (no water and no rain) take any density.
void requireSolidsHeavierThanFluid(const io::RunConfig& cfg, const Scene& s) {
  if (s.flow.hs.empty() || s.flow.rhoS.empty()) return;
  bool fluid = false;
  for (std::size_t k = 0; k < s.flow.h.size(); ++k) fluid = fluid || (s.dem.valid[k] && s.flow.h[k] > 0);
  for (double i : s.rainfall.intensities()) fluid = fluid || i > 0;
  if (!fluid) return;
  const double rhoF = cfg.real("Fluid Density");
  const Grid& g = s.dem.grid;
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i < g.nx; ++i) {
      const std::size_t k = static_cast<std::size_t>(j) * g.nx + i;
      if (!s.dem.valid[k] || s.flow.hs[k] <= 0 || s.flow.rhoS[k] > rhoF) continue;
      throw InputError(cfg.origin("Initial Solid Density") + ": key 'Initial Solid Density': " +
                       io::formatNumber(s.flow.rhoS[k]) + " kg/m^3 at " + cellText(g, i, j) +
                       " is not above Fluid Density (" + io::formatNumber(rhoF) +
                       " kg/m^3) in a run with water: the solids would float; light solids (snow) run dry");
    }
}

void loadSources(const io::RunConfig& cfg, const MapLoader& loadMap, Scene& s) {
  if (cfg.flag("Include Rainfall")) {
    if (!cfg.isDefault("Rainfall Intensity")) {
      s.rainfall = io::Rainfall::uniform(cfg.real("Rainfall Intensity"));
    } else {
      // OpenLISEM writes files with a multiplier, "Rainfall=rain=1" (SaveToRunFile); it scales the
      // intensities (modelruninit.cpp line 24, GetMapMult).
      std::string file = cfg.text("Rainfall");
      double mult = 1.0;
      const std::size_t eq = file.rfind('=');
      if (eq != std::string::npos) {
        char* end = nullptr;
        const std::string m = file.substr(eq + 1);
        const double v = std::strtod(m.c_str(), &end);
        if (!m.empty() && end != nullptr && *end == '\0' && std::isfinite(v) && v >= 0) mult = v, file = file.substr(0, eq);
      }
      if (!std::filesystem::path(file).is_absolute())
        file = (std::filesystem::path(cfg.directory("TimeInput Directory")) / file).lexically_normal().string();
      const io::Rainfall read = io::readRainfallFile(file);
      std::vector<double> scaled = read.intensities();
      for (double& v : scaled) v *= mult;
      s.rainfall = io::Rainfall(read.times(), scaled);
    }
  }
  if (cfg.flag("Include Infiltration")) {
    s.infiltration = loadMap("KSatSimple");
    for (double& f : s.infiltration) f /= 3600.0 * 1000.0;  // mm/h -> m/s (modelruninit.cpp line 738)
  }
}

}  // namespace

Scene loadScene(const io::RunConfig& cfg) {
  Scene s;
  s.runFile = cfg.sourceName();
  const io::MapValue demKey = cfg.map("DEM");
  if (!demKey.isFile) throw InputError(cfg.origin("DEM") + ": key 'DEM': the DEM must be a raster file, not a number");
  for (const std::string& w : cfg.warnings()) s.warnings.push_back(w);
  io::RasterReadOptions demOptions;
  demOptions.convertLinearUnits = cfg.flag("Convert Raster Units");
  demOptions.valuesAreLengths = true;
  s.dem = io::readRaster(demKey.file, demOptions, &s.warnings);
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
  const MapLoader loadMap(cfg, s.dem, demKey.file, s.warnings);
  s.flow.mask = s.dem.valid;
  // The solvers see elevations above a local origin, the lowest valid DEM cell: the water surface
  // b + h is formed in the device's precision, and in float an altitude of 8800 m leaves 0.5 mm
  // of resolution, which is the thickness of the thin films a front is made of. Above the origin
  // the resolution follows the scene's relief instead. Every force uses differences of b, so the
  // physics is unchanged; the maps keep their true elevations (s.dem).
  s.elevationOrigin = HUGE_VAL;
  for (std::size_t k = 0; k < s.dem.values.size(); ++k)
    if (s.dem.valid[k]) s.elevationOrigin = std::min(s.elevationOrigin, s.dem.values[k]);
  std::vector<double> localBed = s.dem.values;
  for (double& z : localBed) z -= s.elevationOrigin;
  s.flow.bed = localBed;
  s.flow.manning = loadMap("Manning");
  if (cfg.flag("Include Initial Water"))
    s.flow.h = loadMap("Initial Fluid Height", "initial water");
  else
    s.flow.h.assign(g.cells(), 0.0);

  flow::FlowSettings& f = s.settings;
  s.particles.enabled = cfg.flag("Use Material Point Method");
  if (cfg.flag("Include Initial Solids")) {
    std::vector<double> hs = loadMap("Initial Solid Height", "initial solids");
    std::vector<double> rhoS = loadMap("Initial Solid Density");
    std::vector<double> phi = loadMap("Initial Solid IFA");
    std::vector<double> cohesion = loadMap("Initial Cohesion");
    for (double& c : cohesion) c *= 1000.0;  // kPa (OpenLISEM Hazard) -> Pa
    std::vector<double> delta = loadMap("Bed Friction Angle");
    if (s.particles.enabled) {
      // Hybrid mode: the structured solids (with the fluid they hold) become particles; the grid
      // keeps the unstructured solids and the free fluid.
      InitialMaterial m;
      m.mask = s.dem.valid;
      m.bed = localBed;
      m.hs = hs;
      m.hf = s.flow.h;
      m.rhoS = rhoS;
      m.rhoF = cfg.real("Fluid Density");
      m.phi = phi;
      m.delta = cfg.flag("Bed Friction Equals IFA") ? phi : delta;
      m.cohesion = cohesion;
      m.structured = loadMap("Structured Fraction");
      m.confined = loadMap("Confined Fluid Fraction");
      m.grain = loadMap("Initial Solid Rocksize");
      // OpenLISEM seeds floor(hs / (dx * PFD)) particles in a cell of solid height hs
      // (modelruninit.cpp, factor_particle = 1 / PFD): each holds about PFD * dx^3.
      const double dx = s.dem.grid.dx;
      const double fraction = cfg.real("Particle Fractional Dimension");
      s.particles.spacing.volume = fraction > 0 ? fraction * dx * dx * dx : cfg.real("Particle Volume");
      s.particles.spacing.perCell = cfg.real("Particles Per Cell");
      try {
        splitStructured(s.dem.grid, m, s.particles, particleLimit(cfg.choice("Precision")));
      } catch (const InputError& e) {  // name the keys that set the particle count
        const char* key = fraction > 0 ? "Particle Fractional Dimension"
                          : s.particles.spacing.volume > 0 ? "Particle Volume" : "Particles Per Cell";
        throw InputError(cfg.origin(key) + ": key '" + key + "' (particle volume " +
                         io::formatNumber(s.particles.spacing.volume) + " m^3, Particles Per Cell " +
                         io::formatNumber(s.particles.spacing.perCell) + "): " + e.what() +
                         " (the memory this run can still take holds " + std::to_string(particleLimit(cfg.choice("Precision"))) +
                         " particles of about " + formatBytes(bytesPerParticle(cfg.choice("Precision"))) + " each)");
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
      s.flow.grain = loadMap("Initial Solid Rocksize");
      s.flow.cohesion = std::move(cohesion);
      s.flow.delta = std::move(delta);
    }
  }
  if (cfg.flag("Include Entrainment")) {
    if (s.particles.enabled)
      throw InputError(cfg.origin("Include Entrainment") + ": key 'Include Entrainment': entrainment is not available "
                       "with Use Material Point Method=1 (the particles' bed does not erode)");
    s.flow.erodible = loadMap("Erodible Depth", "erodible bed");
    f.entrainment.enabled = true;
    f.entrainment.growthRate = cfg.real("Entrainment Growth Rate");
    f.twoPhase = true;  // entrained material joins the solids (default properties where none were)
  }
  if (s.particles.enabled) {
    particles::ParticleSettings& ps = s.particles.settings;
    setElasticity(cfg, ps);
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
    ps.picFraction = cfg.real("PIC Fraction");
    if (s.particles.terrain.mask.empty()) {  // no solids at all: a run without particles
      s.particles.terrain.mask = s.dem.valid;
      s.particles.terrain.bed = localBed;
    }
  }
  flow::DebrisSettings& d = f.debris;
  d.earthPressure = flow::parseEarthPressure(cfg.choice("Earth Pressure"));
  d.kConst = cfg.real("Earth Pressure Coefficient");
  d.poreB = cfg.real("Pore Pressure Factor");
  d.packing = cfg.real("Solid Packing Fraction");
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
  f.scheme = flow::parseTimeScheme(cfg.choice("Time Scheme"));
  if (f.twoPhase && flow::sweeps(f.scheme))
    throw InputError(cfg.origin("Time Scheme") + ": key 'Time Scheme': '" + cfg.choice("Time Scheme") +
                     "' is for water-only runs; this run has solids (the two-phase model runs unsplit)");
  if (f.cfl > flow::kPositiveCfl && !flow::sweeps(f.scheme)) {
    std::ostringstream o;
    o << cfg.origin("CFL") << ": key 'CFL': " << f.cfl << " is above 0.5, where the unsplit scheme is no longer "
      << "positive; Courant numbers up to 1 need Time Scheme=split or hancock (water only)";
    throw InputError(o.str());
  }
  f.hDry = cfg.real("Minimum Flow Height");
  f.arrivalH = cfg.real("Arrival Threshold");
  f.edge = flow::parseBoundary(cfg.choice("Boundary Type"));
  f.nodata = flow::parseBoundary(cfg.choice("Nodata Boundary Type"));
  // The particles meet the same boundaries as the grid: walls hold them, open edges take them out.
  s.particles.settings.edgeWalls = f.edge == flow::Boundary::Wall;
  s.particles.settings.nodataWalls = f.nodata == flow::Boundary::Wall;
  f.slopeCorrection = cfg.flag("Slope Correction");
  f.curvature = cfg.flag("Curvature Acceleration");
  f.skipDryTiles = cfg.flag("Skip Dry Tiles");
  f.depthPressure = flow::parseDepthPressure(cfg.choice("Depth Pressure"));

  // OpenLISEM Hazard reports every "Report every" model steps of "Timestep" s (modelreport.cpp).
  s.reportInterval = cfg.real("Timestep") * cfg.integer("Report every");
  s.startTime = 60.0 * cfg.real("Start Time");
  // Report times are start + k * Timestep: the span to the end is what must land on one.
  s.endTime = s.startTime + minutesOnReportGrid(cfg.real("End Time") - cfg.real("Start Time"), s.reportInterval);
  s.restFraction = cfg.real("Stop At Rest Fraction");
  s.precision = cfg.choice("Precision");
  s.device = cfg.text("Device");
  s.outputDir = cfg.directory("Output Directory");
  s.format = outputFormat(cfg);
  s.series = seriesSelection(cfg);
  s.checkpointInterval = minutesOnReportGrid(cfg.real("Checkpoint Interval"), s.reportInterval);
  s.checkpointWallInterval = 60.0 * cfg.real("Checkpoint Wall Interval");
  loadSources(cfg, loadMap, s);
  setRheology(cfg, s);
  requireSolidsHeavierThanFluid(cfg, s);
  requireMemoryForRun(s, demKey.file);
  return s;
}

void requireMaterial(const Scene& s, const io::RunConfig& cfg) {
  const auto anyInside = [&](const std::vector<double>& v) {
    for (std::size_t k = 0; k < v.size(); ++k)
      if (s.dem.valid[k] && v[k] > 0) return true;
    return false;
  };
  if (anyInside(s.flow.h) || anyInside(s.flow.hs) || !s.particles.seeded.x.empty()) return;
  for (double i : s.rainfall.intensities())
    if (i > 0) return;  // rain brings its own water
  auto state = [&](const char* process, const char* map) {
    return cfg.flag(process) ? std::string("'") + map + "' is 0 in every cell of the DEM's domain"
                             : std::string("'") + process + "' is 0";
  };
  throw InputError(cfg.sourceName() + ": the scene has nothing to move: no initial water (" +
                   state("Include Initial Water", "Initial Fluid Height") + ") and no initial solids (" +
                   state("Include Initial Solids", "Initial Solid Height") + ")");
}

}  // namespace talus::sim
