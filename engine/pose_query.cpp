#include "engine/pose_query.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <numeric>
#include <string>

#include "snapfit/error.h"
#include "engine/kernel_sources.h"
#include "engine/mode_order.h"
#include "engine/translation_lines.h"

namespace snapfit {

struct PoseQueryEngine::Impl {
  Impl(const ComputeContext& c, QueryVariant v) : ctx(c), variant(v) {}
  const ComputeContext& ctx;
  QueryVariant variant;
  // The engine's own in-order queue without profiling: a query is one kernel launch and
  // one small blocking read, not queued behind other stages' work on ctx.queue.
  cl::CommandQueue queue;
  Eigen::Vector3d c1, c2, half1, half2, length;
  std::size_t mode_total = 0, mode_count = 0;
  std::size_t wg = 64, max_groups = 4, modes_per_group = 4096;
  cl::Buffer modes, cube, poses, partials;
  // Translation only (engine/translation_lines.h): the weight box and line sets, the
  // selection for the current m' (uploaded before the next query when `lines_dirty`).
  TranslationLines lines;
  LineSelection selection;
  bool lines_dirty = false;
  cl::Buffer line_weights, line_records, line_extras;
  std::size_t line_capacity = 0;
  std::vector<int> table_half;  // max |k| over all axes of modes [0, i]: the phase tables' reach
  // 6-DOF records (a mode, or a folded conjugate pair): modes held by records [0, j], and
  // record j's first mode alone (weight W, unfolded).
  std::vector<std::size_t> record_modes;
  std::vector<cl_float4> first_of_record;
  std::vector<float> partial_host;
  // Part 2's spectra (host), the |w| of every mode in order, and the radius (in |w|)
  // the device cube currently covers.
  std::array<std::size_t, 3> dims{};
  std::vector<Complex> s2;
  std::array<std::vector<Complex>, 3> sq;
  std::vector<float> mode_radius;
  double cube_radius = -1;
  std::size_t pose_capacity = 0, partial_capacity = 0;
  cl::Kernel kernel;

  // Uploads the part of S2 (and SQ) that interpolation at |w'| <= radius can touch:
  // signed indices |i_a| <= ceil(radius L_a) + 2 (Catmull-Rom reaches 2 beyond floor),
  // sampled periodically. Grown with a margin, so m' changes rarely re-upload.
  void ensure_cube(double radius) {
    if (variant.translation_only || radius <= cube_radius) return;
    radius = std::min(radius * 1.25, double(mode_radius.back()));
    int half[3], n[3];
    for (int a = 0; a < 3; ++a) {
      half[a] = static_cast<int>(std::ceil(radius * length[a])) + 2;
      n[a] = 2 * half[a] + 2;
    }
    const int per_node = variant.torque ? 4 : 1;
    std::vector<Complex> data(static_cast<std::size_t>(n[0]) * n[1] * n[2] * per_node);
    auto wrap = [](long i, std::size_t m) { return static_cast<std::size_t>(((i % long(m)) + long(m)) % long(m)); };
    for (int z = 0; z < n[2]; ++z)
      for (int y = 0; y < n[1]; ++y)
        for (int x = 0; x < n[0]; ++x) {
          const std::size_t k = wrap(x - half[0], dims[0]) + dims[0] * (wrap(y - half[1], dims[1]) + dims[1] * wrap(z - half[2], dims[2]));
          Complex* node = &data[per_node * (static_cast<std::size_t>(x) + n[0] * (static_cast<std::size_t>(y) + n[1] * z))];
          node[0] = s2[k];
          if (variant.torque)
            for (int a = 0; a < 3; ++a) node[1 + a] = sq[a][k];
        }
    cl_float4 scale{{1.0f, 1.0f, 0.0f, 0.0f}};
    if (variant.half_cube) {
      // Half floats hold |x| <= 65504 with 11 significant bits: scale S2 and SQ each
      // by 1 / (largest component) so every stored value is at most 1 in magnitude.
      float largest[2] = {0, 0};
      for (std::size_t i = 0; i < data.size(); ++i) {
        float& l = largest[i % per_node == 0 ? 0 : 1];
        l = std::max({l, std::abs(data[i].real()), std::abs(data[i].imag())});
      }
      for (int j = 0; j < 2; ++j) {
        if (!(largest[j] > 0) || !std::isfinite(largest[j])) largest[j] = 1;
        scale.s[j] = largest[j];
      }
      std::vector<std::uint16_t> halves(2 * data.size());
      for (std::size_t i = 0; i < data.size(); ++i) {
        const float inv = 1.0f / largest[i % per_node == 0 ? 0 : 1];
        halves[2 * i] = float_to_half(data[i].real() * inv);
        halves[2 * i + 1] = float_to_half(data[i].imag() * inv);
      }
      cube = cl::Buffer(ctx.context, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, sizeof(std::uint16_t) * halves.size(), halves.data());
    } else {
      cube = cl::Buffer(ctx.context, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, sizeof(Complex) * data.size(), data.data());
    }
    kernel.setArg(1, cube);
    kernel.setArg(2, cl_int4{{n[0], n[1], n[2], 0}});
    kernel.setArg(3, cl_int4{{half[0], half[1], half[2], 0}});
    kernel.setArg(5, scale);
    cube_radius = radius;
  }

