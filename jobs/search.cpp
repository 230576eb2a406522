// snapfit/search.h: the rotation search. Process 0 builds both parts' fields and spectra
// (cached) and sends the spectra; every process maps its share of the SO(3) grid
// (rotation r on process r mod size) on its own device; process 0 gathers the minima,
// merges them and refines the best with the per-frame query engine.
#include "snapfit/search.h"

#include <chrono>
#include <cmath>
#include <memory>

#include "core/progress.h"
#include "core/so3_grid.h"
#include "engine/maps/map_fft_choice.h"
#include "engine/maps/rotation_search.h"
#include "engine/query/pose_descent.h"
#include "engine/query/query_engine.h"
#include "jobs/search_codec.h"
#include "pipeline/assembly_pair.h"
#include "scheduler/haptics/haptic_setup.h"
#include "scheduler/haptics/rendered_wrench.h"
#include "scheduler/haptics/rigid_contact.h"
#include "scheduler/modes/mode_tuning.h"
#include "snapfit/error.h"

namespace snapfit {
namespace {

constexpr double kDeg = M_PI / 180.0;

// One process: nothing to exchange.
class OneProcess final : public SearchExchange {
 public:
  int rank() const override { return 0; }
  int size() const override { return 1; }
  int local_rank() const override { return 0; }
  void checkpoint(const std::string& error) override {
    if (!error.empty()) throw Error(error);
  }
  std::vector<double> gather(const std::vector<double>& mine) override { return mine; }
  void broadcast(std::vector<double>&) override {}
};

// Runs `work` on every process and agrees on failures: a failure anywhere ends all.
template <typename Work>
void on_every_process(SearchExchange& exchange, Work&& work) {
  std::string error;
  try {
    work();
  } catch (const std::exception& e) {
    error = e.what();
    if (error.empty()) error = "an unnamed failure";
  }
  exchange.checkpoint(error);
}

std::string device_for(const SearchRequest& request, int local_rank) {
  if (request.devices.empty()) return device_spec_from("");
  return device_spec_from(request.devices[std::size_t(local_rank) % request.devices.size()]);
}

void check_request(const SearchRequest& request) {
  if (request.step_deg && request.rotations) throw Error("search: step_deg and rotations: give one of them");
  if (request.top == 0 || request.per_rotation == 0 || request.refine_modes == 0)
    throw Error("search: top, per_rotation and refine_modes must be > 0");
  if (request.map_fft != "auto") parse_map_fft(request.map_fft);  // names an unknown or missing backend
}

// A process's device, FFT library and mapper.
struct MapperOnDevice {
  std::unique_ptr<ComputeContext> ctx;
  std::unique_ptr<FftLibrary> fft;
  std::unique_ptr<TranslationMapper> mapper;
  std::string fft_used;  // the backend and why
};

MapperOnDevice make_mapper(const SearchRequest& request, const PairSpectra& spectra, int local_rank) {
  MapperOnDevice m;
  m.ctx = std::make_unique<ComputeContext>(make_compute_context(select_device(device_for(request, local_rank))));
  m.fft = std::make_unique<FftLibrary>();
  MapFft kind = MapFft::clfft;
  std::size_t batch = request.map_batch ? request.map_batch : 1;
  if (request.map_fft == "auto") {
    const MapFftChoice choice = choose_map_fft(*m.fft, *m.ctx, spectra, request.interpolation, request.modes);
    kind = choice.fft;
    if (!request.map_batch) batch = choice.batch;
    m.fft_used = describe_map_fft_choice(choice);
  } else {
    kind = parse_map_fft(request.map_fft);
    m.fft_used = map_fft_name(kind) + " (SearchRequest::map_fft)";
  }
  if (request.map_batch)
    m.fft_used += ", " + std::to_string(batch) + (batch == 1 ? " rotation" : " rotations") +
                  " per batch (SearchRequest::map_batch)";
  m.mapper = std::make_unique<TranslationMapper>(*m.fft, *m.ctx, spectra, request.interpolation, request.modes, kind,
                                                 default_program_cache(), batch);
  return m;
}

SearchPlan plan_of(const So3Grid& grid, const PairSpectra& spectra, const MapperOnDevice& m, int processes) {
  SearchPlan plan;
  plan.rotations = grid.rotations.size();
  plan.base_cells = grid.base_cells;
  plan.psi_steps = grid.psi_steps;
  plan.step_deg = grid.step_rad / kDeg;
  plan.covering_radius_deg = so3_covering_radius(grid) / kDeg;
  plan.map_dims = spectra.dims;
  plan.spacing = spectra.spacing;
  plan.processes = processes;
  plan.map_fft = m.fft_used;
  plan.minima_on_device = m.mapper->minima_on_device();
  return plan;
}

// This process's share of the rotations, mapped; the bar (process 0) counts each of its
// maps once per process, the processes keeping pace.
RotationScan scan_share(TranslationMapper& mapper, const So3Grid& grid, double spacing, const SearchRequest& request,
                        SearchExchange& exchange, double& seconds) {
  std::vector<std::size_t> mine;
  for (std::size_t r = std::size_t(exchange.rank()); r < grid.rotations.size(); r += std::size_t(exchange.size()))
    mine.push_back(r);
  ScanOptions options;
  options.minima_per_rotation = request.per_rotation;
  options.separation = 2 * spacing;
  std::unique_ptr<Progress> progress;
  if (request.progress && exchange.rank() == 0) {
    progress = std::make_unique<Progress>("rotations", grid.rotations.size());
    progress->show_rate("rotations");
  }
  const auto start = std::chrono::steady_clock::now();
  RotationScan scan = scan_rotations(mapper, grid.rotations, mine, options, [&] {
    if (progress) progress->advance(std::size_t(exchange.size()));
  });
  seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (progress) progress->finish();
  return scan;
}

// The refinement on process 0's device: a descent of the energy, then (with the scene's
// rigid contact) of the potential the haptic loop renders, the energy times the loop's
// gain plus the contact, from where the first ended. The energy alone may be lowest
// inside part 1 (below a blind hole's floor); the rendered potential rests where the
// parts touch.
class Refiner {
 public:
  Refiner(const AssemblyPair& pair, const ComputeContext& ctx, const SearchRequest& request) {
    QueryVariant variant;
    variant.force = variant.torque = true;
    variant.interpolation = Interpolation::tricubic;
    engine_ = make_query_engine(ctx, pair.spectra, variant);
    const double spacing = pair.spectra.spacing;
    if (pair.scene.haptics.contact) {
      contact_ = rigid_contact_for(pair.scene, pair.part(1).mesh, pair.part(2).mesh, spacing);
      const TuningResult at_refine_modes =
          pick_modes({TimingPoint{request.refine_modes, 0, 0, 0, 1}}, pair.scene.frame_budget_ms, 0.25);
      double force_scale = 0;
      loop_ = loop_config_for(pair.scene, pair.part(2).mesh, spacing, *engine_, at_refine_modes, force_scale, contact_);
    }
    engine_->set_modes(request.refine_modes);
    descent_.length = pair.spectra.part2.half_extent.norm();
    descent_.step = spacing;
    descent_.min_step = spacing / 100;
    descent_.max_queries = request.refine_queries;
  }

