// Throughput of `snapfit search`'s map loop (engine/maps/rotation_search.h scan_rotations):
// full translational maps per second over an SO(3) grid, with both spectra uploaded
// once, the inverse FFT plan baked once and two maps in flight, against the one-shot
// path (engine/maps/full_map.h translational_energy_map: upload, bake, map, every call).
//
//   bench_search --help lists its options.
//
// Sizes 64^3 and 128^3, spectra of two synthetic parts (perf/bench_spectra.h: a ball and a
// box, E >= 0 wherever they overlap, so their maps hold no minima with E < 0), or with
// --scene the scene's pair at its own FFT size (maps with the minima of real parts), trilinear
// and tricubic resampling of the rotated spectrum (--quick: trilinear only), each inverse
// FFT this build has (engine/maps/map_fft.h) side by side, and the one choose_map_fft picks;
// with clFFT and VkFFT (the device FFTs) both ways of finding each map's minima: on the
// device (the search's way, engine/maps/device_minima.h: the minima kernel, then a short list
// read back and thinned on the host) and on the host (the whole complex map read back, put
// in grid order, then map_minima), so the two compare in one run. FFTW's maps are on the
// host: host only.
// Per row: where one map's time goes (TranslationMapper::time_minima_stages, or
// time_stages then map_minima: each stage waited for in turn, median of 3), the
// set-up (mapper constructor: uploads, kernels, plan), 2 warm-up maps, then N rotations of
// so3_grid_for_count(N) (default 64^3: 200, 128^3 and a scene: 40; --quick 24 and 6) with 4 minima
// per map, two maps in flight (scan_rotations; the host way on a device FFT: the same loop
// with collect and map_minima, as scan_rotations ran before the device found minima);
// the interval between consecutive finished maps is one rotation's cost; rotations/s =
// 1 / median interval, and the whole scan's count over its wall time. The device FFTs
// also map with their minima on the device in batches (engine/maps/full_map.h; batch "x8"
// or what fits the device): there one rotation's cost is a batch's interval over its
// rotations, and the stages are not timed (they are the batch-1 row's). One-shot: 3 calls
// (--quick 1), median.
// Output in DIR (default results/bench_search): search.csv, search.json, charts.html.
#include <algorithm>
#include <chrono>
#include <functional>
#include <iostream>
#include <memory>

#include "core/quantile.h"
#include "core/so3_grid.h"
#include "engine/maps/full_map.h"
#include "engine/maps/map_fft_choice.h"
#include "engine/maps/map_minima.h"
#include "engine/maps/rotation_search.h"
#include "engine/runtime/device.h"
#include "perf/bench_common.h"
#include "perf/bench_options.h"
#include "perf/bench_spectra.h"
#include "pipeline/assembly_pair.h"