  void ensure_capacity(std::size_t pose_count, std::size_t groups) {
    if (pose_count > pose_capacity) {
      pose_capacity = std::max<std::size_t>(pose_count, 16);
      poses = cl::Buffer(ctx.context, CL_MEM_READ_ONLY, sizeof(cl_float16) * pose_capacity);
      kernel.setArg(variant.translation_only ? 6 : 7, poses);
    }
    if (groups > partial_capacity) {
      partial_capacity = std::max<std::size_t>(groups, 64);
      partials = cl::Buffer(ctx.context, CL_MEM_WRITE_ONLY, sizeof(float) * 8 * partial_capacity);
      kernel.setArg(variant.translation_only ? 11 : 12, partials);
    }
    partial_host.resize(8 * std::max(groups, partial_host.size() / 8));
  }

  // The records that hold the first mode_count modes: all of records [0, n), and when
  // mode_count cuts a pair, `extra` = the pair's first mode alone (else a zero weight).
  // Translation only: the number of lines selected.
  std::size_t record_count(cl_float4* extra) const {
    if (variant.translation_only) return selection.lines.size();
    const std::size_t n = static_cast<std::size_t>(
        std::upper_bound(record_modes.begin(), record_modes.end(), mode_count) - record_modes.begin());
    const std::size_t held = n == 0 ? 0 : record_modes[n - 1];
    *extra = cl_float4{};
    if (held < mode_count) *extra = first_of_record[n];
    return n;
  }

  // Translation only: selects the lines for the current m' (uploaded by upload_lines).
  void select_translation_lines() {
    select_lines(lines, mode_count, selection);
    lines_dirty = true;
  }

  // Translation only: writes the selected lines and extras before the next launch.
  void upload_lines() {
    if (!lines_dirty) return;
    const std::size_t n = std::max<std::size_t>(selection.lines.size(), 1);
    if (n > line_capacity) {
      line_capacity = std::max(n + n / 4, std::size_t(64));
      line_records = cl::Buffer(ctx.context, CL_MEM_READ_ONLY, sizeof(LineRecord) * line_capacity);
      kernel.setArg(1, line_records);
    }
    // Blocking: the host vectors change with the next set_modes.
    if (!selection.lines.empty())
      queue.enqueueWriteBuffer(line_records, CL_TRUE, 0, sizeof(LineRecord) * selection.lines.size(), selection.lines.data());
    if (!selection.extras.empty())
      queue.enqueueWriteBuffer(line_extras, CL_TRUE, 0, sizeof(ExtraMode) * selection.extras.size(), selection.extras.data());
    kernel.setArg(3, static_cast<cl_int>(selection.extras.size()));
    kernel.setArg(4, static_cast<cl_int>(selection.folded ? 1 : 0));
    lines_dirty = false;
  }

  // Work-groups per pose: one per `modes_per_group` units of work (6-DOF records, or
  // translation-only line nodes), at most max_groups (on a CPU device a work-group runs
  // on one core; more groups than cores only add overhead).
  std::size_t groups_per_pose(std::size_t work) const {
    return std::clamp<std::size_t>((work + modes_per_group - 1) / modes_per_group, 1, max_groups);
  }

