// The OpenLISEM Hazard 2.x keys that Talus knows without using them. OpenLISEM's GUI writes all
// ~113 keys of its parameter list into every run-file (bastianvandenbout/LISEM,
// lisem/model/parameters/parametermanager.h, InitParameters), processes that are off included, so
// a migrated run-file must load unchanged. The keys Talus uses, with OpenLISEM's meaning, are
// declared in RunKeys.cpp; the rest fall into four kinds (io::KeyRole):
//   - switches of processes Talus does not model: 0 is accepted, 1 refused naming the process;
//   - inputs of those processes (maps, files, parameters): accepted and never read, as OpenLISEM
//     does not read them either while their process is off (modelruninit.cpp, ModelRunLoadData);
//   - settings without effect in Talus (device, memory, OpenLISEM's sub-step caps): a note;
//   - output switches not honoured (hydrographs, totals, processes Talus lacks): a note
//     (RunConfigNotes.cpp); the format and series switches are honoured (sim/Scene.cpp).
// Keys Talus does not read are text keys: any value is accepted, as none is used. OpenLISEM's
// defaults are quoted from parametermanager.h as its GUI writes them (QString::number).
#include <string>

#include "sim/KeyBuilders.hpp"

namespace talus::sim::keys {

namespace {

/// A switch of a process Talus does not model; `planned`: Talus is meant to model it.
KeySpec process(std::string name, std::string process, bool planned = false) {
  KeySpec k = lisem("0", flag(std::move(name), "0", ""));
  k.role = KeyRole::Unmodelled;
  k.process = std::move(process);
  k.plannedProcess = planned;
  k.help = "OpenLISEM Hazard process Talus does not model" + std::string(planned ? " yet" : "") + ": " + k.process;
  return k;
}

/// A key of a given role that Talus never reads; `why` says what it belongs to.
KeySpec unread(KeyRole role, std::string name, std::string lisemDefault, std::string why) {
  KeySpec k = lisem(lisemDefault, text(std::move(name), lisemDefault, ""));
  k.role = role;
  k.process = std::move(why);
  k.help = k.process;
  return k;
}

/// An input of a process Talus does not model.
KeySpec input(std::string name, std::string lisemDefault, std::string process) {
  return unread(KeyRole::ProcessInput, std::move(name), std::move(lisemDefault), "input of " + process);
}

KeySpec noEffect(std::string name, std::string lisemDefault, std::string why) {
  return unread(KeyRole::NoEffect, std::move(name), std::move(lisemDefault), std::move(why));
}

KeySpec outputSwitch(std::string name, std::string lisemDefault = "0") {
  return unread(KeyRole::OutputSwitch, std::move(name), std::move(lisemDefault), "OpenLISEM output switch");
}

const char* kHydrology = "hydrology (Include Hydrology)";
const char* kEvapo = "evapotranspiration (Include Evapotranspiration)";
const char* kChannel = "channel flow (Include Channel)";
const char* kSlope = "slope stability (Include Slope Stability)";
const char* kLoose = "the loose material layer (Include Loose Material Layer)";
const char* kTrees = "tree instancing (Tree Instancing)";

}  // namespace

void addLisemKeys(KeyRegistry& r) {
  // parametermanager.h lines 73-107: time, folders, processes, compute settings.
  Section(r, "OpenLISEM Hazard processes and settings")
      << noEffect("Timestep Flow", "1", "cap on OpenLISEM's flow step; Talus's flow step follows from CFL")
      << noEffect("Timestep Particle Flow", "0.001", "OpenLISEM's particle step; Talus's follows from Particle CFL")
      << process("Include Hydrology", "hydrology (infiltration and surface storage)", true)
      << input("Custom Infiltration", "0", kHydrology)
      << process("Include Evapotranspiration", "evapotranspiration")
      << process("Include GroundWater Flow", "groundwater flow")
      << process("Include Channel", "1-d channel flow")
      << process("Include Erosion", "surface erosion")
      << process("Include Loose Material Layer", "entrainment of a loose material layer")
      << process("Include Slope Stability", "slope stability")
      << process("Include Slope Failure", "slope failure")
      << process("Include Initial Stability", "initial slope stability")
      << process("Include Seismic Trigger", "seismic triggering")
      << process("Include Rigid-Body Phyisics", "rigid-body physics")
      << noEffect("Use CPU", "0", "Talus's device is chosen by Device (or --device)")
      << noEffect("Limit Memory Usage", "0", "Talus sizes its buffers to the scene")
      << process("Simulate Subsection", "simulating a subsection of the maps (MASK)")
      << input("SubSection Value", "1", "the subsection (Simulate Subsection)")
      // lines 112-119: physical parameters Talus has no counterpart of.
      << noEffect("Reynolds Number Multiplier", "1",
                  "Talus's Reynolds numbers are Viscous and Interfacial Reynolds Number")
      << input("Custom Channel Slope", "1", kChannel)
      << input("Initial Stability Margin", "0.005", "initial slope stability (Include Initial Stability)");
  // lines 125-206: time series files and maps of processes Talus does not model.
  // Rainfall, TimeInput Directory, KSatSimple and their switches are Talus's (RunKeys.cpp).
  Section s(r, "OpenLISEM Hazard inputs");
  for (const char* f : {"Temperature:temp", "Radiation:rad", "Wind:wind", "Vapor Pressure:vap", "ndvi:ndvi"}) {
    const std::string pair = f;
    s << input(pair.substr(0, pair.find(':')), pair.substr(pair.find(':') + 1), kEvapo);
  }
  s << input("MASK", "mask.map", "the subsection (Simulate Subsection)")
    << input("Channel", "channelldd.map", kChannel) << input("Channel Width", "channelwidth.map", kChannel)
    << input("Channel Depth", "channeldepth.map", kChannel) << input("Channel Slope", "channelslope.map", kChannel)
    << input("Building Cover", "buildingcover.map", kHydrology)
    << input("Road Width", "buildingcover.map", kHydrology)  // sic: OpenLISEM's default name
    << input("Vegetation Height", "vegheight.map", kHydrology) << input("Vegetation Cover", "vegcover.map", kHydrology)
    << input("SMAX Surface", "smaxsurface.map", kHydrology) << input("SMAX Canopy", "smaxcanopy.map", kHydrology)
    << input("CropF", "cropf.map", kEvapo) << input("Tree Density", "treedens.map", kTrees)
    << input("Tree Length", "treelength.map", kTrees) << input("Tree Radius", "treeradius.map", kTrees)
    << input("Tree Count", "treecount.map", kTrees);
  for (const char* m : {"KSatBottom:ksatbottom", "Clay:clay", "Sand:sand", "Gravel:gravel", "Organic:om",
                        "Density:density", "MatricSuction:psi", "Porosity:thetas", "A:a", "B:b",
                        "Soil Depth:soildepth", "Ground Water Height:gwh", "Theta Initial:thetaieff"}) {
    const std::string pair = m;
    s << input(pair.substr(0, pair.find(':')), pair.substr(pair.find(':') + 1) + ".map", kHydrology);
  }
  s << input("Cohesion Top", "cohtop.map", "erosion or slope stability")
    << input("Cohesion Channel", "cohch.map", kSlope)
    << input("Aggregate Stability", "aggrst.map", "erosion (Include Erosion)")
    << input("Internal Friction Angle", "ifa.map", kSlope) << input("Cohesion Bottom", "coh.map", kSlope)
    << input("Density Bottom", "densityb.map", kSlope)
    << input("Rocksize", "rocksize.map", "slope failure (Include Slope Failure)")
    << input("Material Depth", "materialdepth.map", kLoose)
    << input("Material Internal Friction Angle", "materialifa.map", kLoose)
    << input("Material Density Bottom", "materialdensity.map", kLoose)
    << input("Material Rocksize", "materialrocksize.map", kLoose)
    << input("Peak Ground Accaleration", "pga.map", "seismic triggering (Include Seismic Trigger)");
  // lines 212-213: rigid bodies.
  Section(r, "OpenLISEM Hazard processes and settings")
      << process("Tree Instancing", "tree instancing (rigid-body physics)")
      << input("Friction Coefficient", "0.005", "rigid-body physics (Include Rigid-Body Phyisics)");
  // lines 219-238: output switches (Report every, line 226, is Talus's: RunKeys.cpp).
  // The switches Talus honours (sim/Scene.cpp, seriesSelection): format, the series and which
  // variables they hold (modelruninit.cpp 283-300, modelreport.cpp 410-465).
  Section o(r, "OpenLISEM Hazard outputs");
  o << lisem("0", flag("Output GeoTIFF format", "0",
                       "OpenLISEM: maps as GeoTIFF (1) or PCRaster (0); used when Output Format is not given"))
    << lisem("0", flag("Output timeseries", "0",
                       "OpenLISEM: write the series selected below; used when Report Series is not given"));
  for (const char* v : {"H", "HS", "HT (total height)", "SFRAC", "V", "VS", "HT (total averaged velocity)"})
    o << lisem("0", flag(std::string("Output timeseries of ") + v, "0", "OpenLISEM: series of this variable"));
  for (const char* name : {"Calculate Max per sub-step", "Output Max Height/Vel only", "Output totals", "Output hydrographs"})
    o << outputSwitch(name);
  o << outputSwitch("Report particles every", "1000");
  for (const char* v : {"Infil", "GWH", "Soil Loss", "Sediment Load"})
    o << outputSwitch(std::string("Output timeseries of ") + v);
}

}  // namespace talus::sim::keys
