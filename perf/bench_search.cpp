// Throughput of `snapfit search`'s map loop (engine/rotation_search.h scan_rotations):
// full translational maps per second over an SO(3) grid, with both spectra uploaded
// once, the inverse FFT plan baked once and two maps in flight, against the one-shot
// path (engine/full_map.h translational_energy_map: upload, bake, map, every call).
//
//   bench_search [--quick] [--device SPEC] [--out DIR] [--rotations N]
//
// Sizes 64^3 and 128^3, spectra of two synthetic parts (perf/bench_spectra.h), trilinear
// and tricubic resampling of the rotated spectrum (--quick: trilinear only), each inverse
// FFT this build has (engine/map_fft.h) side by side, and the one choose_map_fft picks.
// Per row: where one map's time goes (TranslationMapper::time_stages, each stage waited
// for in turn, median of 3; then map_minima on that map), the
// set-up (mapper constructor: uploads, kernel, plan), 2 warm-up maps, then N rotations of
// so3_grid_for_count(N) (default 64^3: 200, 128^3: 40; --quick 24 and 6) through
// scan_rotations with 4 minima per map; the interval between consecutive finished maps
// is one rotation's cost; rotations/s = 1 / median interval, and the whole scan's count
// over its wall time. One-shot: 3 calls (--quick 1), median.
// Output in DIR (default results/bench_search): search.csv, search.json, charts.html.
#include <algorithm>
#include <chrono>
#include <iostream>

#include "core/quantile.h"
#include "core/so3_grid.h"
#include "engine/device.h"
#include "engine/full_map.h"
#include "engine/map_fft_choice.h"
#include "engine/map_minima.h"
#include "engine/rotation_search.h"
#include "perf/bench_common.h"
#include "perf/bench_spectra.h"

namespace {

using namespace snapfit;
using Clock = std::chrono::steady_clock;

void usage(std::ostream& out) {
  out << "bench_search [--quick] [--device SPEC] [--out DIR] [--rotations N]\n"
         "  maps per second of snapfit search's loop at 64^3 and 128^3 (see the file's header)\n";
}

struct Row {
  std::size_t n = 0;
  std::string interpolation, fft;
  MapStageSeconds stages;  // medians
  double minima_s = 0;
  std::size_t rotations = 0;
  double setup_s = 0, median_s = 0, p90_s = 0, scan_rate = 0, one_shot_s = 0, load_before = 0, load_after = 0;
};

double median(const std::vector<double>& v) { return quantile(v, 0.5); }

}  // namespace

