#pragma once
// Small helpers shared by the perf/ benchmarks: load average, date, CPU contention,
// table formatting and the parts of their reports that they share.
#include <CL/opencl.hpp>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iomanip>
#include <iostream>
#include <limits>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <sys/resource.h>
#include <thread>
#include <unistd.h>
#include <vector>

#include "core/progress.h"  // seconds_since
#include "core/quantile.h"
#include "engine/maps/full_map.h"
#include "engine/query/query_engine.h"
#include "engine/runtime/device.h"
#include "report/chart_spec.h"
#include "report/device_json.h"
#include "report/web_assets.h"
#include "snapfit/error.h"
#include "snapfit/query.h"

namespace snapfit::bench {

// The command line as one string, for the JSON reports.
inline std::string command_line(int argc, char** argv) {
  std::string out;
  for (int i = 0; i < argc; ++i) out += (i ? " " : "") + std::string(argv[i]);
  return out;
}

// A benchmark's main: runs `body` and turns an escaping error into a message on stderr
// ("NAME: error: ..." or "NAME: OpenCL error: ... (code)") and exit status 1.
inline int guarded_main(const char* name, const std::function<int()>& body) {
  try {
    return body();
  } catch (const snapfit::Error& e) {
    std::cerr << name << ": error: " << e.what() << "\n";
  } catch (const cl::Error& e) {
    std::cerr << name << ": OpenCL error: " << e.what() << " (" << e.err() << ")\n";
  } catch (const std::exception& e) {
    std::cerr << name << ": error: " << e.what() << "\n";
  }
  return 1;
}

// The loop's device as `snapfit run` picks it (scheduler/tuning/device_choice.h): PoCL's
// single-threaded driver, which runs kernels in the loop's own thread, when there is one
// (asked for as the CLI's main() does); a non-empty `spec` overrides.
inline Device loop_device(const std::string& spec) {
  expose_pocl_caller_thread_driver();
  if (!spec.empty()) return select_device(device_spec_from(spec));
  for (const Device& d : enumerate_devices())
    if (d.info.runs_in_caller_thread()) return d;
  return select_device(device_spec_from(""));
}

// /proc/loadavg as written, and its 1-minute figure (-1 when unreadable).
inline std::string read_loadavg() {
  std::ifstream f("/proc/loadavg");
  std::string line;
  std::getline(f, line);
  return line;
}
inline double load1() {
  std::istringstream in(read_loadavg());
  double l = -1;
  in >> l;
  return l;
}

inline std::string now_iso() {
  const std::time_t t = std::time(nullptr);
  char buf[64];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%S%z", std::localtime(&t));
  return buf;
}
// The header every benchmark's JSON report starts with: what ran, when, where, and the
// load average before and after (this machine is shared; the load says how far to trust it).
inline nlohmann::json run_record(int argc, char** argv, const std::string& device, const std::string& load_start) {
  return {{"command", command_line(argc, argv)},
          {"date", now_iso()},
          {"device", device},
          {"load_average", {{"start", load_start}, {"end", read_loadavg()}}}};
}

// CPU time used by the whole machine (non-idle, all cores) and by this process (all its
// threads, the OpenCL device's worker threads included), in core-seconds: over an
// interval, their difference is what other processes took from the cores meanwhile.
struct CpuSample {
  double machine_busy_s = 0, own_s = 0;
  std::chrono::steady_clock::time_point at = std::chrono::steady_clock::now();
};
inline CpuSample cpu_sample() {
  CpuSample c;
  const double tick = double(sysconf(_SC_CLK_TCK));
  {
    std::ifstream f("/proc/stat");
    std::string cpu;
    double user = 0, nice = 0, system = 0, idle = 0, iowait = 0, irq = 0, softirq = 0, steal = 0;
    f >> cpu >> user >> nice >> system >> idle >> iowait >> irq >> softirq >> steal;
    c.machine_busy_s = (user + nice + system + irq + softirq + steal) / tick;
  }
  {
    std::ifstream f("/proc/self/stat");
    std::string line;
    std::getline(f, line);
    const auto close = line.rfind(')');
    if (close != std::string::npos) {
      std::istringstream in(line.substr(close + 2));
      std::string field;
      double utime = 0, stime = 0;
      for (int i = 3; i <= 15 && in >> field; ++i) {  // fields 3.. after "pid (comm)"
        if (i == 14) utime = std::stod(field);
        if (i == 15) stime = std::stod(field);
      }
      c.own_s = (utime + stime) / tick;
    }
  }
  return c;
}
// Cores kept busy by other processes between two samples (0 on a quiet machine).
inline double other_cores(const CpuSample& a, const CpuSample& b) {
  const double wall = std::chrono::duration<double>(b.at - a.at).count();
  if (wall <= 0) return 0;
  return std::max(0.0, ((b.machine_busy_s - a.machine_busy_s) - (b.own_s - a.own_s)) / wall);
}

using snapfit::seconds_since;  // core/progress.h, for the benches that use this namespace only

// Table formatting shared by the benchmarks' console reports.
// v with `prec` digits in `format` (std::ios_base::fixed, scientific, or {}: significant
// digits); '-' when it is not finite.
inline std::string formatted(double v, int prec, std::ios_base::fmtflags format) {
  if (!std::isfinite(v)) return "-";
  std::ostringstream os;
  os.setf(format, std::ios_base::floatfield);
  os << std::setprecision(prec) << v;
  return os.str();
}
inline std::string fixed(double v, int prec = 1) { return formatted(v, prec, std::ios_base::fixed); }
inline std::string fmt(double v, int prec = 3) { return formatted(v, prec, {}); }
inline std::string sci(double v, int prec = 2) { return formatted(v, prec, std::ios_base::scientific); }
inline std::string pad(const std::string& s, std::size_t w) {
  return s.size() >= w ? s : std::string(w - s.size(), ' ') + s;
}
inline std::string padr(const std::string& s, std::size_t w) {
  return s.size() >= w ? s : s + std::string(w - s.size(), ' ');
}
// The nearest-rank q-quantile of v (core/quantile.h), NaN for none (a '-' in the tables,
// null in the JSON).
inline double percentile(const std::vector<double>& v, double q) {
  return v.empty() ? std::numeric_limits<double>::quiet_NaN() : quantile(v, q);
}
inline double median(const std::vector<double>& v) { return percentile(v, 0.5); }

// A finite number as JSON, anything else as null (JSON has no NaN or Inf).
inline nlohmann::json num(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); }