namespace {

using namespace snapfit;
using Clock = std::chrono::steady_clock;
using bench::median;

struct Row {
  std::string workload;                    // "synthetic" or the scene file
  std::size_t n = 0;                       // FFT points along x
  std::string interpolation, fft, minima;  // minima: "device" or "host"
  std::size_t batch = 1;                   // rotations per batch
  MapStageSeconds stages;                  // medians (NaN: not timed)
  std::size_t rotations = 0;
  double setup_s = 0, median_s = 0, p90_s = 0, scan_rate = 0, one_shot_s = 0, load_before = 0, load_after = 0;
  MapMinimaCounts counts;  // over the row's maps
};

// scan_rotations as it was before the device found the minima: the whole map read
// back, the next map queued, then map_minima on the host.
void scan_on_host(TranslationMapper& mapper, const std::vector<Eigen::Quaterniond>& rotations,
                  const std::vector<std::size_t>& indices, const ScanOptions& options,
                  const std::function<void()>& done) {
  std::vector<float> energy;
  MapMinimaResult map;
  const std::size_t n = indices.size(), slots = TranslationMapper::slots;
  for (std::size_t i = 0; i < n && i < slots; ++i)
    mapper.submit(int(i % slots), rotations[indices[i]].toRotationMatrix(), MapOutput::energy);
  for (std::size_t i = 0; i < n; ++i) {
    const int slot = int(i % slots);
    mapper.collect(slot, energy);
    if (i + slots < n) mapper.submit(slot, rotations[indices[i + slots]].toRotationMatrix(), MapOutput::energy);
    map_minima(mapper.grid(), energy, options.minima_per_rotation, options.separation, map);
    done();
  }
}

// The median over 3 maps of each stage (minima found on the device, or on the host from
// the whole map read back).
MapStageSeconds stage_medians(TranslationMapper& mapper, const So3Grid& grid, const ScanOptions& options,
                              bool on_device) {
  std::vector<MapStageSeconds> stages;
  std::vector<float> energy;
  MapMinimaResult map;
  for (std::size_t k = 0; k < 3; ++k) {
    const Eigen::Matrix3d R = grid.rotations[k].toRotationMatrix();
    if (on_device) {
      stages.push_back(mapper.time_minima_stages(R, options.minima_per_rotation, options.separation, map));
    } else {
      stages.push_back(mapper.time_stages(R, energy));
      const auto t0 = Clock::now();
      map_minima(mapper.grid(), energy, options.minima_per_rotation, options.separation, map);
      stages.back().minima = seconds_since(t0);
    }
  }
  auto stage = [&](double MapStageSeconds::*field) {
    std::vector<double> v;
    for (const MapStageSeconds& s : stages) v.push_back(s.*field);
    return median(v);
  };
  MapStageSeconds medians;
  for (double MapStageSeconds::*field : {&MapStageSeconds::product, &MapStageSeconds::fft, &MapStageSeconds::reduce,
                                         &MapStageSeconds::read, &MapStageSeconds::host, &MapStageSeconds::minima})
    medians.*field = stage(field);
  return medians;
}

// A batch's maps finish together: each batch's intervals as one per rotation, their mean.
std::vector<double> per_rotation(const std::vector<double>& intervals, std::size_t batch) {
  std::vector<double> out;
  for (std::size_t i = 0; i < intervals.size(); i += batch) {
    const std::size_t end = std::min(intervals.size(), i + batch);
    double sum = 0;
    for (std::size_t j = i; j < end; ++j) sum += intervals[j];
    out.push_back(sum / double(end - i));
  }
  return out;
}

// One row: the mapper's set-up, the median of each stage over 3 maps (one rotation at a
// time only), then a scan of the rotations (two batches in flight), and for clFFT on the
// device one at a time the one-shot map.
Row measure_row(const FftLibrary& fft, const ComputeContext& ctx, const PairSpectra& spectra,
                Interpolation interpolation, MapFft kind, bool on_device, std::size_t batch, long rotations, bool quick,
                std::size_t synthetic) {
  Row row;
  row.batch = batch;
  row.n = spectra.dims[0];
  row.interpolation = interpolation == Interpolation::tricubic ? "tricubic" : "trilinear";
  row.fft = map_fft_name(kind);
  row.minima = on_device ? "device" : "host";
  row.rotations = rotations > 0 ? std::size_t(rotations)
                  : quick       ? (synthetic == 64 ? 24 : 6)
                                : (synthetic == 64 ? 200 : 40);
  row.load_before = bench::load1();
  auto t0 = Clock::now();
  TranslationMapper mapper(fft, ctx, spectra, interpolation, 0, kind, default_program_cache(), batch);
  row.setup_s = seconds_since(t0);
  const So3Grid grid = so3_grid_for_count(row.rotations);
  std::vector<std::size_t> warm{1, 2}, all(grid.rotations.size());
  for (std::size_t i = 0; i < all.size(); ++i) all[i] = i;
  const ScanOptions options{4, 1.0};
  auto scan = [&](const std::vector<std::size_t>& indices, const std::function<void()>& done) {
    if (on_device || !map_fft_on_device(kind))
      scan_rotations(mapper, grid.rotations, indices, options, done);
    else
      scan_on_host(mapper, grid.rotations, indices, options, done);
  };
  scan(warm, [] {});
  const double nan = std::nan("");
  row.stages =
      batch > 1 ? MapStageSeconds{nan, nan, nan, nan, nan, nan} : stage_medians(mapper, grid, options, on_device);
  std::vector<double> intervals;
  t0 = Clock::now();
  auto last = t0;
  scan(all, [&] {
    const auto now = Clock::now();
    intervals.push_back(std::chrono::duration<double>(now - last).count());
    last = now;
  });
  const double scan_s = seconds_since(t0);
  row.rotations = all.size();
  row.scan_rate = double(all.size()) / scan_s;
  if (batch > 1) intervals = per_rotation(intervals, batch);
  row.median_s = median(intervals);
  row.p90_s = quantile(intervals, 0.9);
  row.counts = mapper.minima_counts();
  if (kind == MapFft::clfft && on_device && batch == 1) {
    std::vector<double> one_shot;
    for (int k = 0; k < (quick ? 1 : 3); ++k) {
      t0 = Clock::now();
      translational_energy_map(fft, ctx, spectra, grid.rotations[std::size_t(k)].toRotationMatrix(), interpolation);
      one_shot.push_back(seconds_since(t0));
    }
    row.one_shot_s = median(one_shot);
  }
  row.load_after = bench::load1();
  return row;
}

void print_row(const std::string& size, const Row& row, bool on_device) {
  auto ms = [](double s) { return bench::fixed(1e3 * s, 1); };
  std::cout << size << " " << row.interpolation << " " << row.fft
            << (row.batch > 1 ? " x" + std::to_string(row.batch) : std::string()) << ", minima on the " << row.minima
            << ": ";
  if (row.batch > 1)
    std::cout << "stages not timed (batched; longest list " << row.counts.longest << ", " << row.counts.fallbacks
              << " whole maps read)";
  else if (on_device)
    std::cout << "stages product " << ms(row.stages.product) << " ms, inverse FFT " << ms(row.stages.fft)
              << " ms, minima kernel " << ms(row.stages.reduce) << " ms, read-back of the list " << ms(row.stages.read)
              << " ms, thinning " << ms(row.stages.minima) << " ms (longest list " << row.counts.longest << ", "
              << row.counts.long_lists << " read twice, " << row.counts.fallbacks << " whole maps read)";
  else
    std::cout << "stages product " << ms(row.stages.product) << " ms, inverse FFT " << ms(row.stages.fft)
              << " ms, read-back " << ms(row.stages.read) << " ms, host map " << ms(row.stages.host) << " ms, minima "
              << ms(row.stages.minima) << " ms";
  std::cout << "; " << row.rotations << " rotations, set-up " << bench::fixed(row.setup_s, 2) << " s, median "
            << ms(row.median_s) << " ms per rotation (" << bench::fixed(1 / row.median_s, 1) << " rotations/s; p90 "
            << ms(row.p90_s) << " ms), whole scan " << bench::fixed(row.scan_rate, 1) << " rotations/s";
  if (row.one_shot_s > 0)
    std::cout << "; one-shot translational_energy_map " << bench::fixed(1e3 * row.one_shot_s, 0) << " ms";
  std::cout << "; load " << bench::fixed(row.load_before, 2) << " -> " << bench::fixed(row.load_after, 2) << "\n";
}

// Rotations per second against the grid size, per interpolation, FFT and where the
// minima are found, and clFFT's one-shot map.
Chart rate_chart(const std::vector<Row>& rows) {
  Chart chart = bench::make_chart("snapfit search: rotations per second (median interval)", "FFT grid points per axis",
                                  "rotations/s", false, true);
  for (const char* name : {"trilinear", "tricubic"}) {
    for (const MapFft kind : map_ffts_built())
      for (const char* where : {"device", "host", "device, batched"}) {
        const bool batched = std::string(where) == "device, batched";
        Series s;
        s.label = std::string(name) + ", " + map_fft_name(kind) + ", minima on the " + where + ", scan (pipelined)";
        for (const Row& r : rows)
          if (r.interpolation == name && r.fft == map_fft_name(kind) && (r.batch > 1) == batched &&
              r.minima == (batched ? "device" : where)) {
            s.x.push_back(double(r.n));
            s.y.push_back(1 / r.median_s);
          }
        if (!s.x.empty()) chart.series.push_back(s);
      }
    Series one;
    one.label = std::string(name) + ", clfft, one-shot map";
    for (const Row& r : rows)
      if (r.interpolation == name && r.one_shot_s > 0) {
        one.x.push_back(double(r.n));
        one.y.push_back(1 / r.one_shot_s);
      }
    if (!one.x.empty()) chart.series.push_back(one);
  }
  return chart;
}

nlohmann::json row_json(const Row& r) {
  return nlohmann::json{{"workload", r.workload},
                        {"n", r.n},
                        {"interpolation", r.interpolation},
                        {"fft", r.fft},
                        {"batch", r.batch},
                        {"minima_on", r.minima},
                        {"product_s", r.stages.product},
                        {"inverse_fft_s", r.stages.fft},
                        {"reduce_s", r.stages.reduce},
                        {"read_s", r.stages.read},
                        {"host_map_s", r.stages.host},
                        {"minima_s", r.stages.minima},
                        {"longest_list", r.counts.longest},
                        {"long_lists", r.counts.long_lists},
                        {"whole_maps_read", r.counts.fallbacks},
                        {"rotations", r.rotations},
                        {"setup_s", r.setup_s},
                        {"median_s", r.median_s},
                        {"p90_s", r.p90_s},
                        {"rotations_per_s_median", 1 / r.median_s},
                        {"rotations_per_s_scan", r.scan_rate},
                        {"one_shot_s", r.one_shot_s},
                        {"load_before", r.load_before},
                        {"load_after", r.load_after}};
}

}  // namespace

