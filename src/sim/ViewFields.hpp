// What a running simulation offers to viewers, without Qt or OpenGL: the drawable grid layers
// (flow thickness per phase, velocity, solid fraction, maxima, arrival time, ...) with their units,
// the particles of an optional ParticleView, and snapshots of both taken between steps. Derived
// layers (velocity, solid fraction) are computed here so that viewers contain no physics.
#pragma once
#include <CL/cl.h>

#include <cstddef>
#include <string>
#include <vector>

#include "core/Grid.hpp"
#include "sim/ParticleView.hpp"

namespace talus::flow {
class FlowSolver;
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

  /// The layer with this name, or nullptr when the snapshot does not hold it.
  const std::vector<float>* layer(const std::string& name) const;
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
  /// memory: call it between steps on the thread that drives the run.
  ViewSnapshot snapshot(const std::vector<std::string>& names = {}) const;
  /// The device buffer that holds a layer as it is drawn (float, one value per cell), so viewers
  /// can copy it device to device; nullptr when the layer exists only as a host computation (today
  /// every grid layer: the flow solver keeps its buffers private and in the run's precision).
  cl_mem deviceBuffer(const std::string& name) const;

 private:
  std::vector<float> computeLayer(const std::string& name) const;

  const Scene& scene_;
  const flow::FlowSolver& solver_;
  const ParticleView* particles_;
  std::vector<GridLayerInfo> layers_;
  std::vector<float> elevation_;
  double centroidX_ = 0, centroidY_ = 0;  ///< initial mass centroid [cells]
};

}  // namespace talus::sim