// User + system CPU seconds of this process, all its threads (PoCL's workers included).
inline double process_cpu_seconds() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return u.ru_utime.tv_sec + u.ru_utime.tv_usec * 1e-6 + u.ru_stime.tv_sec + u.ru_stime.tv_usec * 1e-6;
}

// `j` indented by `indent` into `path`; throws snapfit::Error when it cannot be written.
inline void write_json(const std::filesystem::path& path, const nlohmann::json& j, int indent = 2) {
  std::ofstream f(path);
  f << j.dump(indent) << "\n";
  if (!f) throw Error(path.string() + ": cannot write");
}

// Sets the kernel's arguments 0, 1, ... to `args`.
template <class... A>
void set_args(cl::Kernel& k, const A&... args) {
  cl_uint i = 0;
  (k.setArg(i++, args), ...);
}

// A CSV file: the header line, then one row per call; throws snapfit::Error when it cannot
// be written.
class CsvFile {
 public:
  CsvFile(const std::filesystem::path& path, const std::string& header) : path_(path), f_(path) {
    f_ << header << "\n";
  }
  // The values as std::ostream prints them, separated by commas.
  template <class First, class... Rest>
  void row(const First& first, const Rest&... rest) {
    f_ << first;
    ((f_ << ',' << rest), ...);
    f_ << "\n";
    if (!f_) throw Error(path_.string() + ": cannot write");
  }

 private:
  std::filesystem::path path_;
  std::ofstream f_;
};
// "s" in double quotes, for a CSV field that may hold commas.
inline std::string quoted(const std::string& s) { return "\"" + s + "\""; }
// A finite number as std::to_string writes it, anything else as an empty field.
inline std::string finite_or_empty(double v) { return std::isfinite(v) ? std::to_string(v) : std::string(); }

// A chart with its title, axis labels and log axes; series, markers and lines come after.
inline Chart make_chart(const std::string& title, const std::string& x_label, const std::string& y_label,
                        bool log_x = false, bool log_y = false) {
  Chart c;
  c.title = title;
  c.x_label = x_label;
  c.y_label = y_label;
  c.log_x = log_x;
  c.log_y = log_y;
  return c;
}

// The device's record in a report: `snapfit devices --json`'s fields (report/device_json.h)
// and two more the benchmarks report: driver (as driver_version) and platform_version.
inline nlohmann::json device_record(const DeviceInfo& info) {
  nlohmann::json j = device_json(info);
  j["driver"] = info.driver_version;
  j["platform_version"] = info.platform_version;
  return j;
}

