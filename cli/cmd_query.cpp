// `snapfit query SCENE --pose ...`: energy, force and torque of part 2 at given poses,
// one JSON object per line, so results can be checked from outside the program.
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "cli/commands.h"
#include "cli/parse_options.h"
#include "snapfit/assembly.h"
#include "snapfit/collision.h"
#include "snapfit/error.h"
#include "snapfit/pose_json.h"

namespace snapfit::cli {
namespace {

struct QueryOptions {
  std::string scene;
  std::vector<std::string> poses;
  std::string poses_file;
  std::size_t modes = 32768;
  std::string interpolation = "tricubic";
  std::string device;
  bool collision = false;
};

// "x,y,z" or "x,y,z,ax,ay,az,angle_deg" (axis-angle, degrees): part 2 in part 1's frame.
Pose parse_pose(const std::string& text, const std::string& where) {
  std::vector<double> v;
  std::stringstream in(text);
  std::string item;
  while (std::getline(in, item, ',')) {
    try {
      std::size_t used = 0;
      v.push_back(std::stod(item, &used));
      if (item.find_first_not_of(" \t", used) != std::string::npos) throw std::invalid_argument(item);
    } catch (const std::exception&) {
      throw Error(where + ": '" + item + "' is not a number (pose format: x,y,z or x,y,z,ax,ay,az,angle_deg)");
    }
  }
  if (v.size() != 3 && v.size() != 7)
    throw Error(where + ": expected 3 or 7 numbers (x,y,z or x,y,z,ax,ay,az,angle_deg), got " +
                std::to_string(v.size()));
  for (double x : v)
    if (!std::isfinite(x)) throw Error(where + ": pose has a non-finite number");
  Pose pose;
  pose.translation = Eigen::Vector3d(v[0], v[1], v[2]);
  if (v.size() == 7) {
    const Eigen::Vector3d axis(v[3], v[4], v[5]);
    if (axis.norm() == 0) throw Error(where + ": rotation axis is zero");
    pose.rotation = Eigen::Quaterniond(Eigen::AngleAxisd(v[6] * M_PI / 180.0, axis.normalized()));
  }
  return pose;
}

// One pose's JSON line (the fields are listed in docs/design.md, "snapfit query").
nlohmann::json result_json(const Pose& pose, const QueryResult& r, std::size_t batch_poses,
                           const TruncationTails* tails) {
  nlohmann::json flags = nlohmann::json::array();
  if (r.flags & query_outside_grid) flags.push_back("outside_grid");
  if (r.flags & query_bad_pose) flags.push_back("bad_pose");
  nlohmann::json j = pose_json<nlohmann::json>(pose);
  j.update(
      {{"energy", r.energy},
       {"force", {r.force.x(), r.force.y(), r.force.z()}},
       {"torque", {r.torque.x(), r.torque.y(), r.torque.z()}},
       {"score", {r.score.real(), r.score.imag()}},
       {"error_estimate",
        {{"energy", r.error_estimate.energy}, {"force", r.error_estimate.force}, {"torque", r.error_estimate.torque}}},
       {"flags", flags},
       {"modes", r.modes},
       {"batch_mean_ms", r.seconds * 1e3},
       {"batch_poses", batch_poses}});
  if (tails) {
    // The predicate is one-sided: an overlap above its truncation bound proves a
    // collision; below it the truncated sum cannot tell a touch from a small overlap.
    const CollisionVerdict v = collision_verdict(r, *tails);
    j["collides"] = v.collides ? nlohmann::json(true) : nlohmann::json("unknown");
    j["overlap"] = v.overlap;
    j["truncation_bound"] = v.bound;
    j["collision_rule"] = "true when overlap > truncation_bound (proven); otherwise unknown, not free";
  }
  return j;
}

void run_query(const QueryOptions& opt) {
  const Scene scene = opt.collision ? indicator_scene(load_scene(opt.scene)) : load_scene(opt.scene);
  std::vector<Pose> poses;
  for (std::size_t i = 0; i < opt.poses.size(); ++i)
    poses.push_back(parse_pose(opt.poses[i], "--pose " + opt.poses[i]));
  if (!opt.poses_file.empty()) {
    std::ifstream in(opt.poses_file);
    if (!in) throw Error(opt.poses_file + ": cannot read the poses file");
    std::string line;
    for (int n = 1; std::getline(in, line); ++n) {
      if (line.find_first_not_of(" \t\r") == std::string::npos || line[line.find_first_not_of(" \t")] == '#') continue;
      poses.push_back(parse_pose(line, opt.poses_file + ":" + std::to_string(n)));
    }
  }
  if (poses.empty()) poses.push_back(scene.part2.pose);  // the scene's initial pose
  const Interpolation interpolation = parse_interpolation(opt.interpolation);

  AssemblyOptions options;
  options.device = opt.device;
  options.progress = true;
  const Assembly assembly(scene, options);
  auto engine = assembly.make_query_engine(assembly.query_variant(interpolation));
  engine->set_modes(opt.modes);
  const std::vector<QueryResult> results = engine->query_batch(poses);
  const TruncationTails tails = opt.collision ? truncation_tails(assembly) : TruncationTails{};
  for (std::size_t i = 0; i < poses.size(); ++i)
    std::cout << result_json(poses[i], results[i], poses.size(), opt.collision ? &tails : nullptr).dump() << "\n";
}

}  // namespace

void add_query_command(CLI::App& app) {
  auto opt = std::make_shared<QueryOptions>();
  CLI::App* cmd = app.add_subcommand("query", "Energy, force and torque of part 2 at poses (one JSON line per pose)");
  cmd->add_option("scene", opt->scene, "Scene file (JSON)")->required();
  cmd->add_option(
      "--pose", opt->poses,
      "Part 2 in part 1's frame: x,y,z or x,y,z,ax,ay,az,angle_deg (repeatable; default: the scene's initial pose)");
  cmd->add_option("--poses", opt->poses_file, "File with one pose per line (same format; # comments)");
  cmd->add_option("--modes", opt->modes, "m': number of retained Fourier modes (lowest |w| first)");
  cmd->add_option("--interpolation", opt->interpolation, "trilinear (seed 000) or tricubic (Catmull-Rom)");
  cmd->add_option("--device", opt->device, "OpenCL device (see `snapfit devices`)");
  cmd->add_flag("--collision", opt->collision,
                "Collision verdict (seed 001): the indicator descriptor, and `collides`: true when the overlap volume "
                "summed over m' modes exceeds its truncation bound (proven), else \"unknown\" (docs/spheres.md)");
  cmd->callback([opt] { run_query(*opt); });
}

}  // namespace snapfit::cli
