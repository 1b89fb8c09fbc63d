// What a particle model offers to viewers: particle positions and per-particle attributes, read
// between steps. The desktop application draws whatever a ParticleView lists, so a particle solver
// shows up in it by implementing this interface; Simulation::particleView() returns nullptr until
// a run has particles. No Qt, no OpenGL here.
#pragma once
#include <CL/cl.h>

#include <cstddef>
#include <string>
#include <vector>

namespace talus::sim {

/// One per-particle quantity a viewer can colour particles by.
struct ParticleAttributeInfo {
  std::string name;   ///< e.g. "velocity", "stress invariant", "cohesion fraction"
  std::string unit;   ///< "m/s", "Pa", "-" (dimensionless)
};

/// Read access to the particles of a run (implemented by the particle model).
class ParticleView {
 public:
  virtual ~ParticleView() = default;
  /// Number of live particles.
  virtual std::size_t count() const = 0;
  /// The attributes attribute() can read, in display order.
  virtual std::vector<ParticleAttributeInfo> attributes() const = 0;
  /// World coordinates x, y (georeferenced, as the grid's geotransform) and z (elevation) [m],
  /// three floats per particle.
  virtual std::vector<float> positions() const = 0;
  /// One value per particle of a listed attribute (empty for an unknown name).
  virtual std::vector<float> attribute(const std::string& name) const = 0;
  /// The device buffer holding positions as float x, y, z triples, when the model keeps them so
  /// (viewers may then copy device to device); nullptr otherwise.
  virtual cl_mem positionBuffer() const { return nullptr; }
};

}  // namespace talus::sim
