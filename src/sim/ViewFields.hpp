// What a running simulation offers to viewers, without Qt or OpenGL: the drawable grid layers
// (flow thickness per phase, velocity, solid fraction, maxima, arrival time, ...) with their units,
// the particles of an optional ParticleView, and snapshots of both taken between steps. Derived
// layers (velocity, solid fraction) are computed here so that viewers contain no physics.
#pragma once
#include <CL/cl.h>

#include <cstddef>
#include <limits>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "core/Grid.hpp"
#include "sim/ParticleView.hpp"
#include "sim/ViewPacker.hpp"

namespace talus::flow {
class FlowSolver;
}
namespace talus::compute {
class Context;
class RawBuffer;
}

namespace talus::sim {

struct Scene;

/// One drawable grid layer.
struct GridLayerInfo {
  std::string name;    ///< identifier, e.g. "h", "velocity", "arrival"
  std::string label;   ///< human-readable, e.g. "flow thickness (total)"
  std::string unit;    ///< "m", "m/s", "s", "-"
  /// True when 0 means "nothing here" (a dry cell): viewers draw such cells transparent. Cells a
  /// layer has no value for (outside the domain, never arrived) are NaN in every layer.
  bool zeroIsEmpty = true;
};

/// Host copies of the layers and particles at one instant: what a viewer draws.
struct ViewSnapshot {
  Grid grid;
  double time = 0;       ///< simulated [s]
  long long steps = 0;
  std::vector<std::string> layerNames;       ///< names of the layers held, parallel to layers
  std::vector<std::vector<float>> layers;    ///< one value per cell (grid.index(i, j)), NaN: no value
  std::size_t particleCount = 0;
  std::vector<float> particlePositions;      ///< x, y, z [m] per particle (world coordinates)
  std::vector<std::string> particleAttributeNames;
  std::vector<std::vector<float>> particleAttributes;  ///< parallel to particleAttributeNames
  double frontDistance = 0;  ///< largest distance of a flowing cell from the initial mass centroid [m]
  /// Device copies (float, one per cell) of the layers packed on the device, kept only when the
  /// snapshot was asked to (ViewFields::snapshot keepDevice): viewers sharing buffers with OpenGL
  /// copy them device to device. They live as long as the snapshot.
  std::map<std::string, std::shared_ptr<compute::RawBuffer>> deviceLayers;

  /// The layer with this name, or nullptr when the snapshot does not hold it.
  const std::vector<float>* layer(const std::string& name) const;
  /// The device copy of a layer, or nullptr when the snapshot holds none.
  cl_mem deviceLayer(const std::string& name) const;
  /// The particle attribute with this name, or nullptr.
  const std::vector<float>* particleAttribute(const std::string& name) const;
};

class ViewFields {
 public:
  /// Layers of `solver` (and particles of `particles`, which may be nullptr) for the scene it runs.
  /// The scene and solver must outlive this object.
  ViewFields(const Scene& scene, const flow::FlowSolver& solver, const ParticleView* particles = nullptr);

  /// The grid layers of this run (two-phase runs list the per-phase layers as well).
  const std::vector<GridLayerInfo>& gridLayers() const { return layers_; }
  /// The layer with this name, or nullptr.
  const GridLayerInfo* findLayer(const std::string& name) const;
  /// The particle attributes (empty when the run has no particles).
  std::vector<ParticleAttributeInfo> particleAttributes() const;
  bool hasParticles() const { return particles_ != nullptr; }
  const Grid& grid() const;
  /// Bed elevation as float, NaN outside the domain (static: read once).
  const std::vector<float>& elevation() const { return elevation_; }

  /// Reads the named layers (every layer when `names` is empty) and the particles. Reads device
  /// memory: call it between steps on the thread that drives the run. Layers whose solver fields
  /// are on the device (setDeviceFields) are packed there and read back once; with `keepDevice`
  /// their packed float copies stay in ViewSnapshot::deviceLayers for device-to-device drawing,
  /// holding `deviceNoValue` where the host copy holds NaN (shaders cannot test for NaN reliably).
  ViewSnapshot snapshot(const std::vector<std::string>& names = {}, bool keepDevice = false,
                        float deviceNoValue = std::numeric_limits<float>::quiet_NaN()) const;

  /// Makes the solver's device fields (`real`, one per cell) known: names as the solver calls them,
  /// "h", "qx", "qy", "hs", "qsx", "qsy", "hMax", "vMax", "arrival" (two-phase maxima: "m.hf", "m.hs",
  /// "m.h", "m.vf", "m.vs"). The buffers must live as long as this object. Layers all of whose
  /// fields are listed are then packed on the device (packLayer, snapshot). Today's solvers keep
  /// their buffers private, so no caller does this yet and every layer is computed on the host.
  void setDeviceFields(compute::Context& ctx, std::map<std::string, cl_mem> fields);
  /// True when packLayer can fill `name` on the device.
  bool canPackOnDevice(const std::string& name) const;
  /// Enqueues the packing of layer `name` into `out` (float, at least grid().cells() values; a plain
  /// buffer or an acquired OpenGL buffer) on `queue` (null: the run's). Call between steps.
  /// Cells without a value get `noValue`. Throws talus::ComputeError when !canPackOnDevice(name).
  void packLayer(const std::string& name, cl_mem out, cl_command_queue queue = nullptr,
                 float noValue = std::numeric_limits<float>::quiet_NaN()) const;

 private:
  /// The packing of a layer: mode and solver field names for a..f (empty: unused). False when the
  /// layer has no device recipe (cohesion: a host map).
  bool recipe(const std::string& name, PackMode& mode, std::vector<std::string>& fields) const;

  const Scene& scene_;
  const flow::FlowSolver& solver_;
  const ParticleView* particles_;
  std::vector<GridLayerInfo> layers_;
  std::vector<float> elevation_;
  double centroidX_ = 0, centroidY_ = 0;  ///< initial mass centroid [cells]
  // Device packing (setDeviceFields): the fields, the packer, the cell mask.
  compute::Context* ctx_ = nullptr;
  std::map<std::string, cl_mem> deviceFields_;
  std::unique_ptr<ViewPacker> packer_;
  std::shared_ptr<compute::RawBuffer> validMask_;
};

}  // namespace talus::sim