int main(int argc, char** argv) {
  return bench::guarded_main("bench_search", [&] {
    bool quick = false;
    std::string device, out = "results/bench_search";
    long rotations = 0;
    bench::parse_options(argc, argv, quick, device, out, usage, [&](const std::string&, auto value, auto is) {
      if (!is("--rotations")) return false;
      rotations = bench::integer_option("--rotations", value("--rotations"), 1, 1000000);
      return true;
    });
    const FftLibrary fft;
    const ComputeContext ctx = make_compute_context(select_device(device_spec_from(device)));
    std::cout << "bench_search on " << ctx.device.info.name << (quick ? " (quick)" : "") << ", load "
              << bench::read_loadavg() << "\n";
    std::vector<Row> rows;
    for (const std::size_t n : {64, 128}) {
      const PairSpectra spectra = bench::synthetic_spectra(fft, ctx, {n, n, n}, 0.5);
      for (const Interpolation interpolation : {Interpolation::trilinear, Interpolation::tricubic}) {
        if (quick && interpolation == Interpolation::tricubic) continue;
        const MapFftChoice choice = choose_map_fft(fft, ctx, spectra, interpolation);
        std::cout << n << "^3 " << (interpolation == Interpolation::tricubic ? "tricubic" : "trilinear")
                  << ": choose_map_fft picks " << describe_map_fft_choice(choice) << "\n";
        for (const MapFft kind : map_ffts_built()) {
          Row row;
          row.n = n;
          row.interpolation = interpolation == Interpolation::tricubic ? "tricubic" : "trilinear";
          row.fft = map_fft_name(kind);
          row.rotations = rotations > 0 ? std::size_t(rotations) : quick ? (n == 64 ? 24 : 6) : (n == 64 ? 200 : 40);
          row.load_before = bench::load1();
          auto t0 = Clock::now();
          TranslationMapper mapper(fft, ctx, spectra, interpolation, 0, kind);
          row.setup_s = bench::seconds_since(t0);
          const So3Grid grid = so3_grid_for_count(row.rotations);
          std::vector<std::size_t> warm{1, 2}, all(grid.rotations.size());
          for (std::size_t i = 0; i < all.size(); ++i) all[i] = i;
          scan_rotations(mapper, grid.rotations, warm, ScanOptions{4, 1.0});
          std::vector<double> product, inverse, read, host, minima;
          std::vector<float> energy;
          for (std::size_t k = 0; k < 3; ++k) {
            const MapStageSeconds st = mapper.time_stages(grid.rotations[k].toRotationMatrix(), energy);
            product.push_back(st.product);
            inverse.push_back(st.fft);
            read.push_back(st.read);
            host.push_back(st.host);
            t0 = Clock::now();
            map_minima(mapper.grid(), energy, 4, 1.0);
            minima.push_back(bench::seconds_since(t0));
          }
          row.stages = {median(product), median(inverse), median(read), median(host)};
          row.minima_s = median(minima);
          std::vector<double> intervals;
          t0 = Clock::now();
          auto last = t0;
          scan_rotations(mapper, grid.rotations, all, ScanOptions{4, 1.0}, [&] {
            const auto now = Clock::now();
            intervals.push_back(std::chrono::duration<double>(now - last).count());
            last = now;
          });
          const double scan_s = bench::seconds_since(t0);
          row.rotations = all.size();
          row.scan_rate = double(all.size()) / scan_s;
          row.median_s = median(intervals);
          row.p90_s = quantile(intervals, 0.9);
          if (kind == MapFft::clfft) {
            std::vector<double> one_shot;
            for (int k = 0; k < (quick ? 1 : 3); ++k) {
              t0 = Clock::now();
              translational_energy_map(fft, ctx, spectra, grid.rotations[std::size_t(k)].toRotationMatrix(),
                                       interpolation);
              one_shot.push_back(bench::seconds_since(t0));
            }
            row.one_shot_s = median(one_shot);
          }
          row.load_after = bench::load1();
          auto ms = [](double s) { return bench::fixed(1e3 * s, 1); };
          std::cout << n << "^3 " << row.interpolation << " " << row.fft << ": stages product "
                    << ms(row.stages.product) << " ms, inverse FFT " << ms(row.stages.fft) << " ms, read-back "
                    << ms(row.stages.read) << " ms, host map " << ms(row.stages.host) << " ms, minima "
                    << ms(row.minima_s) << " ms; " << row.rotations << " rotations, set-up "
                    << bench::fixed(row.setup_s, 2) << " s, median " << ms(row.median_s) << " ms per rotation ("
                    << bench::fixed(1 / row.median_s, 1) << " rotations/s; p90 " << ms(row.p90_s) << " ms), whole scan "
                    << bench::fixed(row.scan_rate, 1) << " rotations/s";
          if (row.one_shot_s > 0)
            std::cout << "; one-shot translational_energy_map " << bench::fixed(1e3 * row.one_shot_s, 0) << " ms";
          std::cout << "; load " << bench::fixed(row.load_before, 2) << " -> " << bench::fixed(row.load_after, 2)
                    << "\n";
          rows.push_back(row);
        }
      }
    }
    std::filesystem::create_directories(out);
    std::ofstream csv(std::filesystem::path(out) / "search.csv");
    csv << "n,interpolation,fft,product_s,inverse_fft_s,read_s,host_map_s,minima_s,rotations,setup_s,median_s,p90_s,"
           "rotations_per_s_median,rotations_per_s_scan,one_shot_s,"
           "load_before,load_after\n";
    nlohmann::json json = {{"command", bench::command_line(argc, argv)},
                           {"device", ctx.device.info.name},
                           {"date", bench::now_iso()},
                           {"rows", nlohmann::json::array()}};
    Chart chart;
    chart.title = "snapfit search: rotations per second (median interval)";
    chart.x_label = "FFT grid points per axis";
    chart.y_label = "rotations/s";
    chart.log_y = true;
    for (const char* name : {"trilinear", "tricubic"}) {
      for (const MapFft kind : map_ffts_built()) {
        Series s;
        s.label = std::string(name) + ", " + map_fft_name(kind) + ", scan (pipelined)";
        for (const Row& r : rows)
          if (r.interpolation == name && r.fft == map_fft_name(kind)) {
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
    for (const Row& r : rows) {
      csv << r.n << "," << r.interpolation << "," << r.fft << "," << r.stages.product << "," << r.stages.fft << ","
          << r.stages.read << "," << r.stages.host << "," << r.minima_s << "," << r.rotations << "," << r.setup_s << ","
          << r.median_s << "," << r.p90_s << "," << 1 / r.median_s << "," << r.scan_rate << "," << r.one_shot_s << ","
          << r.load_before << "," << r.load_after << "\n";
      json["rows"].push_back({{"n", r.n},
                              {"interpolation", r.interpolation},
                              {"fft", r.fft},
                              {"product_s", r.stages.product},
                              {"inverse_fft_s", r.stages.fft},
                              {"read_s", r.stages.read},
                              {"host_map_s", r.stages.host},
                              {"minima_s", r.minima_s},
                              {"rotations", r.rotations},
                              {"setup_s", r.setup_s},
                              {"median_s", r.median_s},
                              {"p90_s", r.p90_s},
                              {"rotations_per_s_median", 1 / r.median_s},
                              {"rotations_per_s_scan", r.scan_rate},
                              {"one_shot_s", r.one_shot_s},
                              {"load_before", r.load_before},
                              {"load_after", r.load_after}});
    }
    std::ofstream(std::filesystem::path(out) / "search.json") << json.dump(2) << "\n";
    std::cout << bench::write_charts(out, "bench_search", bench::command_line(argc, argv), {chart}) << "\n";
    return 0;
  });
}
