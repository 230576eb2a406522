// Mesh import cost and the import child's limits (io/mesh_load.cpp). A torus of
// --triangles triangles (default 1e6) is written as binary STL and as OBJ; each is
// imported in this process (inside a child, to measure it alone: peak address space
// and peak RSS above what the child started with, CPU and wall time) and then through
// load_mesh's import child with the default limits (wall time, the same triangles).
// Then the fuzz regression files that make Assimp allocate gigabytes
// (tests/data/fuzz/*_memory_blowup.bin) are loaded with the default limits: time to the error.
//
//   bench_mesh_import --help lists its options.
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>

#include "io/isolated_import.h"
#include "io/mesh_export.h"
#include "io/mesh_load.h"
#include "perf/bench_common.h"
#include "perf/bench_options.h"
#include "snapfit/error.h"

using namespace snapfit;
namespace fs = std::filesystem;

namespace {

const ChildLimits kNoLimit{1 << 20, 3600, 3600};  // 1 TiB, an hour: only for isolation

// A torus (R = 10, r = 3) of about `triangles` triangles, indexed, outward-facing.
Mesh torus(long triangles) {
  const int nv = std::max(3, static_cast<int>(std::lround(std::sqrt(triangles / 4.0)))), nu = 2 * nv;
  Mesh m;
  const double pi = std::acos(-1.0);
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j) {
      const double u = 2 * pi * i / nu, v = 2 * pi * j / nv, rr = 10 + 3 * std::cos(v);
      m.vertices.emplace_back(rr * std::cos(u), rr * std::sin(u), 3 * std::sin(v));
    }
  const auto at = [&](int i, int j) { return (i % nu) * nv + (j % nv); };
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j) {
      m.triangles.emplace_back(at(i, j), at(i + 1, j), at(i + 1, j + 1));
      m.triangles.emplace_back(at(i, j), at(i + 1, j + 1), at(i, j + 1));
    }
  return m;
}

// A field of /proc/self/status in MiB ("VmPeak", "VmHWM", ...).
double status_mib(const std::string& key) {
  std::ifstream f("/proc/self/status");
  std::string line;
  while (std::getline(f, line))
    if (line.rfind(key + ":", 0) == 0) return std::stod(line.substr(key.size() + 1)) / 1024.0;  // kB
  return -1;
}

// Imports `file` in this process, inside a child of its own so that its peaks are its
// alone (the child's VmPeak starts at the parent's, which is kept small: the meshes are
// written by a child too).
nlohmann::json measure_in_process(const std::string& file) {
  const ChildResult r = run_in_child(
      [&] {
        ::setenv("SNAPFIT_IMPORT_MEMORY_MIB", "inprocess", 1);
        std::ofstream("/proc/self/clear_refs") << "5";  // resets VmHWM
        const double vm0 = status_mib("VmSize"), rss0 = status_mib("VmRSS"), cpu0 = bench::process_cpu_seconds();
        const auto t0 = std::chrono::steady_clock::now();
        const Mesh m = load_mesh(file);
        const nlohmann::json j = {{"wall_s", seconds_since(t0)},
                                  {"cpu_s", bench::process_cpu_seconds() - cpu0},
                                  {"peak_address_space_mib", status_mib("VmPeak") - vm0},
                                  {"peak_rss_mib", status_mib("VmHWM") - rss0},
                                  {"triangles", m.triangles.size()},
                                  {"vertices", m.vertices.size()}};
        return j.dump();
      },
      kNoLimit);
  if (r.status != ChildResult::Status::ok) throw Error(file + ": in-process import failed: " + r.bytes);
  return nlohmann::json::parse(r.bytes);
}

}  // namespace

int main(int argc, char** argv) {
  return bench::guarded_main("bench_mesh_import", [&] {
    std::string out_dir = "results/bench_mesh_import";
    long triangles = 1000000;
    bool quick = false;
    CLI::App app{
        "Mesh import cost and the import child's limits: a torus as binary STL and OBJ, then the fuzz files "
        "that make Assimp allocate gigabytes",
        "bench_mesh_import"};
    bench::add_quick_and_out(app, quick, out_dir, "20,000 triangles and no fuzz files");
    app.add_option("--triangles", triangles, "the torus's triangles")->check(CLI::Range(100L, 20000000L));
    bench::parse(app, argc, argv);
    if (quick) triangles = 20000;
    const std::string load_start = bench::read_loadavg();
    fs::create_directories(out_dir);
    const fs::path stl = fs::path(out_dir) / "torus.stl", obj = fs::path(out_dir) / "torus.obj";
    const ChildResult written = run_in_child(
        [&] {
          const Mesh m = torus(triangles);
          write_stl(m, stl.string());
          write_obj(m, obj.string());
          return std::string();
        },
        kNoLimit);
    if (written.status != ChildResult::Status::ok) throw Error("cannot write the torus: " + written.bytes);

    nlohmann::json imports = nlohmann::json::array();
    for (const fs::path& file : {stl, obj}) {
      nlohmann::json j = measure_in_process(file.string());
      const auto t0 = std::chrono::steady_clock::now();
      const Mesh m = load_mesh(file.string());  // through the import child, default limits
      j["child_wall_s"] = seconds_since(t0);
      j["child_triangles"] = m.triangles.size();
      j["file"] = file.filename().string();
      j["file_mib"] = fs::file_size(file) / 1048576.0;
      std::cout << bench::padr(file.filename().string(), 10) << " " << bench::fixed(j["file_mib"].get<double>())
                << " MiB, " << m.triangles.size() << " triangles: in-process peak address space +"
                << bench::fixed(j["peak_address_space_mib"].get<double>()) << " MiB, peak RSS +"
                << bench::fixed(j["peak_rss_mib"].get<double>()) << " MiB, "
                << bench::fixed(j["cpu_s"].get<double>(), 2) << " s CPU, " << bench::fixed(j["wall_s"].get<double>(), 2)
                << " s; through the child " << bench::fixed(j["child_wall_s"].get<double>(), 2) << " s\n";
      imports.push_back(j);
      fs::remove(file);
    }

    nlohmann::json blowups = nlohmann::json::array();
    if (!quick) {
      const fs::path data = "tests/data/fuzz";  // run from the source folder, like the others
      for (const auto& [name, ext] :
           {std::pair<std::string, std::string>{"x_memory_blowup.bin", ".x"}, {"dae_memory_blowup.bin", ".dae"}}) {
        const fs::path file = fs::path(out_dir) / ("blowup" + ext);
        fs::copy_file(data / name, file, fs::copy_options::overwrite_existing);
        const auto t0 = std::chrono::steady_clock::now();
        std::string message = "(loaded)";
        try {
          load_mesh(file.string());
        } catch (const Error& e) {
          message = e.what();
        }
        const double s = seconds_since(t0);
        std::cout << bench::padr(name, 15) << " " << bench::fixed(s, 2) << " s: " << message << "\n";
        blowups.push_back({{"file", name}, {"seconds", s}, {"message", message}});
        fs::remove(file);
      }
    }
    const std::string load_end = bench::read_loadavg();
    std::cout << "load average: start " << load_start << ", end " << load_end << "\n";
    const nlohmann::json report = {{"command", bench::command_line(argc, argv)},
                                   {"date", bench::now_iso()},
                                   {"triangles", triangles},
                                   {"imports", imports},
                                   {"blowups", blowups},
                                   {"load_average", {{"start", load_start}, {"end", load_end}}}};
    std::ofstream(fs::path(out_dir) / "mesh_import.json") << report.dump(2) << "\n";
    std::cout << "wrote " << out_dir << "/mesh_import.json\n";
    return 0;
  });
}