  RefinedPose refine(const Pose& start) {
    RefinedPose r;
    try {
      const DescentResult by_energy = descend_pose(*engine_, start, descent_);
      r.energy_minimum = r.pose = by_energy.pose;
      r.energy_minimum_energy = r.energy = by_energy.energy;
      r.queries = by_energy.queries;
      if (contact_) {
        const RestPoint rest = descend_rendered(wrench_evaluator(*engine_), loop_.geometry_gain, loop_.contact,
                                                loop_.coupling, by_energy.pose);
        r.rendered = true;
        r.pose = rest.pose;
        r.energy = engine_->query(rest.pose).energy;
        r.potential_j = rest.potential_j;
        r.newton_steps = std::size_t(rest.steps);
      }
      r.modes = engine_->modes();
    } catch (const Error& e) {
      r = RefinedPose{};
      r.error = e.what();
    }
    return r;
  }

 private:
  std::unique_ptr<QueryEngine> engine_;
  std::shared_ptr<const RigidContactModel> contact_;
  LoopConfig loop_;
  DescentOptions descent_;
};

// Process 0: the gathered maps merged into the result, the best refined.
SearchResult merge_and_refine(const So3Grid& grid, const std::vector<double>& all_best,
                              const std::vector<double>& all_candidates, const std::vector<double>& rates,
                              const AssemblyPair& pair, const MapperOnDevice& m, const SearchRequest& request) {
  SearchResult result;
  result.rotations = grid.rotations;
  result.best_energy.assign(grid.rotations.size(), std::nan(""));
  for (std::size_t i = 0; i + 2 <= all_best.size(); i += 2)
    result.best_energy[std::size_t(all_best[i])] = all_best[i + 1];
  for (std::size_t i = 0; i + 2 <= rates.size(); i += 2) {
    result.process_rotations.push_back(std::size_t(rates[i]));
    result.process_seconds.push_back(rates[i + 1]);
  }
  result.map_fft = map_fft_name(m.mapper->fft());
  result.map_batch = m.mapper->batch();
  const double spacing = pair.spectra.spacing;
  Refiner refiner(pair, *m.ctx, request);
  for (const PoseCandidate& c :
       merge_candidates(decode_candidates(all_candidates, grid.rotations), request.top, 2 * spacing, grid.step_rad)) {
    FoundPose found;
    found.rotation = c.rotation;
    found.pose = c.pose;
    found.energy = c.energy;
    found.refined = refiner.refine(c.pose);
    result.top.push_back(found);
  }
  return result;
}

}  // namespace

SearchResult search(const Scene& scene, const SearchRequest& request, SearchExchange& exchange) {
  const bool root = exchange.rank() == 0;
  // Process 0 builds the pair (fields and spectra, cached); the others get its spectra.
  std::shared_ptr<AssemblyPair> pair;
  So3Grid grid;
  on_every_process(exchange, [&] {
    check_request(request);
    grid = request.rotations ? so3_grid_for_count(*request.rotations)
                             : so3_grid_for_step(request.step_deg.value_or(30.0) * kDeg);
    if (!root) return;
    Scene turning = scene;
    turning.motion = Motion::six_dof;  // part 2 in its own frame: the search turns it
    // The search goes everywhere, not along the trajectory (a declared workspace still bounds it).
    if (turning.grid.region.kind == RegionKind::reach) turning.grid.region.kind = RegionKind::whole;
    const ComputeContext ctx = make_compute_context(select_device(device_for(request, 0)));
    const FftLibrary fft;
    PairOptions options;
    if (request.progress) options.descriptors.progress = pass_progress_bars();
    options.note = request.note;
    pair = std::make_shared<AssemblyPair>(build_assembly_pair(turning, ctx, fft, options));
  });
  std::vector<double> sent = root ? encode_spectra(pair->spectra) : std::vector<double>{};
  exchange.broadcast(sent);
  PairSpectra received;
  on_every_process(exchange, [&] {
    if (!root) received = decode_spectra(sent);
  });
  const PairSpectra& spectra = root ? pair->spectra : received;

  // Process 0 measures the inverse FFTs first (alone on the machine), so the others on
  // the same kind of device find its pick in the cache.
  MapperOnDevice m;
  on_every_process(exchange, [&] {
    if (root) m = make_mapper(request, spectra, exchange.local_rank());
  });
  on_every_process(exchange, [&] {
    if (!root) m = make_mapper(request, spectra, exchange.local_rank());
  });
  SearchPlan plan;
  if (root) plan = plan_of(grid, spectra, m, exchange.size());
  if (root && request.on_plan) request.on_plan(plan);

  RotationScan scan;
  double seconds = 0;
  on_every_process(exchange, [&] { scan = scan_share(*m.mapper, grid, spectra.spacing, request, exchange, seconds); });
  std::vector<double> best_mine;
  for (std::size_t i = 0; i < scan.rotations.size(); ++i)
    best_mine.insert(best_mine.end(), {double(scan.rotations[i]), scan.best_energy[i]});
  const std::vector<double> all_best = exchange.gather(best_mine);
  const std::vector<double> all_candidates = exchange.gather(encode_candidates(scan.candidates));
  const std::vector<double> rates = exchange.gather({double(scan.rotations.size()), seconds});
  if (!root) return {};
  SearchResult result = merge_and_refine(grid, all_best, all_candidates, rates, *pair, m, request);
  result.plan = plan;
  return result;
}

SearchResult search(const Scene& scene, const SearchRequest& request) {
  OneProcess one;
  return search(scene, request, one);
}

std::vector<std::string> map_ffts_in_this_build() {
  std::vector<std::string> names;
  for (MapFft fft : map_ffts_built()) names.push_back(map_fft_name(fft));
  return names;
}

}  // namespace snapfit