  // Round to nearest even; subnormal halves kept (IEEE 754 binary16).
  static std::uint16_t float_to_half(float f) {
    std::uint32_t x;
    std::memcpy(&x, &f, 4);
    const auto sign = static_cast<std::uint16_t>((x >> 16) & 0x8000u);
    x &= 0x7fffffffu;
    if (x >= 0x7f800000u) return sign | 0x7c00u | (x > 0x7f800000u ? 0x200u : 0u);  // inf, nan
    if (x >= 0x477ff000u) return sign | 0x7c00u;                                     // rounds past 65504
    if (x < 0x38800000u) {                                                            // below 2^-14: subnormal
      float a;
      std::memcpy(&a, &x, 4);
      return sign | static_cast<std::uint16_t>(std::nearbyint(a * 16777216.0f));  // units of 2^-24
    }
    std::uint32_t h = ((x >> 23) - 112u) << 10 | ((x & 0x7fffffu) >> 13);
    const std::uint32_t rest = x & 0x1fffu;
    if (rest > 0x1000u || (rest == 0x1000u && (h & 1u))) ++h;  // a carry moves into the exponent correctly
    return static_cast<std::uint16_t>(sign | h);
  }

  // The kernel's pose: R row-major, then tau / L as a float pair (hi + lo).
  cl_float16 pack_pose(const Eigen::Matrix3d& R, const Eigen::Vector3d& tau) const {
    cl_float16 p{};
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) p.s[3 * r + c] = static_cast<float>(R(r, c));
    for (int a = 0; a < 3; ++a) {
      const double x = tau[a] / length[a];
      p.s[9 + a] = static_cast<float>(x);
      p.s[12 + a] = static_cast<float>(x - double(p.s[9 + a]));
    }
    return p;
  }
};

namespace {

// Rotation matrix of a unit quaternion, or false when the pose is unusable.
bool checked_rotation(const Pose& pose, Eigen::Matrix3d& R) {
  if (!pose.is_finite()) return false;
  const double norm = pose.rotation.norm();
  if (!(std::abs(norm - 1.0) < 1e-3)) return false;  // not a rotation: refuse rather than guess
  R = pose.rotation.normalized().toRotationMatrix();
  return true;
}

}  // namespace

