// The smallest haptics-side use of snapfit: load a scene, build its assembly (cached),
// and ask for energy, force and torque of part 2 at a pose.
//
//   snapfit_consumer SCENE [MODES [x y z]]
//
// Prints one JSON line. The pose: part 2 unrotated at (x, y, z) in part 1's frame, else
// its initial pose in the scene.
#include <cstdio>
#include <cstdlib>
#include <snapfit/snapfit.h>
#include <string>

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: %s SCENE [MODES [x y z]]\n", argv[0]);
    return 2;
  }
  try {
    const snapfit::Scene scene = snapfit::load_scene(argv[1]);
    snapfit::Pose pose = scene.part2.pose;
    if (argc >= 6) {  // part 2 unrotated at (x, y, z) in part 1's frame
      pose = snapfit::Pose{};
      pose.translation = Eigen::Vector3d(std::atof(argv[3]), std::atof(argv[4]), std::atof(argv[5]));
    }
    const std::size_t modes = argc >= 3 ? std::strtoul(argv[2], nullptr, 10) : 4096;

    snapfit::Assembly assembly(scene);
    std::unique_ptr<snapfit::QueryEngine> engine = assembly.make_query_engine();
    engine->set_modes(modes);
    const snapfit::QueryResult r = engine->query(pose);
    std::printf(
        "{\"device\": \"%s\", \"modes\": %zu, \"energy\": %.17g, \"force\": [%.17g, %.17g, %.17g], "
        "\"torque\": [%.17g, %.17g, %.17g], \"flags\": %u}\n",
        assembly.device_name().c_str(), r.modes, r.energy, r.force.x(), r.force.y(), r.force.z(), r.torque.x(),
        r.torque.y(), r.torque.z(), r.flags);
    return r.flags == snapfit::query_ok ? 0 : 1;
  } catch (const snapfit::Error& e) {
    std::fprintf(stderr, "snapfit_consumer: %s\n", e.what());
    return 1;
  }
}
