// Declarations of Talus's run-file keys. OpenLISEM Hazard's names, meanings and units are kept where
// it defines the key (times in minutes, Timestep in seconds, Elastic Modulus the bulk modulus);
// lisem(default, ...) marks them with OpenLISEM's default. Talus's own keys follow the same style;
// the OpenLISEM keys Talus does not use are declared in LisemKeys.cpp.
#include "sim/RunKeys.hpp"

#include <algorithm>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "flow/Rheology.hpp"
#include "io/RunConfig.hpp"
#include "sim/KeyBuilders.hpp"

namespace talus::sim {

namespace {

using io::KeyRegistry;
using io::KeySpec;
using io::KeyType;
using namespace keys;

void addInputKeys(KeyRegistry& r) {
  Section(r, "Input")
      << lisem("<site>/maps/", text("Map Directory", "", "folder holding the maps (relative to the run-file's folder)",
                                     KeyType::Directory))
      << lisem("dem.map", required(map("DEM", "", "m", -kInf, kInf, "bed elevation; nodata cells are outside the domain")))
      << flag("Convert Raster Units", "0",
              "convert maps in a projected CRS in feet (or another non-metre unit) to metres: cell sizes, "
              "elevations and thicknesses; 0: such maps are refused")
      << lisem("0", flag("Include Initial Water", "0", "start with the water of Initial Fluid Height"))
      << lisem("initialfh.map", readWhen("Include Initial Water", map("Initial Fluid Height", "0", "m", 0, 1e4,
                                                                       "vertical water thickness at t = start")));
}

std::vector<std::string> rheologyNames() {
  std::vector<std::string> names;
  for (const flow::RheologyLaw& law : flow::rheologyLaws()) names.push_back(law.name);
  return names;
}

/// The parameters of the basal laws (flow/Rheology.cpp), each key once (naming the laws that read
/// it), with each law's consistency rule.
void addRheologyKeys(KeyRegistry& r) {
  const std::vector<flow::RheologyLaw>& laws = flow::rheologyLaws();
  Section section(r, "Solids");
  std::vector<std::string> declared;
  for (const flow::RheologyLaw& law : laws)
    for (const flow::RheologyKey& key : law.keys) {
      if (std::find(declared.begin(), declared.end(), key.name) != declared.end()) continue;
      declared.push_back(key.name);
      std::string users;
      for (const flow::RheologyLaw& other : laws)
        for (const flow::RheologyKey& k : other.keys)
          if (k.name == key.name) users += (users.empty() ? "" : " or ") + other.name;
      section << real(key.name, key.defaultValue, key.unit, key.min, key.max, key.help + " (Solid Rheology=" + users + ")");
    }
  for (const flow::RheologyLaw& law : laws) {
    if (law.keys.empty()) continue;
    std::vector<std::string> names{"Solid Rheology"};
    for (const flow::RheologyKey& key : law.keys) names.push_back(key.name);
    r.addRule(names, [&law](const io::RunConfig& c) -> std::string {
      if (c.choice("Solid Rheology") != law.name) return "";
      std::vector<double> values;
      for (const flow::RheologyKey& key : law.keys) values.push_back(c.real(key.name));
      return law.check(values);
    });
  }
}

/// Solids of the two-phase grid model (spec §4): OpenLISEM Hazard's names and units first.
void addSolidKeys(KeyRegistry& r) {
  Section(r, "Solids")
      << lisem("0", flag("Include Initial Solids", "0", "start with the solids of Initial Solid Height (two-phase model)"))
      << lisem("initialsh.map", solidMap("Initial Solid Height", "0", "m", 0, 1e4, "vertical solid thickness alpha_s H at t = start"))
      << lisem("initialsd.map", solidMap("Initial Solid Density", "2650", "kg/m^3", 50, 6000,
                                                     "density rho_s of the solid grains (snow: 200-500; above Fluid Density in runs with water)"))
      << lisem("initialsifa.map", solidMap("Initial Solid IFA", "0.5236", "rad", 0, 1.5, "internal friction angle phi of the solids"))
      << lisem("initialsrocksize.map", solidMap("Initial Solid Rocksize", "0.01", "m", 1e-6, 100, "representative grain or block size d"))
      // OpenLISEM's form says Pa, but its particle kernel multiplies the value by 1000 (kPa), as
      // Talus does: docs/runfile.md, "OpenLISEM Hazard run-files".
      << lisem("initialscohesion.map", solidMap("Initial Cohesion", "0", "kPa", 0, 1e6,
                                                "cohesion c of the initial solids, carried with them (reduces the lateral "
                                                "pressure, Bell); kPa as OpenLISEM's code reads it"))
      << flag("Bed Friction Equals IFA", "1", "bed friction angle delta = internal friction angle phi")
      << solidMap("Bed Friction Angle", "0.5236", "rad", 0, 1.5, "bed friction angle delta (when not equal to IFA)")
      << choice("Solid Rheology", rheologyNames(), "coulomb",
                "basal law of the solids: coulomb (Bed Friction Angle), voellmy, mu-i (Pouliquen-Forterre), "
                "bingham or herschel-bulkley (docs/rheology.md); grid solids only (not with Use Material Point Method)")
      << choice("Earth Pressure", {"savage-hutter", "constant"}, "savage-hutter",
                "lateral earth-pressure coefficient: active/passive from phi and delta, or constant")
      << real("Earth Pressure Coefficient", "1", "-", 0.01, 100, "K when Earth Pressure=constant")
      << real("Pore Pressure Factor", "1", "-", 0, 1, "B: share of buoyancy that reduces basal friction")
      << real("Solid Packing Fraction", "0.6", "-", 0.2, 0.74,
              "solid volume fraction of the saturated deposit: fluid fills its pores from the bed up, "
              "and buoyancy grows with the submerged share of the solids")
      << real("Fluid Density", "1000", "kg/m^3", 500, 2000, "density rho_f of the fluid phase")
      << choice("Drag Law", {"off", "linear", "quadratic"}, "linear",
                "solid-fluid drag of Pudasaini (2012): j = 1 (linear) or j = 2 (quadratic)")
      << lisem("1", real("Drag coefficient multiplier", "1", "-", 0, 1e9, "multiplies the drag coefficient"))
      << real("Drag P Exponent", "1", "-", 0.1, 10, "m in P = alpha_s^m (fluid-like / solid-like drag)")
      << real("Drag M", "2.4", "-", 1, 10, "M in the solid-like drag G = alpha_f^(M-1) (Pitman & Le 2005)")
      << real("Drag Smoothing Velocity", "10", "m/s", 0, 1e4, "K of the smoothing function S_p (P.33)")
      << real("Viscosity Coefficient", "0.001", "Pa s", 1e-6, 1e5, "a in O'Brien-Julien eta = a exp(b alpha_s)")
      << real("Viscosity Exponent", "10", "-", 0, 50, "b in O'Brien-Julien eta = a exp(b alpha_s)")
      << flag("Virtual Mass", "1", "virtual mass in the phase exchange (C_vm = (1 + 2 alpha_s) / (2 alpha_f))")
      << real("Viscous Reynolds Number", "0", "-", 0, 1e12,
              "N_R of the fluid's Newtonian stress (P.30; paper: 15000); 0 = off; two-phase model only")
      << real("Interfacial Reynolds Number", "0", "-", 0, 1e12,
              "N_RA of the fluid's non-Newtonian stress from solid-fraction gradients (paper: 30); 0 = off")
      << real("Viscous Shear Factor", "0", "-", 0, 100,
              "chi: basal viscous damping -chi nu_R u_f / H^2 of the fluid (needs N_R > 0)")
      << real("Viscous Profile Factor", "0", "-", 0, 100,
              "xi: damping -xi alpha_s nu_RA (u_f - u_s) / H^2 of the relative motion (needs N_RA > 0)");
  addRheologyKeys(r);
}

/// Entrainment of an erodible bed layer into the solids (docs/entrainment.md).
void addEntrainmentKeys(KeyRegistry& r) {
  Section(r, "Entrainment")
      << flag("Include Entrainment", "0",
              "the flow takes up bed material of Erodible Depth into its solids (two-phase grid model; not with "
              "Use Material Point Method)")
      << readWhen("Include Entrainment", map("Erodible Depth", "0", "m", 0, 1e4,
                                             "vertical depth of bed material the flow can take up, as solid volume per "
                                             "area; the bed is lowered by what is taken"))
      << real("Entrainment Growth Rate", "0.002", "1/m", 0, 1,
              "E of McDougall & Hungr (2005): the volume grows as dV/dt = E V |U| (calibrated as "
              "E = ln(V_final / V_release) / path length)");
}

/// Structured solids as particles (hybrid mode, spec §5): OpenLISEM Hazard's names first.
void addParticleKeys(KeyRegistry& r) {
  Section(r, "Particles")
      << lisem("0", flag("Use Material Point Method", "0", "structured solids as elasto-plastic particles (hybrid mode)"))
      << particleMap("Structured Fraction", "1", "-", 0, 1, "f_sc: share of the initial solids that is structured (particles)")
      << particleMap("Confined Fluid Fraction", "1", "-", 0, 1, "f_fc: share of the initial fluid held in the structured solids")
      << lisem("1e+13", real("Elastic Modulus", "0", "Pa", 0, 1e14,
                              "bulk modulus K (OpenLISEM Hazard's meaning); 0: the material is set by Young Modulus"))
      << real("Young Modulus", "1e7", "Pa", 1e3, 1e14, "Young's modulus E, used when Elastic Modulus is 0")
      << real("Poisson Ratio", "0.3", "-", 0, 0.49, "Poisson ratio nu (used when Shear Modulus is 0)")
      << lisem("1e+12", real("Shear Modulus", "0", "Pa", 0, 1e14,
                             "shear modulus G; > 0 sets nu from K and G (or from E and G when Elastic Modulus is 0)"))
      << lisem("0.2", real("Particle Fractional Dimension", "0", "-", 0, 100,
                           "particle volume as a fraction of the cell volume dx^3 (OpenLISEM Hazard); 0: Particle "
                           "Volume or Particles Per Cell"))
      << real("Particle Volume", "0", "m^3", 0, 1e12,
              "particle volume V_I when Particle Fractional Dimension is 0; 0: from Particles Per Cell")
      << real("Particles Per Cell", "4", "-", 1, 400, "particles in the thickest cell when neither volume is given")
      << real("Critical Strain", "0.1", "-", 1e-6, 10, "epsilon_c of the cohesion degradation while yielding (P.26)")
      << real("Dilatancy Angle", "0", "rad", 0, 1.5, "psi of the plastic flow")
      << real("Sound Speed", "0", "m/s", 0, 1e6,
              "c of the time step and artificial viscosity; 0: elastic sqrt(E / (rho (1 - nu^2))), plane stress")
      << real("Smoothing Length Factor", "1", "-", 0.5, 3, "SPH smoothing length h in cells (paper: 1)")
      << real("Particle CFL", "0.2", "-", 0.01, 1, "particle sub-step dt = CFL h / (c + |v|max)")
      << real("Artificial Viscosity Alpha", "0.1", "-", 0, 10,
              "alpha_Pi of Monaghan's artificial viscosity (P.83); default Bui et al. 2008, the paper's scenes use 1")
      << real("Artificial Viscosity Beta", "0", "-", 0, 10,
              "beta_Pi of Monaghan's artificial viscosity (P.83); default Bui et al. 2008, the paper's scenes use 1")
      << real("Artificial Stress Epsilon", "0", "-", 0, 1,
              "epsilon_0 of the artificial stress against tensile clumping (P.85); off by default (its work is an "
              "energy source, docs/particles.md); Gray et al. 2001 and the paper's scenes use 0.3")
      << real("Artificial Stress Exponent", "4", "-", 1, 8, "n of the artificial stress (P.86)")
      << real("PIC Fraction", "0", "-", 0, 1,
              "PIC share of the velocity the particles take from the exchange with the grid's fluid: 0 FLIP "
              "(own velocity plus the exchange's change), 1 PIC (the cells' velocity; smooths, dissipates)");
}

void addTimeKeys(KeyRegistry& r) {
  Section(r, "Time")
      << lisem("0", alias("Begin time", real("Start Time", "0", "min", 0, 1e6,
                                             "simulated time at the start (openLISEM 6: Begin time); also ddd:mmmm")))
      << lisem("100", real("End Time", "1", "min", 0, 1e6, "simulated time at the end; must exceed Start Time; also ddd:mmmm"))
      << lisem("10", real("Timestep", "10", "s", 1e-6, 1e9,
                          "model time step of OpenLISEM Hazard: results are reported every Report every steps "
                          "(the solvers take their own stable steps within it)"))
      << lisem("1", integer("Report every", "1", "-", 1, 1e9, "report maps and progress every this many Timesteps"))
      << real("Stop At Rest Fraction", "0", "-", 0, 0.99,
              "end the run once the kinetic energy (grid phases and particles) has fallen below this fraction "
              "of its peak, as com1DFA's stopCrit; 0: run to End Time. Thin films that still drain carry "
              "little kinetic energy: with Voellmy friction a run can end with them on steep slopes "
              "(docs/voellmy_comparison.md)");
  r.addRule({"Particle Fractional Dimension", "Particle Volume"}, [](const io::RunConfig& c) -> std::string {
    if (c.real("Particle Fractional Dimension") == 0 || c.real("Particle Volume") == 0) return "";
    return "give either Particle Fractional Dimension (a fraction of dx^3) or Particle Volume (m^3), not both";
  });
  r.addRule({"Start Time", "End Time"}, [](const io::RunConfig& c) -> std::string {
    if (c.real("End Time") > c.real("Start Time")) return "";
    return "End Time (" + io::formatNumber(c.real("End Time")) + " min) must exceed Start Time (" +
           io::formatNumber(c.real("Start Time")) + " min)";
  });
}

void addFlowKeys(KeyRegistry& r) {
  Section(r, "Flow")
      << lisem("n.map", map("Manning", "0.01", "s/m^(1/3)", 0, 1, "Manning roughness n"))
      << flag("Slope Correction", "1", "gravity g cos^2(theta) on steep beds (spec section 1)")
      << flag("Curvature Acceleration", "1",
              "solids and particles: the bed turns the material onto its tangent plane along its path, and the "
              "turn's normal force adds to friction where the bed presses; material thrown off a convex edge "
              "lifts off and lands (run-up in smooth valleys within 2 %; 0: the plane's g cos^2(theta) only)")
      << choice("Depth Pressure", {"cos2", "cos4"}, "cos2",
                "depth-pressure gravity g_p = g cos^2(theta) (lake at rest exact) or g cos^4(theta)");
}

/// Rainfall and infiltration (docs/sources.md), with OpenLISEM Hazard's names and units
/// (parametermanager.h lines 76-85, 125, 161; modelruninit.cpp lines 24, 236, 252, 382, 738).
void addSourceKeys(KeyRegistry& r) {
  Section(r, "Rain and infiltration")
      << lisem("0", flag("Include Rainfall", "0", "rain on every domain cell (single-phase model)"))
      << lisem("<site>/time/", text("TimeInput Directory", "", "folder holding the rainfall file (relative to the "
                                    "run-file's folder)", KeyType::Directory))
      << lisem("rain", readWhen("Include Rainfall", text("Rainfall", "rain",
                                "rainfall file in OpenLISEM's format (one station, minutes and mm/h), in "
                                "TimeInput Directory; not read when Rainfall Intensity is given")))
      << readWhen("Include Rainfall", real("Rainfall Intensity", "0", "mm/h", 0, 1e4,
                                           "uniform constant intensity; when given it replaces the Rainfall file"))
      << lisem("0", flag("Include Infiltration", "0", "constant-rate infiltration of KSatSimple (single-phase model)"))
      << lisem("ksatsimple.map", readWhen("Include Infiltration", map("KSatSimple", "0", "mm/h", 0, 1e5,
                                          "infiltration capacity (saturated conductivity of the top soil)")));
}

void addNumericsKeys(KeyRegistry& r) {
  Section(r, "Numerics")
      << real("CFL", "0.5", "-", 0.01, 1.0,
              "Courant number over the sum of both directions' wave speeds (at most 0.5, which keeps the scheme "
              "positive), or per direction with Time Scheme=split or hancock (up to 1: the sweeps stay positive by the "
              "draining time; GeoClaw's default is 0.9)")
      << choice("Time Scheme", {"unsplit", "split", "hancock"}, "unsplit",
                "water: SSP-RK2 over both directions at once; dimensionally split sweeps with a per-direction "
                "time step (about half the steps where the flow is not along one axis), each one SSP-RK2; or the "
                "same sweeps with one MUSCL-Hancock stage each (half the flux evaluations of split; at CFL 0.9 "
                "far less damping of roll waves and surges on steep slopes); two-phase runs are unsplit")
      << choice("Limiter", {"minmod", "vanleer", "mc", "none"}, "mc",
                "slope limiter of the MUSCL reconstruction (none: first-order scheme, for comparisons)")
      << choice("Riemann Solver", {"hll", "hllc"}, "hllc", "approximate Riemann solver of the fluxes")
      << choice("Precision", {"float", "double"}, "float", "floating-point precision on the device")
      << text("Device", "", "device selector: index or name substring; empty = automatic")
      << choice("Boundary Type", {"open", "wall", "level"}, "open",
                "boundary condition at the raster edge: open (outflow only, the outside continues the inside), "
                "wall, or level (outflow only against still water at the edge's initial surface outside, a free "
                "overfall where it starts dry; keeps standing water at the edge at rest; in two-phase runs for the "
                "fluid, the solids see an open edge)")
      << choice("Nodata Boundary Type", {"wall", "open", "level"}, "wall", "boundary condition at nodata cells (as Boundary Type)")
      << real("Minimum Flow Height", "1e-6", "m", 1e-9, 1,
              "dry threshold below which velocity is zero (at least 1 nm: the velocity q/h of thinner films "
              "overflows in single precision)")
      << flag("Skip Dry Tiles", "1", "skip 16x16-cell tiles with no flow within one tile (0: update every cell)");
}

void addOutputKeys(KeyRegistry& r) {
  Section(r, "Output")
      << real("Arrival Threshold", "0.01", "m", 0, 100, "thickness that marks arrival")
      << lisem("<site>/res/", text("Output Directory", "output",
                                    "folder the results are written to (relative to the run-file's folder)",
                                    KeyType::Directory))
      << choice("Output Format", {"geotiff", "pcraster"}, "geotiff", "raster format of the outputs")
      << flag("Report Series", "1", "write time-series maps every report (Timestep x Report every)")
      << choice("Series Names", {"talus", "openlisem"}, "talus",
                "series file names: series/hf_NNNN (report index) or OpenLISEM's hf000000.012 (model step)")
      << real("Checkpoint Interval", "0", "min", 0, 1e6,
              "simulated time between checkpoints for `talus run --resume` (0: none)")
      << real("Checkpoint Wall Interval", "10", "min", 0, 1e6,
              "wall-clock time between checkpoints (0: none); short runs never reach it");
}

KeyRegistry buildKeys() {
  KeyRegistry r;
  addInputKeys(r);
  addSolidKeys(r);
  addEntrainmentKeys(r);
  addParticleKeys(r);
  addTimeKeys(r);
  addFlowKeys(r);
  addSourceKeys(r);
  addNumericsKeys(r);
  addOutputKeys(r);
  addLisemKeys(r);
  return r;
}

}  // namespace

const io::KeyRegistry& talusRunKeys() {
  static const io::KeyRegistry keys = buildKeys();
  return keys;
}

}  // namespace talus::sim
