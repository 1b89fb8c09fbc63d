#include "sim/ViewFields.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <memory>

#include "compute/Buffer.hpp"
#include "compute/ClError.hpp"
#include "compute/Context.hpp"
#include "compute/Program.hpp"
#include "core/Error.hpp"
#include "flow/FlowSolver.hpp"
#include "sim/Scene.hpp"

namespace talus::sim {
namespace {

constexpr float kNoValue = std::numeric_limits<float>::quiet_NaN();

/// |q| / h where h exceeds the dry threshold, else 0.
double speed(double qx, double qy, double h, double hDry) { return h > hDry ? std::hypot(qx, qy) / h : 0.0; }

/// Solver fields downloaded at most once per snapshot.
class FieldCache {
 public:
  explicit FieldCache(const flow::FlowSolver& s) : s_(s) {}
  const std::vector<double>& get(const std::string& field) {
    auto it = fields_.find(field);
    if (it != fields_.end()) return it->second;
    return fields_[field] = download(field);
  }

 private:
  std::vector<double> download(const std::string& f) {
    if (f == "h") return s_.h();
    if (f == "qx") return s_.qx();
    if (f == "qy") return s_.qy();
    if (f == "hs") return s_.hs();
    if (f == "qsx") return s_.qsx();
    if (f == "qsy") return s_.qsy();
    if (f == "hMax") return s_.hMax();
    if (f == "vMax") return s_.vMax();
    if (f == "arrival") return s_.arrival();
    if (f == "cohesion") return s_.solidScalar(3);
    if (!maxima_) maxima_ = std::make_unique<flow::DebrisMaxima>(s_.debrisMaxima());
    if (f == "m.hf") return maxima_->hf;
    if (f == "m.hs") return maxima_->hs;
    if (f == "m.h") return maxima_->h;
    if (f == "m.vf") return maxima_->vf;
    if (f == "m.vs") return maxima_->vs;
    return {};
  }
  const flow::FlowSolver& s_;
  std::map<std::string, std::vector<double>> fields_;
  std::unique_ptr<flow::DebrisMaxima> maxima_;
};

}  // namespace

const std::vector<float>* ViewSnapshot::layer(const std::string& name) const {
  for (std::size_t k = 0; k < layerNames.size(); ++k)
    if (layerNames[k] == name) return &layers[k];
  return nullptr;
}

cl_mem ViewSnapshot::deviceLayer(const std::string& name) const {
  auto it = deviceLayers.find(name);
  return it == deviceLayers.end() || !it->second ? nullptr : it->second->mem();
}

const std::vector<float>* ViewSnapshot::particleAttribute(const std::string& name) const {
  for (std::size_t k = 0; k < particleAttributeNames.size(); ++k)
    if (particleAttributeNames[k] == name) return &particleAttributes[k];
  return nullptr;
}

ViewFields::ViewFields(const Scene& scene, const flow::FlowSolver& solver, const ParticleView* particles)
    : scene_(scene), solver_(solver), particles_(particles) {
  const bool two = solver.twoPhase();
  layers_.push_back({"h", two ? "flow thickness (total)" : "flow thickness", "m", true});
  if (two) {
    layers_.push_back({"hf", "flow thickness (fluid)", "m", true});
    layers_.push_back({"hs", "flow thickness (solid)", "m", true});
  }
  layers_.push_back({"velocity", two ? "velocity (mixture)" : "velocity", "m/s", true});
  if (two) {
    layers_.push_back({"vf", "velocity (fluid)", "m/s", true});
    layers_.push_back({"vs", "velocity (solid)", "m/s", true});
    layers_.push_back({"solid fraction", "solid fraction", "-", true});
  }
  layers_.push_back({"hmax", "maximum thickness", "m", true});
  if (two) {
    layers_.push_back({"hfmax", "maximum thickness (fluid)", "m", true});
    layers_.push_back({"hsmax", "maximum thickness (solid)", "m", true});
  }
  layers_.push_back({"vmax", "maximum velocity", "m/s", true});
  layers_.push_back({"arrival", "arrival time", "s", false});
  if (two && !scene.flow.cohesion.empty()) layers_.push_back({"cohesion", "cohesion", "Pa", true});

  const Raster& dem = scene.dem;
  elevation_.resize(dem.values.size());
  double mass = 0, mx = 0, my = 0;
  for (int j = 0; j < dem.grid.ny; ++j)
    for (int i = 0; i < dem.grid.nx; ++i) {
      const std::size_t k = dem.grid.index(i, j);
      elevation_[k] = dem.valid[k] ? static_cast<float>(dem.values[k]) : kNoValue;
      double m = scene.flow.h.empty() ? 0.0 : scene.flow.h[k];
      if (!scene.flow.hs.empty()) m += scene.flow.hs[k];
      mass += m;
      mx += m * i;
      my += m * j;
    }
  if (mass > 0) {
    centroidX_ = mx / mass;
    centroidY_ = my / mass;
  }
}

const Grid& ViewFields::grid() const { return scene_.dem.grid; }

const GridLayerInfo* ViewFields::findLayer(const std::string& name) const {
  for (const auto& l : layers_)
    if (l.name == name) return &l;
  return nullptr;
}

std::vector<ParticleAttributeInfo> ViewFields::particleAttributes() const {
  return particles_ ? particles_->attributes() : std::vector<ParticleAttributeInfo>{};
}

void ViewFields::setDeviceFields(compute::Context& ctx, std::map<std::string, cl_mem> fields) {
  ctx_ = &ctx;
  deviceFields_ = std::move(fields);
  packer_ = std::make_unique<ViewPacker>(ctx);
  const std::vector<uint8_t>& valid = scene_.dem.valid;
  validMask_ = std::make_shared<compute::RawBuffer>(ctx, valid.size(), "view mask");
  validMask_->writeBytes(valid.data(), valid.size());
}

bool ViewFields::recipe(const std::string& n, PackMode& mode, std::vector<std::string>& f) const {
  // The same formulas as the host computation in snapshot(), field by field.
  const bool two = solver_.twoPhase();
  if (n == "h") {
    mode = two ? PackMode::Sum : PackMode::Copy;
    f = two ? std::vector<std::string>{"h", "hs"} : std::vector<std::string>{"h"};
  } else if (n == "hf" || n == "hs") {
    mode = PackMode::Copy;
    f = {n == "hf" ? "h" : "hs"};
  } else if (n == "velocity" && two) {
    mode = PackMode::SpeedSum;
    f = {"h", "qx", "qy", "hs", "qsx", "qsy"};
  } else if (n == "velocity" || n == "vf") {
    mode = PackMode::Speed;
    f = {"h", "qx", "qy"};
  } else if (n == "vs") {
    mode = PackMode::Speed;
    f = {"hs", "qsx", "qsy"};
  } else if (n == "solid fraction") {
    mode = PackMode::Fraction;
    f = {"h", "hs"};
  } else if (n == "hmax" || n == "hfmax" || n == "hsmax") {
    mode = PackMode::Copy;
    f = {n == "hfmax" ? "m.hf" : n == "hsmax" ? "m.hs" : two ? "m.h" : "hMax"};
  } else if (n == "vmax") {
    mode = two ? PackMode::Max2 : PackMode::Copy;
    f = two ? std::vector<std::string>{"m.vf", "m.vs"} : std::vector<std::string>{"vMax"};
  } else if (n == "arrival") {
    mode = PackMode::Arrival;
    f = {"arrival"};
  } else {
    return false;
  }
  return true;
}

bool ViewFields::canPackOnDevice(const std::string& name) const {
  PackMode mode;
  std::vector<std::string> fields;
  if (!packer_ || !findLayer(name) || !recipe(name, mode, fields)) return false;
  for (const std::string& f : fields)
    if (!deviceFields_.count(f) || !deviceFields_.at(f)) return false;
  return true;
}

void ViewFields::packLayer(const std::string& name, cl_mem out, cl_command_queue queue, float noValue) const {
  PackMode mode;
  std::vector<std::string> fields;
  if (!canPackOnDevice(name) || !recipe(name, mode, fields))
    throw ComputeError("layer '" + name + "' cannot be packed on the device (its solver fields are not on it)");
  cl_mem in[6] = {};
  for (std::size_t k = 0; k < fields.size(); ++k) in[k] = deviceFields_.at(fields[k]);
  const PackInputs inputs{in[0], in[1], in[2], in[3], in[4], in[5], validMask_->mem()};
  packer_->packValues(mode, grid().cells(), inputs, scene_.settings.hDry, out, queue, noValue);
}

ViewSnapshot ViewFields::snapshot(const std::vector<std::string>& names, bool keepDevice, float deviceNoValue) const {
  ViewSnapshot s;
  s.grid = grid();
  s.time = solver_.time();
  FieldCache cache(solver_);
  const std::vector<uint8_t>& valid = scene_.dem.valid;
  const double hDry = scene_.settings.hDry;
  const bool two = solver_.twoPhase();
  auto add = [&](const std::string& name, std::vector<float> values) {
    for (std::size_t k = 0; k < values.size(); ++k)
      if (!valid[k]) values[k] = kNoValue;
    s.layerNames.push_back(name);
    s.layers.push_back(std::move(values));
  };
  auto fromField = [&](const std::string& field) {
    const std::vector<double>& v = cache.get(field);
    return std::vector<float>(v.begin(), v.end());
  };
  for (const GridLayerInfo& info : layers_) {
    const std::string& n = info.name;
    if (!names.empty() && std::find(names.begin(), names.end(), n) == names.end()) continue;
    const std::size_t cells = s.grid.cells();
    if (canPackOnDevice(n)) {
      // Packed on the device (the kernel applies the mask), read back once; the no-value marker
      // of the device copy becomes NaN on the host.
      const float noValue = keepDevice ? deviceNoValue : kNoValue;
      auto packed = std::make_shared<compute::RawBuffer>(*ctx_, cells * sizeof(float), "packed view layer");
      packLayer(n, packed->mem(), nullptr, noValue);
      std::vector<float> values(cells);
      packed->readBytes(values.data(), cells * sizeof(float));
      if (!std::isnan(noValue))
        for (float& v : values)
          if (v == noValue) v = kNoValue;
      s.layerNames.push_back(n);
      s.layers.push_back(std::move(values));
      if (keepDevice) s.deviceLayers[n] = std::move(packed);
      continue;
    }
    std::vector<float> out(cells, 0.0f);
    if (n == "h" || n == "velocity" || n == "hf" || n == "vf") {
      const auto &h = cache.get("h"), &qx = cache.get("qx"), &qy = cache.get("qy");
      const bool fluidOnly = n == "hf" || n == "vf" || !two;
      const bool thickness = n == "h" || n == "hf";
      for (std::size_t k = 0; k < cells; ++k) {
        double ht = h[k], ux = qx[k], uy = qy[k];
        if (!fluidOnly) {
          ht += cache.get("hs")[k];
          ux += cache.get("qsx")[k];
          uy += cache.get("qsy")[k];
        }
        out[k] = static_cast<float>(thickness ? ht : speed(ux, uy, ht, hDry));
      }
    } else if (n == "hs" || n == "vs") {
      const auto &hs = cache.get("hs"), &qx = cache.get("qsx"), &qy = cache.get("qsy");
      for (std::size_t k = 0; k < cells; ++k)
        out[k] = static_cast<float>(n == "hs" ? hs[k] : speed(qx[k], qy[k], hs[k], hDry));
    } else if (n == "solid fraction") {
      const auto &hf = cache.get("h"), &hs = cache.get("hs");
      for (std::size_t k = 0; k < cells; ++k) {
        const double ht = hf[k] + hs[k];
        out[k] = ht > hDry ? static_cast<float>(hs[k] / ht) : 0.0f;
      }
    } else if (n == "hmax") {
      out = fromField(two ? "m.h" : "hMax");
    } else if (n == "hfmax") {
      out = fromField("m.hf");
    } else if (n == "hsmax") {
      out = fromField("m.hs");
    } else if (n == "vmax") {
      if (!two) {
        out = fromField("vMax");
      } else {
        const auto &vf = cache.get("m.vf"), &vs = cache.get("m.vs");
        for (std::size_t k = 0; k < cells; ++k) out[k] = static_cast<float>(std::max(vf[k], vs[k]));
      }
    } else if (n == "arrival") {
      const auto& a = cache.get("arrival");
      for (std::size_t k = 0; k < cells; ++k) out[k] = a[k] < 0 ? kNoValue : static_cast<float>(a[k]);
    } else if (n == "cohesion") {
      // the cohesion the solids carry now (none where there are none)
      const auto &c = cache.get("cohesion"), &hs = cache.get("hs");
      for (std::size_t k = 0; k < cells; ++k) out[k] = hs[k] > hDry ? static_cast<float>(c[k]) : kNoValue;
    }
    add(n, std::move(out));
  }
  // Front: the flowing cell farthest from where the mass started (thickness above the arrival threshold).
  const std::vector<double>& h = cache.get("h");
  const std::vector<double>* hs = two ? &cache.get("hs") : nullptr;
  double front2 = 0;
  for (int j = 0; j < s.grid.ny; ++j)
    for (int i = 0; i < s.grid.nx; ++i) {
      const std::size_t k = s.grid.index(i, j);
      const double ht = h[k] + (hs ? (*hs)[k] : 0.0);
      if (ht > scene_.settings.arrivalH)
        front2 = std::max(front2, (i - centroidX_) * (i - centroidX_) + (j - centroidY_) * (j - centroidY_));
    }
  s.frontDistance = std::sqrt(front2) * s.grid.dx;
  if (particles_) {
    s.particleCount = particles_->count();
    s.particlePositions = particles_->positions();
    for (const ParticleAttributeInfo& a : particles_->attributes()) {
      s.particleAttributeNames.push_back(a.name);
      s.particleAttributes.push_back(particles_->attribute(a.name));
    }
  }
  return s;
}

}  // namespace talus::sim