// A run from construction to stop(): its date, the load average and the cores other
// processes kept busy, for the console and the report's header.
struct RunSpan {
  std::string date = now_iso(), load_start = read_loadavg(), load_end;
  CpuSample start = cpu_sample();
  double total_s = 0, others_run = 0;

  // "NAME: COMMAND", then the date and the load average at the start.
  void announce(const std::string& name, const std::string& command) const {
    std::cout << name << ": " << command << "\n  date " << date << ", load average at start: " << load_start << "\n";
  }
  void stop() {
    const CpuSample end = cpu_sample();
    load_end = read_loadavg();
    others_run = other_cores(start, end);
    total_s = std::chrono::duration<double>(end.at - start.at).count();
  }
  // "\nload average at end: E (start: S), total T s; ", before the benchmark's own summary.
  std::string end_text() const {
    return "\nload average at end: " + load_end + " (start: " + load_start + "), total " + fixed(total_s, 0) + " s; ";
  }
  // benchmark, command_line, date, quick, total_seconds, loadavg_start, loadavg_end, nproc
  // and the device's record (device_record above).
  nlohmann::json header(const std::string& name, const std::string& command, bool quick,
                        const DeviceInfo& device) const {
    return {{"benchmark", name},
            {"command_line", command},
            {"date", date},
            {"quick", quick},
            {"total_seconds", total_s},
            {"loadavg_start", load_start},
            {"loadavg_end", load_end},
            {"nproc", std::thread::hardware_concurrency()},
            {"device", device_record(device)}};
  }
};

// The variant of the exact reference: every one of `modes` modes of the exact-rotation
// product, made for each pose's own rotation (scheduler/tuning/accuracy.h); translation-only
// variants have no rotation and stay as they are.
inline QueryVariant exact_reference_variant(QueryVariant v, std::size_t modes) {
  if (v.translation_only) return v;
  v.rotation = RotationMethod::exact_product;
  v.product_update = ProductUpdate::each_query;
  v.product_modes = modes;
  return v;
}

// The exact reference at each pose (exact_reference_variant with every mode); `each` sees
// each result with its pose's index and the seconds it took.
inline std::vector<QueryResult> exact_references(
    const ComputeContext& ctx, const PairSpectra& spectra, const QueryVariant& variant, const std::vector<Pose>& poses,
    const std::function<void(std::size_t, const QueryResult&, double)>& each) {
  auto engine = make_query_engine(ctx, spectra, exact_reference_variant(variant, spectra.part1.rho.size()));
  engine->set_modes(engine->max_modes());
  std::vector<QueryResult> reference;
  for (const Pose& p : poses) {
    const auto t0 = std::chrono::steady_clock::now();
    reference.push_back(engine->query(p));
    each(reference.size() - 1, reference.back(), seconds_since(t0));
  }
  return reference;
}

// Seconds of `warm` + 1 full translational maps (engine/maps/full_map.h, all modes), each
// at next_rotation(): the first call's into `cold` while that is NaN (a repeated attempt
// is not cold), the others' returned.
inline std::vector<double> time_full_maps(const FftLibrary& fft, const ComputeContext& ctx, const PairSpectra& s,
                                          Interpolation interp, int warm, double& cold,
                                          const std::function<Eigen::Matrix3d()>& next_rotation) {
  std::vector<double> warm_s;
  for (int i = 0; i <= warm; ++i) {
    const Eigen::Matrix3d R = next_rotation();
    const auto t = std::chrono::steady_clock::now();
    const TranslationMap map = translational_energy_map(fft, ctx, s, R, interp, 0);
    const double sec = seconds_since(t);
    if (map.energy.size() != s.dims[0] * s.dims[1] * s.dims[2]) throw Error("full map: wrong size");
    if (i > 0)
      warm_s.push_back(sec);
    else if (std::isnan(cold))
      cold = sec;
  }
  return warm_s;
}

// DIR/charts.html: the benchmark's charts on one self-contained page (report/chart_spec.h),
// with the command, the date and the load average above them. Returns what was written, or
// why nothing was (a build with -DSNAPFIT_WEB_REPORT=OFF); perf/run_benchmarks.sh turns
// the page into charts.png with headless chromium where it can.
inline std::string write_charts(const std::filesystem::path& dir, const std::string& title, const std::string& command,
                                const std::vector<Chart>& charts) {
  if (!web_pages_available()) return "no charts.html (this build has -DSNAPFIT_WEB_REPORT=OFF)";
  write_chart_page((dir / "charts.html").string(), title,
                   {"command: " + command, "date: " + now_iso() + ", load average " + read_loadavg()}, charts);
  return (dir / "charts.html").string();
}

}  // namespace snapfit::bench
