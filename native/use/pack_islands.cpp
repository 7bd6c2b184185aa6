#include "use/pack_islands.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

namespace polycube {
namespace {

struct Box {
  Eigen::Vector2d min{std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
  Eigen::Vector2d max = -min;
  double width() const { return max.x() - min.x(); }
  double height() const { return max.y() - min.y(); }
};

std::vector<Box> island_boxes(const CornerUvs& uvs, const std::vector<int>& island_of_corner, int island_count) {
  std::vector<Box> boxes(island_count);
  for (Eigen::Index c = 0; c < uvs.rows(); ++c) {
    Box& box = boxes[island_of_corner[c]];
    box.min = box.min.cwiseMin(uvs.row(c).transpose());
    box.max = box.max.cwiseMax(uvs.row(c).transpose());
  }
  for (Box& box : boxes)
    if (!(box.min.x() <= box.max.x())) box.min = box.max = Eigen::Vector2d::Zero();  // an island without corners
  return boxes;
}

// Lower-left corner of each rectangle on shelves of the given width; returns the side of the square it needs.
double shelve(const std::vector<Eigen::Vector2d>& sizes, const std::vector<int>& order, double width,
              std::vector<Eigen::Vector2d>& at) {
  double x = 0.0, y = 0.0, shelf_height = 0.0, used_width = 0.0;
  for (int i : order) {
    if (x > 0.0 && x + sizes[i].x() > width) {
      y += shelf_height;
      x = shelf_height = 0.0;
    }
    at[i] = {x, y};
    x += sizes[i].x();
    used_width = std::max(used_width, x);
    shelf_height = std::max(shelf_height, sizes[i].y());
  }
  return std::max(used_width, y + shelf_height);
}

}  // namespace

void pack_islands(CornerUvs& uvs, const std::vector<int>& island_of_corner, int island_count, double padding) {
  if (island_count == 0) return;
  std::vector<Box> boxes = island_boxes(uvs, island_of_corner, island_count);
  // Upright: turn by +90 degrees, (u, v) -> (-v, u), which keeps the winding.
  std::vector<char> turned(island_count, 0);
  for (int i = 0; i < island_count; ++i) turned[i] = boxes[i].height() > boxes[i].width();
  for (Eigen::Index c = 0; c < uvs.rows(); ++c)
    if (turned[island_of_corner[c]]) uvs.row(c) = Eigen::RowVector2d(-uvs(c, 1), uvs(c, 0));
  boxes = island_boxes(uvs, island_of_corner, island_count);

  double area = 0.0;
  for (const Box& box : boxes) area += box.width() * box.height();
  double widest = 0.0;
  for (const Box& box : boxes) widest = std::max(widest, box.width());
  const double gap = padding * std::sqrt(std::max(area, widest * widest * 1e-6));
  std::vector<Eigen::Vector2d> sizes(island_count);
  for (int i = 0; i < island_count; ++i) sizes[i] = {boxes[i].width() + gap, boxes[i].height() + gap};
  std::vector<int> order(island_count);
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return sizes[a].y() > sizes[b].y(); });

  double padded_area = 0.0;
  for (const Eigen::Vector2d& s : sizes) padded_area += s.x() * s.y();
  std::vector<Eigen::Vector2d> at(island_count), best_at;
  double best_side = std::numeric_limits<double>::infinity();
  for (int k = 0; k <= 20; ++k) {
    const double width = std::max(widest + gap, std::sqrt(padded_area) * (1.0 + 0.05 * k));
    const double side = shelve(sizes, order, width, at);
    if (side < best_side) {
      best_side = side;
      best_at = at;
    }
  }
  const double scale = best_side > 0.0 ? 1.0 / best_side : 1.0;
  for (Eigen::Index c = 0; c < uvs.rows(); ++c) {
    const int i = island_of_corner[c];
    const Eigen::Vector2d moved = uvs.row(c).transpose() - boxes[i].min + best_at[i] +
                                  Eigen::Vector2d::Constant(0.5 * gap);
    uvs.row(c) = scale * moved.transpose();
  }
}

}  // namespace polycube
