#include "mesh/contact_blocks.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>

#include "snapfit/error.h"

namespace snapfit {

namespace {

// The sphere about the mean of points[order[b, e)].
ShellChunk sphere(const ContactSamples& s, const std::vector<std::size_t>& order, std::size_t b, std::size_t e) {
  ShellChunk c;
  for (std::size_t i = b; i < e; ++i) c.centre += s.points[order[i]];
  c.centre /= double(e - b);
  for (std::size_t i = b; i < e; ++i) c.radius = std::max(c.radius, (s.points[order[i]] - c.centre).norm());
  return c;
}

}  // namespace

ContactBlocks build_contact_blocks(const ContactSamples& s, double block_size, double group_size) {
  if (!(std::isfinite(block_size) && block_size > 0 && std::isfinite(group_size) && group_size > 0))
    throw Error("contact blocks: the block and group sizes must be > 0");
  ContactBlocks out;
  if (s.points.empty()) return out;
  Eigen::Vector3d lo = s.points[0];
  for (const Eigen::Vector3d& p : s.points) lo = lo.cwiseMin(p);
  // Each point's group cube, then block cube.
  std::vector<std::array<long, 6>> key(s.points.size());
  for (std::size_t i = 0; i < s.points.size(); ++i)
    for (int a = 0; a < 3; ++a) {
      key[i][a] = static_cast<long>(std::floor((s.points[i][a] - lo[a]) / group_size));
      key[i][3 + a] = static_cast<long>(std::floor((s.points[i][a] - lo[a]) / block_size));
    }
  std::vector<std::size_t> order(s.points.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return key[a] < key[b]; });
  const auto same_group = [&](std::size_t a, std::size_t b) {
    return std::equal(key[order[a]].begin(), key[order[a]].begin() + 3, key[order[b]].begin());
  };
  out.x.reserve(order.size()), out.y.reserve(order.size()), out.z.reserve(order.size()), out.area.reserve(order.size());
  for (std::size_t group_begin = 0; group_begin < order.size();) {
    std::size_t group_end = group_begin;
    while (group_end < order.size() && same_group(group_end, group_begin)) ++group_end;
    ShellChunk group = sphere(s, order, group_begin, group_end);
    group.begin = out.blocks.size();
    for (std::size_t begin = group_begin; begin < group_end;) {
      std::size_t cube_end = begin;
      while (cube_end < group_end && key[order[cube_end]] == key[order[begin]]) ++cube_end;
      // A crowded cube (many sharp edges meeting) is cut into runs of at most kMaxBlockPoints.
      const std::size_t runs = (cube_end - begin + kMaxBlockPoints - 1) / kMaxBlockPoints;
      for (std::size_t run = 0; run < runs; ++run) {
        const std::size_t b = begin + (cube_end - begin) * run / runs,
                          e = begin + (cube_end - begin) * (run + 1) / runs;
        ShellChunk block = sphere(s, order, b, e);
        block.begin = out.x.size(), block.end = block.begin + (e - b);
        for (std::size_t i = b; i < e; ++i) {
          const Eigen::Vector3d d = s.points[order[i]] - block.centre;
          out.x.push_back(float(d.x())), out.y.push_back(float(d.y())), out.z.push_back(float(d.z()));
          out.area.push_back(float(s.areas[order[i]]));
        }
        out.blocks.push_back(block);
      }
      begin = cube_end;
    }
    group.end = out.blocks.size();
    out.groups.push_back(group);
    group_begin = group_end;
  }
  return out;
}

}  // namespace snapfit
