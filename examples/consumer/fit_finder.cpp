// Where part 2 fits part 1, from the library: the rotation search (snapfit/search.h)
// over about ROTATIONS rotations, in this one process.
//
//   snapfit_fit_finder SCENE [ROTATIONS]
//
// Prints the best pose as one JSON line: the map's energy and pose, and where the
// refinement ended.
#include <cstdio>
#include <cstdlib>
#include <snapfit/snapfit.h>

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: %s SCENE [ROTATIONS]\n", argv[0]);
    return 2;
  }
  try {
    snapfit::SearchRequest request;
    request.rotations = argc >= 3 ? std::strtoul(argv[2], nullptr, 10) : 64;
    request.top = 1;
    request.map_fft = "clfft";
    const snapfit::SearchResult result = snapfit::search(snapfit::load_scene(argv[1]), request);
    if (result.top.empty()) {
      std::fprintf(stderr, "snapfit_fit_finder: no pose found\n");
      return 1;
    }
    const snapfit::FoundPose& best = result.top[0];
    const Eigen::AngleAxisd turn(best.pose.rotation);
    const Eigen::Vector3d& t = best.pose.translation;
    const Eigen::Vector3d& rest = best.refined.pose.translation;
    std::printf(
        "{\"rotations\": %zu, \"energy\": %.17g, \"position\": [%.17g, %.17g, %.17g], \"rotation_deg\": %.17g, "
        "\"refined_position\": [%.17g, %.17g, %.17g]}\n",
        result.rotations.size(), best.energy, t.x(), t.y(), t.z(), turn.angle() * 180 / M_PI, rest.x(), rest.y(),
        rest.z());
    return 0;
  } catch (const snapfit::Error& e) {
    std::fprintf(stderr, "snapfit_fit_finder: %s\n", e.what());
    return 1;
  }
}
