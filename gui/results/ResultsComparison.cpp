#include "results/ResultsComparison.hpp"

#include <algorithm>
#include <cmath>

namespace talus::gui {

std::string differenceLayerName(const std::string& name) { return name + "-diff"; }

std::vector<float> layerDifference(const std::vector<float>& a, const std::vector<float>& b) {
  std::vector<float> d(a.size(), NAN);
  if (a.size() != b.size()) return d;
  for (std::size_t k = 0; k < a.size(); ++k)
    if (std::isfinite(a[k]) && std::isfinite(b[k]) && !(a[k] == 0 && b[k] == 0)) d[k] = a[k] - b[k];
  return d;
}

void addDifferenceLayers(sim::ViewSnapshot& into, const sim::ViewSnapshot& other) {
  const std::size_t own = into.layerNames.size();  // not the differences appended here
  for (std::size_t l = 0; l < own; ++l) {
    const std::vector<float>* b = other.layer(into.layerNames[l]);
    if (!b) continue;
    std::vector<float> d = layerDifference(into.layers[l], *b);
    into.layerNames.push_back(differenceLayerName(into.layerNames[l]));
    into.layers.push_back(std::move(d));
  }
}

std::vector<sim::GridLayerInfo> differenceCatalogue(const std::vector<sim::GridLayerInfo>& layers,
                                                    const std::vector<sim::GridLayerInfo>& other,
                                                    const QString& otherName) {
  std::vector<sim::GridLayerInfo> out;
  for (const sim::GridLayerInfo& l : layers) {
    if (std::none_of(other.begin(), other.end(), [&](const sim::GridLayerInfo& o) { return o.name == l.name; }))
      continue;
    sim::GridLayerInfo d = l;
    d.name = differenceLayerName(l.name);
    d.label = l.name + " minus " + otherName.toStdString();
    d.zeroIsEmpty = false;  // cells without a difference are NaN; 0 is "the same here"
    out.push_back(std::move(d));
  }
  return out;
}

}  // namespace talus::gui
