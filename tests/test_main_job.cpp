// snapfit::run_job (jobs/main_job.cpp, jobs/vps_job.cpp): the library's main job on the
// shipped scenes, checked against what the same steps give when run one by one, and its
// errors.
#include <doctest/doctest.h>

#include "snapfit/assembly.h"
#include "snapfit/error.h"
#include "snapfit/fields.h"
#include "snapfit/inspect.h"
#include "snapfit/job.h"
#include "tests/test_support.h"

using namespace snapfit;

namespace {

Scene shipped(const std::string& name) { return load_scene(std::string(SNAPFIT_SOURCE_DIR) + "/scenes/" + name); }

}  // namespace

TEST_CASE("main job: the default scene at a fixed m' on simulated time ends assembled, its steps said in order") {
  const Scene scene = shipped("default.json");
  JobRequest request;
  request.modes = 2048;
  request.simulated_time = true;
  std::string said;
  request.say = [&](const std::string& text) { said += text; };
  const JobResult r = run_job(scene, request);
  std::size_t at = 0;
  for (const char* step : {"[2/7]", "[3/7]", "[4/7]", "[5/7]", "[6/7]", "[7/7]"}) {
    CAPTURE(step);
    const std::size_t next = said.find(step, at);
    CHECK(next != std::string::npos);
    at = next == std::string::npos ? at : next;
  }
  CHECK(r.tuning.chosen_modes == 2048);
  CHECK(r.strategy_chosen_by == "JobRequest::modes (not measured)");
  REQUIRE(r.loop);
  const Trajectory& t = scene.trajectory;
  const double seconds = t.keyframes.back().time_s - t.keyframes.front().time_s + scene.haptics.settle_s;
  CHECK(r.loop->frames == std::size_t(std::llround(seconds * scene.loop_rate_hz)));
  CHECK(r.evaluated);
  CHECK(r.assembled);
  // The result holds, as public data, what the report draws: the session's end, the parts'
  // meshes as part_geometry builds them, their fields as scene_part_fields gives them, and
  // the spectra's grid an Assembly of the same scene builds.
  REQUIRE(r.session);
  CHECK(r.final_position_error == r.session->final_error.position);
  CHECK(r.final_position_error <= r.session->position_tolerance);
  CHECK(session_verdict(*r.session) == "assembled");
  REQUIRE(r.session->rigid_contact);  // the default scene renders the rigid contact
  CHECK(r.session->rigid_contact->part2_points > 0);
  CHECK(r.session->rigid_contact->pressure_stiffness_n_per_mm3 > 0);
  CHECK(r.scene.name == scene.name);
  CHECK_FALSE(r.plan.empty());
  for (int part : {1, 2}) {
    CAPTURE(part);
    const JobPart& p = r.part(part);
    REQUIRE(p.mesh);
    const PartGeometry built = part_geometry(scene, part);
    CHECK(p.mesh->vertices == built.vertices);
    CHECK(p.mesh->triangles == built.triangles);
    CHECK(p.report.triangle_count == built.triangles.size());
    REQUIRE(p.fields);
    PartFieldsRequest fields_request;
    fields_request.part = part;
    const ScenePartFields fields = scene_part_fields(scene, fields_request);
    CHECK(p.fields->fields.grid.dims == fields.grid.dims);
    CHECK(p.fields->fields.grid.spacing == doctest::Approx(r.spacing));
    CHECK(p.fields->fields.winding == fields.result.fields.winding);
    CHECK(p.fields->fields.skeletal_density == fields.result.fields.skeletal_density);
  }
  const Assembly assembly(scene);
  CHECK(r.fft_dims == assembly.fft_dims());
  CHECK(r.device == assembly.device_name());
  CHECK(r.device_check_passed);
}

TEST_CASE("main job: a vps scene runs on the host with the voxmap's facts") {
  Scene scene = shipped("default.json");
  scene.method = Method::vps;
  JobRequest request;
  request.simulated_time = true;
  const JobResult r = run_job(scene, request);
  CHECK(r.device == "host");
  CHECK(r.loop_device == "host");
  REQUIRE(r.vps);
  CHECK(r.vps->shell_points > 0);
  CHECK(r.vps->surface_voxels > 0);
  CHECK_FALSE(r.part1.fields);  // no fields for the VPS peer, but its meshes
  REQUIRE(r.part2.mesh);
  CHECK(r.part2.mesh->triangles == part_geometry(scene, 2).triangles);
  REQUIRE(r.loop);
  CHECK(r.loop->frames > 0);
}

TEST_CASE("main job: an unknown strategy, a bad margin and a missing device are errors that name them") {
  const Scene scene = shipped("default.json");
  JobRequest strategy;
  strategy.strategy = "fastest";
  CHECK(test::error_of([&] { run_job(scene, strategy); }).find("fastest") != std::string::npos);
  JobRequest margin;
  margin.margin = 1.5;
  CHECK(test::error_of([&] { run_job(scene, margin); }).find("margin") != std::string::npos);
  JobRequest device;
  device.device = "no-such-device";
  CHECK(test::error_of([&] { run_job(scene, device); }).find("no-such-device") != std::string::npos);
}
