#include "deform/recut_collapsed_faces.h"

#include "labels/recut_region.h"

namespace polycube {

std::vector<int> recut_collapsed_faces(const std::vector<std::vector<int>>& neighbours, const LabelEnergy& energy,
                                       const std::vector<char>& collapsed, std::vector<int>& labels, int rings) {
  const int face_count = static_cast<int>(labels.size());
  std::vector<char> inside(collapsed.begin(), collapsed.end());
  for (int ring = 0; ring < rings; ++ring) {
    std::vector<char> grown = inside;
    for (int f = 0; f < face_count; ++f)
      if (inside[f])
        for (int g : neighbours[f]) grown[g] = 1;
    inside = std::move(grown);
  }
  std::vector<int> region;
  for (int f = 0; f < face_count; ++f)
    if (inside[f]) region.push_back(f);
  if (region.empty()) return {};
  const std::vector<int> cut = recut_region(energy, labels, region);
  std::vector<int> changed;
  for (int f : region)
    if (cut[f] != labels[f]) changed.push_back(f);
  labels = cut;
  return changed;
}

}  // namespace polycube