int main(int argc, char** argv) {
  return bench::guarded_main("bench_search", [&] {
    bool quick = false;
    std::string device, out = "results/bench_search";
    std::string scene_path;
    long rotations = 0;
    CLI::App app{
        "Maps per second of snapfit search's loop at 64^3 and 128^3, or on a scene's pair (see the file's "
        "header)",
        "bench_search"};
    bench::add_common_options(app, quick, device, out);
    app.add_option("--rotations", rotations,
                   "timed rotations per row (0: 200 at 64^3, 40 at 128^3 and on a scene; --quick 24 and 6)")
        ->check(CLI::Range(1, 1000000));
    app.add_option("--scene", scene_path, "a scene's pair instead of the synthetic sizes");
    bench::parse(app, argc, argv);
    const FftLibrary fft;
    const ComputeContext ctx = make_compute_context(select_device(device_spec_from(device)));
    std::cout << "bench_search on " << ctx.device.info.name << (quick ? " (quick)" : "") << ", load "
              << bench::read_loadavg() << "\n";
    std::vector<Row> rows;
    // A scene's pair (fields and spectra through the caches), or none: the synthetic sizes.
    std::unique_ptr<AssemblyPair> pair;
    if (!scene_path.empty()) {
      PairOptions options;
      options.note = [](const std::string&) {};
      pair = std::make_unique<AssemblyPair>(build_assembly_pair(load_scene(scene_path), ctx, fft, options));
    }
    const std::vector<std::size_t> sizes = pair ? std::vector<std::size_t>{0} : std::vector<std::size_t>{64, 128};
    for (const std::size_t synthetic : sizes) {
      const PairSpectra spectra =
          pair ? pair->spectra : bench::synthetic_spectra(fft, ctx, {synthetic, synthetic, synthetic}, 0.5);
      const std::size_t n = spectra.dims[0];
      const std::string size = std::to_string(spectra.dims[0]) +
                               (spectra.dims[1] == n && spectra.dims[2] == n
                                    ? std::string("^3")
                                    : "x" + std::to_string(spectra.dims[1]) + "x" + std::to_string(spectra.dims[2]));
      for (const Interpolation interpolation : {Interpolation::trilinear, Interpolation::tricubic}) {
        if (quick && interpolation == Interpolation::tricubic) continue;
        const MapFftChoice choice = choose_map_fft(fft, ctx, spectra, interpolation);
        std::cout << size << " " << (interpolation == Interpolation::tricubic ? "tricubic" : "trilinear")
                  << ": choose_map_fft picks " << describe_map_fft_choice(choice) << "\n";
        std::vector<std::size_t> batches{1};
        if (const std::size_t b = map_batch_limit(ctx, spectra.dims, kMapBatch); b > 1) batches.push_back(b);
        for (const MapFft kind : map_ffts_built())
          for (const std::size_t batch : batches)
            for (const bool on_device : {true, false}) {
              if (on_device && !map_fft_on_device(kind)) continue;  // FFTW's maps are on the host
              if (batch > 1 && !on_device) continue;                // batches: the search's way only
              Row row =
                  measure_row(fft, ctx, spectra, interpolation, kind, on_device, batch, rotations, quick, synthetic);
              row.workload = pair ? scene_path : "synthetic";
              print_row(size, row, on_device);
              rows.push_back(row);
            }
      }
    }
    std::filesystem::create_directories(out);
    bench::CsvFile csv(std::filesystem::path(out) / "search.csv",
                       "workload,n,interpolation,fft,batch,minima_on,product_s,inverse_fft_s,reduce_s,read_s,"
                       "host_map_s,minima_s,rotations,setup_s,median_s,p90_s,rotations_per_s_median,"
                       "rotations_per_s_scan,one_shot_s,longest_list,whole_maps_read,load_before,load_after");
    nlohmann::json json = {{"command", bench::command_line(argc, argv)},
                           {"device", ctx.device.info.name},
                           {"date", bench::now_iso()},
                           {"rows", nlohmann::json::array()}};
    const Chart chart = rate_chart(rows);
    for (const Row& r : rows) {
      csv.row(r.workload, r.n, r.interpolation, r.fft, r.batch, r.minima, r.stages.product, r.stages.fft,
              r.stages.reduce, r.stages.read, r.stages.host, r.stages.minima, r.rotations, r.setup_s, r.median_s,
              r.p90_s, 1 / r.median_s, r.scan_rate, r.one_shot_s, r.counts.longest, r.counts.fallbacks, r.load_before,
              r.load_after);
      json["rows"].push_back(row_json(r));
    }
    bench::write_json(std::filesystem::path(out) / "search.json", json);
    std::cout << bench::write_charts(out, "bench_search", bench::command_line(argc, argv), {chart}) << "\n";
    return 0;
  });
}