PoseQueryEngine::PoseQueryEngine(const ComputeContext& ctx, const PairSpectra& spectra, QueryVariant variant,
                                 const ProgramCacheConfig& cache)
    : impl_(std::make_unique<Impl>(ctx, variant)) {
  Impl& m = *impl_;
  if (variant.torque && !spectra.torque) throw Error("the query variant needs torque, but the spectra have no torque terms");
  if (variant.torque && variant.translation_only) throw Error("a translation-only query has no torque");
  m.c1 = spectra.part1.centre;
  m.c2 = spectra.part2.centre;
  m.half1 = spectra.part1.half_extent;
  m.half2 = spectra.part2.half_extent;
  m.length = spectra.length;
  const auto& dims = spectra.dims;
  const std::size_t total = dims[0] * dims[1] * dims[2];
  for (std::size_t n : dims)
    if (n > 65534) throw Error("FFT grid axis of " + std::to_string(n) + " points is beyond the query kernel's 16-bit mode indices");

  // Every node, by increasing |w| (the low-pass ball grows with m'), conjugate pairs
  // adjacent (engine/mode_order.h).
  const std::vector<std::size_t> order = mode_order(spectra);
  auto mode_k = [&](std::size_t k) { return signed_node(dims, k); };
  m.table_half.resize(total);
  m.mode_radius.resize(total);
  int reach = 0;
  for (std::size_t i = 0; i < total; ++i) {
    const std::array<int, 3> k = mode_k(order[i]);
    reach = std::max({reach, std::abs(k[0]), std::abs(k[1]), std::abs(k[2])});
    m.table_half[i] = reach;
    const float wx = float(spectra.frequency(0, order[i] % dims[0])),
                wy = float(spectra.frequency(1, (order[i] / dims[0]) % dims[1])),
                wz = float(spectra.frequency(2, order[i] / (dims[0] * dims[1])));
    m.mode_radius[i] = std::sqrt(wx * wx + wy * wy + wz * wz);
  }

  // dw = 1 / (L_x L_y L_z) (DESIGN.md), folded into the weights. One float4 per record:
  // (Re W, Im W, (kx, ky) as two shorts, (kz, folded) as two shorts), w_k = k / L in
  // the kernel. With a real correlation (PairSpectra::conjugate_pairs) the 6-DOF terms
  // at w and -w are complex conjugates: one record holds the pair, weight 2 W, and adds
  // only to the real parts (Re f, F, T; the pair's Im f is 0). Records follow the mode
  // order; record_modes[j] is the number of modes the first j + 1 records hold.
  const double dw = 1.0 / (spectra.length.x() * spectra.length.y() * spectra.length.z());
  auto record = [&](std::size_t k, Complex weight, bool folded) {
    const std::array<int, 3> kk = mode_k(k);
    const cl_short2 kxy{{cl_short(kk[0]), cl_short(kk[1])}}, kzf{{cl_short(kk[2]), cl_short(folded ? 1 : 0)}};
    cl_float4 out;
    out.s[0] = weight.real();
    out.s[1] = weight.imag();
    std::memcpy(&out.s[2], &kxy, 4);
    std::memcpy(&out.s[3], &kzf, 4);
    return out;
  };
  const bool fold = !variant.translation_only && variant.fold_conjugate_pairs && spectra.conjugate_pairs() == 1;
  std::vector<cl_float4> mode_data;
  if (!variant.translation_only) {
    mode_data.reserve(total);
    m.record_modes.reserve(total);
    m.first_of_record.reserve(total);
    for (std::size_t i = 0; i < total;) {
      const std::size_t k = order[i];
      const std::size_t neg = negated_node(dims, k);
      const Complex weight = spectra.part1.rho[k] * static_cast<float>(dw);
      const bool pair = fold && neg != kNoNode && neg != k && i + 1 < total && order[i + 1] == neg;
      mode_data.push_back(record(k, pair ? 2.0f * weight : weight, pair));
      m.first_of_record.push_back(record(k, weight, false));  // the mode alone, for an m' that cuts the pair
      i += pair ? 2 : 1;
      m.record_modes.push_back(i);
    }
  }
  // Translation only: the product W_k in a dense box of x-lines, and the lines that hold
  // each m' (engine/translation_lines.h).
  if (variant.translation_only) m.lines = build_translation_lines(spectra, order, variant.fold_conjugate_pairs);
  m.mode_total = total;
  m.mode_count = total;

  try {
    m.queue = cl::CommandQueue(ctx.context, ctx.device.device, 0);
    m.dims = dims;
    if (!variant.translation_only) {
      m.s2 = spectra.part2.rho;
      if (variant.torque) m.sq = spectra.part2.moments;
    }
    // Launch shape: 64 work-items, one group per 64 modes up to 2 per compute unit. On
    // PoCL's CPU device 1-256 work-items and 1-4 groups per pose measured alike at
    // m' = 32,768 (a work-group runs as a loop on one core); SNAPFIT_QUERY_WG, _GROUPS and
    // _MODES_PER_GROUP override them for measurements on other devices.
    auto env = [](const char* name, std::size_t fallback) {
      const char* v = std::getenv(name);
      return v && *v ? static_cast<std::size_t>(std::strtoul(v, nullptr, 10)) : fallback;
    };
    const std::size_t wg_target = env("SNAPFIT_QUERY_WG", 64);
    m.wg = 1;
    while (m.wg * 2 <= std::min<std::size_t>(wg_target, ctx.device.info.max_work_group_size)) m.wg *= 2;
    m.max_groups = std::max<std::size_t>(1, env("SNAPFIT_QUERY_GROUPS", std::max<std::size_t>(2, 2 * ctx.device.info.compute_units)));
    m.modes_per_group = std::max<std::size_t>(1, env("SNAPFIT_QUERY_MODES_PER_GROUP", m.wg));
    // Phase tables for |k| <= reach on every axis, in local memory.
    const std::size_t local_bytes = 3 * (2 * std::size_t(reach) + 17) * sizeof(Complex) + 8 * sizeof(float) * m.wg;
    if (local_bytes > ctx.device.info.local_memory_bytes)
      throw Error("FFT grid of " + std::to_string(dims[0]) + "x" + std::to_string(dims[1]) + "x" + std::to_string(dims[2]) +
                  " needs " + std::to_string(local_bytes) + " bytes of local memory for the query kernel's phase tables; " +
                  ctx.device.info.name + " has " + std::to_string(ctx.device.info.local_memory_bytes));
    std::string options = "-cl-std=CL1.2 -D WG_SIZE=" + std::to_string(m.wg) + " -D MAX_HALF=" + std::to_string(reach);
    if (variant.force) options += " -D FORCE";
    if (variant.torque) options += " -D TORQUE";
    if (variant.translation_only) options += " -D TRANSLATION_ONLY";
    if (!variant.translation_only && variant.interpolation == Interpolation::tricubic) options += " -D TRICUBIC";
    if (!variant.translation_only && variant.half_cube) options += " -D HALF_CUBE";
    m.kernel = cl::Kernel(build_program(ctx, "pose_query", kernel_source("spectrum_sample") + kernel_source("pose_query"), options, cache).program,
                          variant.translation_only ? "translation_lines" : "pose_query");
    const cl_float4 inv_length{{float(1.0 / spectra.length.x()), float(1.0 / spectra.length.y()), float(1.0 / spectra.length.z()), 0.0f}};
    if (variant.translation_only) {
      const auto& box = m.lines.weights;
      m.line_weights = cl::Buffer(ctx.context, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, sizeof(Complex) * box.size(),
                                  const_cast<Complex*>(box.data()));
      m.line_extras = cl::Buffer(ctx.context, CL_MEM_READ_ONLY, sizeof(ExtraMode) * (kMaxUnpairedExtras + 1));
      m.kernel.setArg(0, m.line_weights);
      m.kernel.setArg(2, m.line_extras);
      m.kernel.setArg(5, cl_float16{});
      m.kernel.setArg(12, inv_length);
      m.select_translation_lines();
    } else {
      m.modes = cl::Buffer(ctx.context, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, sizeof(cl_float4) * mode_data.size(), mode_data.data());
      m.kernel.setArg(0, m.modes);
      m.kernel.setArg(4, cl_float4{{float(spectra.length.x()), float(spectra.length.y()), float(spectra.length.z()), 0.0f}});
      m.kernel.setArg(5, cl_float4{{1.0f, 1.0f, 0.0f, 0.0f}});
      m.kernel.setArg(6, cl_float16{});
      m.kernel.setArg(13, inv_length);
      m.kernel.setArg(14, cl_float4{});
    }
    m.ensure_capacity(1, m.max_groups);
  } catch (const cl::Error& e) {
    throw Error("cannot set up pose queries on " + ctx.device.info.name + ": " + e.what() + " (error " +
                std::to_string(e.err()) + ")");
  }
}

