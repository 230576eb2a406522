// One pipeline (pipeline/assembly_pair.h): for every shipped scene, `snapfit run` (its
// loop log), `snapfit query` (its JSON lines) and the library give the same energy,
// force and torque at the same pose and m'; report.html carries the same frames as loop.csv. The CLI runs as a user
// runs it, with the test's cache folder, so it reuses the fields and spectra the library computed.
#include <doctest/doctest.h>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <nlohmann/json.hpp>
#include <sstream>

#include "engine/query/query_engine.h"
#include "pipeline/assembly_pair.h"
#include "report/loop_display.h"
#include "report/run_page.h"
#include "report/web_assets.h"
#include "tests/test_engine_support.h"

namespace snapfit {
namespace {

namespace fs = std::filesystem;
constexpr std::size_t kModes = 4096;

std::vector<std::vector<double>> read_csv(const fs::path& file, std::vector<std::string>& header) {
  std::ifstream in(file);
  std::string line;
  std::vector<std::vector<double>> rows;
  for (bool first = true; std::getline(in, line); first = false) {
    std::stringstream cells(line);
    std::string cell;
    std::vector<double> row;
    while (std::getline(cells, cell, ',')) {
      if (first)
        header.push_back(cell);
      else
        row.push_back(std::stod(cell));
    }
    if (!first) rows.push_back(row);
  }
  return rows;
}

std::string number(double v) {
  std::ostringstream out;
  out << std::setprecision(17) << v;
  return out.str();
}

// A pose as `snapfit query --pose` reads it (x,y,z,ax,ay,az,deg), and the pose it makes.
std::string pose_argument(const Pose& p, Pose& parsed) {
  const Eigen::AngleAxisd aa(p.rotation.normalized());
  const double deg = aa.angle() * 180.0 / M_PI;
  parsed.translation = p.translation;
  parsed.rotation = Eigen::Quaterniond(Eigen::AngleAxisd(deg * M_PI / 180.0, aa.axis().normalized()));
  return number(p.translation.x()) + "," + number(p.translation.y()) + "," + number(p.translation.z()) + "," +
         number(aa.axis().x()) + "," + number(aa.axis().y()) + "," + number(aa.axis().z()) + "," + number(deg);
}

Eigen::Vector3d vec3(const nlohmann::json& j) { return {j[0].get<double>(), j[1].get<double>(), j[2].get<double>()}; }

// A float32 of the page against loop.csv's value (9 significant digits): equal to float
// rounding.
bool same_float(float page, double csv) { return std::abs(page - csv) <= 1e-6 * std::abs(csv) + 1e-30; }

// report.html's data block: the summary as summary.json has it, and the playback and
// time series at the frames loop.csv has (float32 in the page).
void check_report_page(const fs::path& run_dir, const nlohmann::json& summary,
                       const std::vector<std::vector<double>>& rows, const std::vector<std::string>& header) {
  if (!web_pages_available()) {
    CHECK(summary["report_html"].is_null());
    return;
  }
  CHECK(summary["report_html"] == "report.html");
  std::ifstream in(run_dir / "report.html");
  const std::string html((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string open = "<script id=\"snapfit-data\" type=\"application/json\">";
  const std::size_t at = html.find(open);
  REQUIRE(at != std::string::npos);
  const std::size_t end = html.find("</script>", at);
  const nlohmann::json data = nlohmann::json::parse(html.substr(at + open.size(), end - at - open.size()));
  CHECK(data["summary"]["scene"] == summary["scene"]);
  CHECK(data["summary"]["modes"] == kModes);
  CHECK(data["parts"].size() == 2);
  if (rows.empty()) {
    CHECK(data["playback"].is_null());
    return;
  }
  CHECK(data["summary"]["misses"] == summary["haptic_loop"]["misses"]);
  CHECK(data["summary"]["assembled"] == summary["haptic_loop"]["assembled"]);
  const nlohmann::json& pb = data["playback"];
  REQUIRE(pb["frames_total"] == rows.size());
  auto col = [&](const std::string& name) {
    return static_cast<std::size_t>(std::find(header.begin(), header.end(), name) - header.begin());
  };
  const std::vector<std::size_t> frames = evenly_spaced_frames(rows.size(), RunPageLimits{}.playback_frames);
  const std::vector<float> time = test::decode_float32_base64(pb["time"].get<std::string>());
  const std::vector<float> position = test::decode_float32_base64(pb["position"].get<std::string>());
  const std::vector<float> force = test::decode_float32_base64(pb["force"].get<std::string>());
  REQUIRE(time.size() == frames.size());
  REQUIRE(position.size() == 3 * frames.size());
  for (std::size_t k = 0; k < frames.size(); k += 97) {
    const auto& r = rows[frames[k]];
    CHECK(same_float(time[k], r[col("time_s")]));
    CHECK(same_float(position[3 * k + 2], r[col("part_z")]));
    CHECK(same_float(force[3 * k], r[col("sent_fx")]));
  }
  // The energy chart: an envelope whose extremes are those of the CSV's energy column.
  const nlohmann::json& energy_chart = data["timeline"]["charts"][0];
  const std::vector<float> e = test::decode_float32_base64(energy_chart["series"][0]["y"].get<std::string>());
  double lo = rows[0][col("energy")], hi = lo;
  for (const auto& r : rows) lo = std::min(lo, r[col("energy")]), hi = std::max(hi, r[col("energy")]);
  CHECK(same_float(*std::min_element(e.begin(), e.end()), lo));
  CHECK(same_float(*std::max_element(e.begin(), e.end()), hi));
}

}  // namespace

TEST_CASE("pipeline: snapfit run, snapfit query and the library give the same wrench on every shipped scene") {
  const test::CacheDirScope cache;
  const test::TempDir out;
  std::vector<fs::path> scenes;
  for (const auto& entry : fs::directory_iterator(fs::path(SNAPFIT_SOURCE_DIR) / "scenes"))
    if (entry.path().extension() == ".json") scenes.push_back(entry.path());
  std::sort(scenes.begin(), scenes.end());
  REQUIRE(scenes.size() >= 5);
  bool translation_scene = false;
  for (const fs::path& file : scenes) {
    CAPTURE(file.string());
    const Scene scene = load_scene(file.string());
    translation_scene |= scene.motion == Motion::translation;
    const FftLibrary fft;
    PairOptions options;
    options.note = [](const std::string&) {};
    const AssemblyPair pair = build_assembly_pair(scene, test::test_context(), fft, options);
    auto engine = make_query_engine(test::test_context(), pair.spectra,
                                    query_variant_for(scene, Interpolation::tricubic), test::test_program_cache());
    engine->set_modes(kModes);

    // snapfit run: the loop's log holds the pose each frame's wrench was computed at.
    const fs::path run_dir = out.path / file.stem();
    const test::Command run = test::run_command(std::string(SNAPFIT_CLI_PATH) + " run " + file.string() + " --modes " +
                                                std::to_string(kModes) + " --simulated-time --out " + run_dir.string());
    INFO(run.output);
    REQUIRE(run.status == 0);
    std::ifstream summary_file(run_dir / "summary.json");
    const nlohmann::json summary = nlohmann::json::parse(summary_file);
    CHECK(summary["fft_dims"] == nlohmann::json(pair.spectra.dims));
    std::vector<Pose> poses;
    if (scene.trajectory.keyframes.empty()) check_report_page(run_dir, summary, {}, {});
    if (!scene.trajectory.keyframes.empty()) {
      std::vector<std::string> h;
      const auto rows = read_csv(run_dir / "loop.csv", h);
      check_report_page(run_dir, summary, rows, h);
      auto col = [&](const std::string& name) {
        const auto it = std::find(h.begin(), h.end(), name);
        REQUIRE(it != h.end());
        return static_cast<std::size_t>(it - h.begin());
      };
      REQUIRE(rows.size() > 100);
      const double gain = summary["haptic_loop"]["geometry_gain"].get<double>();
      const double torque_gain = gain * metres_per_unit(scene.units);
      // The kernels sum in float: a pose read back from the log's 9 digits rounds their
      // terms differently, by float epsilons of the wrench's size along the run, which
      // is far more than a torque that cancels to nearly zero (an inserted peg's).
      double torque_scale = 0, energy_scale = 0;
      for (const auto& r : rows) {
        torque_scale =
            std::max(torque_scale, Eigen::Vector3d(r[col("geo_tx")], r[col("geo_ty")], r[col("geo_tz")]).norm());
        energy_scale = std::max(energy_scale, std::abs(r[col("energy")]));
      }
      for (std::size_t i = 0; i < rows.size(); i += rows.size() / 7) {
        const auto& r = rows[i];
        REQUIRE(r[col("modes")] == double(kModes));
        Pose p;
        p.translation = {r[col("part_x")], r[col("part_y")], r[col("part_z")]};
        p.rotation = Eigen::Quaterniond(r[col("part_qw")], r[col("part_qx")], r[col("part_qy")], r[col("part_qz")]);
        poses.push_back(p);
        const QueryResult q = engine->query(p);
        CAPTURE(i);
        REQUIRE(q.flags == unsigned(r[col("flags")]));
        const double e = r[col("energy")];
        // Devices split the modes into different work-groups: float round-off of the
        // energy's size along the run, not of an energy that cancels at one pose.
        CHECK(std::abs(q.energy - e) <= 1e-6 * std::max({1.0, std::abs(e), energy_scale}));
        const Eigen::Vector3d f(r[col("geo_fx")], r[col("geo_fy")], r[col("geo_fz")]);
        const Eigen::Vector3d t(r[col("geo_tx")], r[col("geo_ty")], r[col("geo_tz")]);
        // The log's geometric wrench is the engine's times the share its estimate vouched for.
        const double trust = r[col("trust")];
        CHECK(trust >= 0);
        CHECK(trust <= 1);
        CHECK((trust * gain * q.force - f).norm() <= 1e-6 * std::max(1e-9, f.norm()) + 1e-12);
        // The kernels sum the torque about part 2's box centre c2 and add (R c2) x F, in
        // float: on another device's order it agrees to round-off of |c2| |F| and of the
        // torque's size along the run, not of a torque that cancels at one pose.
        const double lever = pair.spectra.part2.centre.norm() * metres_per_unit(scene.units);
        CHECK((trust * torque_gain * q.torque - t).norm() <=
              1e-6 * (std::max({1e-12, t.norm(), torque_scale}) + lever * f.norm()) + 1e-15);
      }
    }
    if (poses.empty()) poses.push_back(scene.part2.pose);

    // snapfit query at the same poses.
    std::string arguments;
    std::vector<Pose> parsed(poses.size());
    for (std::size_t i = 0; i < poses.size(); ++i) arguments += " --pose " + pose_argument(poses[i], parsed[i]);
    const test::Command query = test::run_command(
        std::string(SNAPFIT_CLI_PATH) + " query " + file.string() + " --modes " + std::to_string(kModes) + arguments,
        false);
    INFO(query.output);
    REQUIRE(query.status == 0);
    std::stringstream lines(query.output);
    std::string line;
    std::size_t n = 0;
    for (; std::getline(lines, line) && n < parsed.size(); ++n) {
      const nlohmann::json j = nlohmann::json::parse(line);
      const QueryResult q = engine->query(parsed[n]);
      CAPTURE(n);
      CHECK(j["modes"].get<std::size_t>() == kModes);
      CHECK(j["energy"].get<double>() == doctest::Approx(q.energy).epsilon(1e-9).scale(1.0));
      CHECK((vec3(j["force"]) - q.force).norm() <= 1e-9 * std::max(1.0, q.force.norm()));
      CHECK((vec3(j["torque"]) - q.torque).norm() <= 1e-9 * std::max(1.0, q.torque.norm()));
    }
    CHECK(n == parsed.size());
  }
  CHECK(translation_scene);
}


TEST_CASE("pipeline: snapfit run says how the run ended: signed axial and lateral errors, the force, or no verdict") {
  const test::CacheDirScope cache;
  const test::TempDir out;
  const std::string scene_file = std::string(SNAPFIT_SOURCE_DIR) + "/scenes/default.json";
  const std::string run = std::string(SNAPFIT_CLI_PATH) + " run ";
  const test::Command judged =
      test::run_command(run + scene_file + " --modes 2048 --simulated-time --out " + (out.path / "judged").string());
  INFO(judged.output);
  REQUIRE(judged.status == 0);
  nlohmann::json s;
  std::ifstream(out.path / "judged" / "summary.json") >> s;
  const nlohmann::json& loop = s["haptic_loop"];
  // The default trajectory ends straight down (-z) into the fit at z = -20: axial is the
  // depth past the fit, the rest is lateral.
  const auto& p = loop["final_pose"]["position"];
  const double x = p[0], y = p[1], z = p[2];
  CHECK(loop["final_error"]["axial"].get<double>() == doctest::Approx(-(z + 20)).epsilon(1e-9));
  CHECK(loop["final_error"]["lateral"].get<double>() == doctest::Approx(std::hypot(x, y)).epsilon(1e-9));
  CHECK(loop["final_error"]["insertion_direction"] == nlohmann::json({0.0, 0.0, -1.0}));
  CHECK(loop["final_force_n"].size() == 3);
  CHECK(loop["verdict"] == (loop["assembled"].get<bool>() ? "assembled" : "not assembled"));
  CHECK(judged.output.find("axial ") != std::string::npos);

  // Without an assembled pose the run is not judged.
  nlohmann::json scene;
  std::ifstream(scene_file) >> scene;
  scene.erase("assembled_pose");
  for (auto& part : {"part1", "part2"})
    if (scene[part].contains("mesh"))
      scene[part]["mesh"] = (fs::path(SNAPFIT_SOURCE_DIR) / "scenes" / scene[part]["mesh"].get<std::string>()).string();
  std::ofstream(out.path / "unjudged.json") << scene.dump();
  const test::Command unjudged = test::run_command(run + (out.path / "unjudged.json").string() +
                                                   " --modes 2048 --simulated-time --out " +
                                                   (out.path / "unjudged").string());
  INFO(unjudged.output);
  REQUIRE(unjudged.status == 0);
  nlohmann::json u;
  std::ifstream(out.path / "unjudged" / "summary.json") >> u;
  CHECK(u["haptic_loop"]["assembled"].is_null());
  CHECK(u["haptic_loop"]["verdict"] == "not evaluated (no assembled pose)");
  CHECK(unjudged.output.find("not evaluated (the scene has no assembled pose)") != std::string::npos);
  CHECK(unjudged.output.find("NOT assembled") == std::string::npos);
}

}  // namespace snapfit
