#pragma once
// A group of consecutive surface points (a point shell's, a part's contact samples')
// within `radius` of `centre` (the part's frame), so that a query can skip the whole
// group when its centre lies far from the other part.
#include <Eigen/Core>
#include <cstddef>

namespace snapfit {

struct ShellChunk {
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  double radius = 0;
  std::size_t begin = 0, end = 0;  // points[begin, end)
};

}  // namespace snapfit