PoseQueryEngine::~PoseQueryEngine() = default;

std::size_t PoseQueryEngine::max_modes() const { return impl_->mode_total; }
std::size_t PoseQueryEngine::modes() const { return impl_->mode_count; }
std::size_t PoseQueryEngine::evaluated_terms() const {
  // Translation only: the nodes of the selected line intervals (folded: one per pair)
  // and the extra single terms.
  if (impl_->variant.translation_only) return impl_->selection.nodes + impl_->selection.extras.size();
  cl_float4 extra{};
  const std::size_t records = impl_->record_count(&extra);
  return records + (extra.s[0] != 0.0f || extra.s[1] != 0.0f ? 1 : 0);
}
void PoseQueryEngine::set_modes(std::size_t m) {
  const std::size_t clamped = std::clamp<std::size_t>(m, 1, impl_->mode_total);
  if (clamped == impl_->mode_count) return;
  impl_->mode_count = clamped;
  if (impl_->variant.translation_only) impl_->select_translation_lines();
  impl_->ensure_cube(impl_->mode_radius[impl_->mode_count - 1]);
}

QueryResult PoseQueryEngine::query(const Pose& pose) {
  std::vector<QueryResult> one = query_batch(std::vector<Pose>(1, pose));
  return one.front();
}

std::vector<QueryResult> PoseQueryEngine::query_batch(const std::vector<Pose>& poses) {
  Impl& m = *impl_;
  const auto start = std::chrono::steady_clock::now();
  std::vector<QueryResult> results(poses.size());
  std::vector<cl_float16> packed;
  packed.reserve(poses.size());
  std::vector<std::size_t> slot;  // poses sent to the device, by index
  std::vector<Eigen::Matrix3d> rotations;
  slot.reserve(poses.size());
  rotations.reserve(poses.size());
  for (std::size_t i = 0; i < poses.size(); ++i) {
    results[i].modes = m.mode_count;
    Eigen::Matrix3d R;
    if (!checked_rotation(poses[i], R) || (m.variant.translation_only && !R.isIdentity(1e-6))) {
      results[i].flags |= query_bad_pose;
      continue;
    }
    // tau = t + R c2 - c1: the offset between the two centred boxes.
    const Eigen::Vector3d tau = poses[i].translation + R * m.c2 - m.c1;
    // The periodic sum aliases once part 2's box reaches an image of part 1's box.
    const Eigen::Vector3d reach = m.half1 + R.cwiseAbs() * m.half2;
    if (((tau.cwiseAbs() + reach).array() > m.length.array()).any()) {
      results[i].flags |= query_outside_grid;
      continue;
    }
    packed.push_back(m.pack_pose(R, tau));
    slot.push_back(i);
    rotations.push_back(R);
  }
  if (!slot.empty()) {
    cl_float4 extra{};
    const std::size_t records = m.record_count(&extra);
    const std::size_t groups_per_pose = m.groups_per_pose(m.variant.translation_only ? m.selection.nodes : records);
    const std::size_t groups = groups_per_pose * slot.size();
    try {
      m.ensure_capacity(slot.size(), groups);
      m.ensure_cube(m.mode_radius[m.mode_count - 1]);
      if (m.variant.translation_only) m.upload_lines();
      // Argument numbers: pose_query, or translation_lines 1 lower (kernels/pose_query.cl).
      const cl_uint shift = m.variant.translation_only ? 1 : 0;
      if (slot.size() == 1) {
        m.kernel.setArg(6 - shift, packed[0]);  // one pose: an argument, no buffer write
      } else {
        m.queue.enqueueWriteBuffer(m.poses, CL_FALSE, 0, sizeof(cl_float16) * packed.size(), packed.data());
      }
      m.kernel.setArg(8 - shift, static_cast<cl_int>(slot.size()));
      m.kernel.setArg(9 - shift, static_cast<cl_int>(records));
      if (!m.variant.translation_only) m.kernel.setArg(14, extra);
      m.kernel.setArg(10 - shift, static_cast<cl_int>(groups_per_pose));
      m.kernel.setArg(11 - shift, static_cast<cl_int>(m.table_half[m.mode_count - 1]));
      m.queue.enqueueNDRangeKernel(m.kernel, cl::NullRange, cl::NDRange(groups * m.wg), cl::NDRange(m.wg));
      m.queue.enqueueReadBuffer(m.partials, CL_TRUE, 0, sizeof(float) * 8 * groups, m.partial_host.data());
      const std::vector<float>& partial = m.partial_host;
      for (std::size_t s = 0; s < slot.size(); ++s) {
        double sum[8] = {0, 0, 0, 0, 0, 0, 0, 0};
        for (std::size_t g = 0; g < groups_per_pose; ++g)
          for (int j = 0; j < 8; ++j) sum[j] += partial[8 * (s * groups_per_pose + g) + j];
        QueryResult& r = results[slot[s]];
        r.score = {sum[0], sum[1]};
        r.energy = -sum[0];  // E = -Re f
        if (m.variant.force) r.force = Eigen::Vector3d(sum[2], sum[3], sum[4]);
        if (m.variant.torque) r.torque = rotations[s] * Eigen::Vector3d(sum[5], sum[6], sum[7]);  // to part 1's frame
      }
    } catch (const cl::Error& e) {
      throw Error("pose query failed on " + m.ctx.device.info.name + ": " + e.what() + " (error " +
                  std::to_string(e.err()) + ")");
    }
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  for (QueryResult& r : results) r.seconds = seconds / std::max<std::size_t>(1, poses.size());
  return results;
}

}  // namespace snapfit
