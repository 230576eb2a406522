// The main job for a scene whose method is "vps" or "vps_hybrid" (Faas 2010): part 1's
// voxmap and part 2's point shell on the host, the hybrid's analytic faces where both
// parts have them, then the same scripted loop (no device, fields, spectra or tuning).
#include <algorithm>
#include <chrono>
#include <sstream>

#include "core/progress.h"
#include "jobs/job_steps.h"
#include "scheduler/haptics/haptic_setup.h"
#include "scheduler/vps/vps_hybrid.h"
#include "scheduler/vps/vps_method.h"

namespace snapfit {
namespace {

VpsFacts model_facts(const VpsModel& model) {
  VpsFacts facts;
  facts.voxel_size = model.voxmap.voxel_size;
  facts.shell_spacing = model.shell.spacing;
  facts.surface_voxels = model.voxmap.count(VoxelState::surface);
  facts.interior_voxels = model.voxmap.count(VoxelState::interior);
  facts.proximity_voxels = model.voxmap.count(VoxelState::proximity);
  facts.shell_points = model.shell.points.size();
  facts.stiffness_n_per_m = model.stiffness;
  facts.braking_n_s_per_m = model.braking;
  return facts;
}

// Why a part has no analytic faces for the hybrid ("" when both have some).
std::string plain_reason(const AssemblyPair& pair) {
  const Scene& scene = pair.scene;
  std::string reason;
  for (int part = 1; part <= 2; ++part) {
    const PartSpec& spec = part == 1 ? scene.part1 : scene.part2;
    if (!pair.part(part).faces.empty()) continue;
    reason += std::string(reason.empty() ? "" : "; ") + "part '" + spec.name + "' " +
              (spec.procedural      ? "(procedural " + spec.procedural->type + ")"
               : pair.part(part).cad ? std::string("(a CAD file with no plane, cylinder or cone)")
                                     : std::string("(a mesh file)")) +
              " has no analytic faces";
  }
  return reason;
}

// The hybrid's model on top of the voxmap, with its facts in `facts`.
HybridModel hybrid_for(const AssemblyPair& pair, const VpsModel& model, const CouplingParams& coupling,
                       VpsFacts& facts) {
  std::vector<AnalyticFace> f1 = pair.part(1).faces, f2 = pair.part(2).faces;
  facts.faces1 = f1.size();
  facts.faces2 = f2.size();
  HybridModel hybrid = hybrid_model(model, std::move(f1), std::move(f2), coupling, hybrid_params_for(pair.scene));
  facts.hybrid = true;
  const auto on_a_face = [](std::int16_t f) { return f >= 0; };
  facts.labelled_voxels = std::count_if(hybrid.voxel_face.begin(), hybrid.voxel_face.end(), on_a_face);
  facts.labelled_points = std::count_if(hybrid.point_face.begin(), hybrid.point_face.end(), on_a_face);
  facts.alignment_k_n_per_m = hybrid.k_a_n_per_m;
  return hybrid;
}

}  // namespace

JobResult run_vps_job(std::shared_ptr<AssemblyPair> pair, const JobRequest& request, const JobOutput& out) {
  const Scene& scene = pair->scene;
  out.say("[3/7] Voxmap PointShell: voxelising part 1, point shell of part 2 (no OpenCL device)\n");
  const auto built = std::chrono::steady_clock::now();
  const CouplingParams coupling = coupling_for(scene, pair->part(2).mesh);
  const VpsModel model = vps_model_for(scene, pair->part(1).mesh, pair->part(2).mesh, pair->grids.spacing, coupling);
  auto record = std::make_shared<JobRecord>();
  record->pair = pair;
  VpsFacts& facts = record->vps.emplace(model_facts(model));
  facts.build_seconds = seconds_since(built);
  record->device.name = record->loop_device.name = "host";
  std::ostringstream line;
  line << "    voxel " << facts.voxel_size << " " << scene.units << ": " << facts.surface_voxels << " surface, "
       << facts.interior_voxels << " interior, " << facts.proximity_voxels << " proximity voxels; "
       << facts.shell_points << " shell points at " << facts.shell_spacing << " " << scene.units << " (built in "
       << facts.build_seconds << " s)\n";
  out.say(line.str());
  // The hybrid needs both parts' analytic faces; a part without them runs as plain VPS.
  std::optional<HybridModel> hybrid;
  std::optional<HybridState> hybrid_state;
  if (scene.method == Method::vps_hybrid) {
    facts.plain_reason = plain_reason(*pair);
    if (!facts.plain_reason.empty()) {
      out.say("    vps_hybrid: " + facts.plain_reason + ": running as plain Voxmap PointShell\n");
    } else {
      hybrid = hybrid_for(*pair, model, coupling, facts);
      hybrid_state = hybrid_state_for(*hybrid);
      std::ostringstream h;
      h << "    vps_hybrid: " << facts.faces1 << " + " << facts.faces2 << " analytic faces; " << facts.labelled_voxels
        << " surface voxels and " << facts.labelled_points << " shell points on one face; alignment k_A "
        << facts.alignment_k_n_per_m << " N/m\n";
      out.say(h.str());
    }
  }
  run_session_step(scene, request, out, hybrid ? "VPS - constraint hybrid" : "Voxmap PointShell", *record,
                   [&](const SessionOptions& session) {
                     return run_scripted_session(
                         scene, pair->part(2).mesh, pair->grids.spacing, vps_loop_config(scene, model, coupling),
                         hybrid ? hybrid_evaluator(*hybrid, *hybrid_state) : vps_evaluator(model), session);
                   });
  return job_result(std::move(*record));
}

}  // namespace snapfit
