#include "engine/query/six_dof_query.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "core/half_float.h"
#include "engine/query/query_launch.h"
#include "engine/runtime/cl_values.h"
#include "engine/runtime/compute_context.h"
#include "engine/spectra/mode_order.h"
#include "snapfit/error.h"

namespace snapfit {
namespace {

// Arguments of the pose_query kernel (kernels/pose_query.cl), in order.
enum PoseQueryArg : cl_uint {
  kRecords = 0,    // global float4*: the mode records in mode order
  kCube,           // global Sample*: part 2's spectrum near the low-pass ball
  kCubeDims,       // int4
  kCubeOffset,     // int4: cube index of signed frequency index 0
  kLength,         // float4: L
  kCubeScale,      // float4: the half cube's scales (S2, SQ)
  kPose,           // float16
  kPoses,          // global float16*
  kPoseCount,      // int
  kRecordCount,    // int
  kGroupsPerPose,  // int
  kTableHalf,      // int
  kPartials,       // global float*
  kInvLength,      // float4: 1 / L
  kExtraMode,      // float4: the first mode of a pair that m' cuts (weight 0 otherwise)
  kBandStarts,     // int2: the first records beyond m'/4 and m'/2 (the error estimate's bands)
};

// The 6-DOF sum over interpolated, rotated spectra (seed 000 eq. 10-12). Each record is
// a mode or, with a real correlation folded, a conjugate pair w, -w: one float4
// (Re W, Im W, (kx, ky) and (kz, folded) as shorts) with W = S1(w_k) dw, twice that
// for a pair, which adds to the real outputs only (its Im f is 0).
class SixDofQuery final : public QueryEngine, private QueryHooks {
 public:
  SixDofQuery(const ComputeContext& ctx, const PairSpectra& spectra, QueryVariant variant,
              const ProgramCacheConfig& cache)
      : variant_(variant), dims_(spectra.dims), length_(spectra.length), c2_(spectra.part2.centre) {
    const std::vector<std::size_t> order = mode_order(spectra);
    const std::size_t total = order.size();
    reach_ = mode_reach(dims_, order);
    mode_radius_.resize(total);
    for (std::size_t i = 0; i < total; ++i) {
      const std::size_t k = order[i];
      const float wx = float(spectra.frequency(0, k % dims_[0])),
                  wy = float(spectra.frequency(1, (k / dims_[0]) % dims_[1])),
                  wz = float(spectra.frequency(2, k / (dims_[0] * dims_[1])));
      mode_radius_[i] = std::sqrt(wx * wx + wy * wy + wz * wz);
    }
    s2_ = spectra.part2.rho;

    // dw = 1 / (L_x L_y L_z) (docs/design.md), folded into the weights. Records follow
    // the mode order; record_modes_[j] is the number of modes records [0, j] hold.
    const double dw = 1.0 / (length_.x() * length_.y() * length_.z());
    const bool fold = variant.fold_conjugate_pairs && spectra.conjugate_pairs() == 1;
    std::vector<cl_float4> records;
    records.reserve(total);
    record_modes_.reserve(total);
    first_of_record_.reserve(total);
    for (std::size_t i = 0; i < total;) {
      const std::size_t k = order[i], neg = negated_node(dims_, k);
      const Complex weight = spectra.part1.rho[k] * static_cast<float>(dw);
      const bool pair = fold && neg != kNoNode && neg != k && i + 1 < total && order[i + 1] == neg;
      records.push_back(record(k, pair ? 2.0f * weight : weight, pair));
      first_of_record_.push_back(record(k, weight, false));  // the mode alone, for an m' that cuts the pair
      i += pair ? 2 : 1;
      record_modes_.push_back(i);
    }

    std::string options;
    if (variant.force || variant.torque) options += " -D FORCE";  // the torque needs F (R c2 x F)
    if (variant.torque) options += " -D TORQUE";
    if (variant.interpolation == Interpolation::tricubic) options += " -D TRICUBIC";
    if (variant.half_cube) options += " -D HALF_CUBE";
    launch_ = std::make_unique<QueryLaunch>(ctx, spectra, variant, reach_.back(), "pose_query", options,
                                            SharedQueryArgs{kPose, kPoses, kPoseCount, kGroupsPerPose, kPartials},
                                            cache, static_cast<const QueryHooks*>(this));
    try {
      cl::Kernel& k = launch_->kernel();
      records_ = cl::Buffer(launch_->context(), CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR,
                            sizeof(cl_float4) * records.size(), records.data());
      k.setArg(kRecords, records_);
      k.setArg(kLength, float4_of(length_));
      k.setArg(kCubeScale, cl_float4{{1.0f, 1.0f, 0.0f, 0.0f}});
      k.setArg(kInvLength, float4_of(length_.cwiseInverse()));
    } catch (const cl::Error& e) {
      throw_device_error("cannot set up pose queries", launch_->device_name(), e);
    }
    select_modes(total);  // the cube follows on the first query or set_modes
  }

  const QueryVariant& variant() const override { return variant_; }
  std::size_t max_modes() const override { return mode_radius_.size(); }
  std::size_t modes() const override { return mode_count_; }
  std::size_t evaluated_terms() const override { return record_count_ + (cut_pair_ ? 1 : 0); }

  void set_modes(std::size_t m) override {
    const std::size_t clamped = std::clamp<std::size_t>(m, 1, max_modes());
    if (clamped != mode_count_) select_modes(clamped);
    upload_cube();
  }

  QueryResult query(const Pose& pose) override {
    upload_cube();
    QueryResult result;
    launch_->evaluate(&pose, 1, &result);
    return result;
  }
  using QueryEngine::query_batch;
  void query_batch(const Pose* poses, std::size_t count, QueryResult* results) override {
    upload_cube();
    launch_->evaluate(poses, count, results);
  }

 private:
  void select_modes(std::size_t modes) {
    mode_count_ = modes;
    // The records that hold the first m' modes: all of records [0, n), and when m' cuts a
    // pair, the pair's first mode alone as the extra mode.
    const auto records_within = [&](std::size_t m) {
      return static_cast<std::size_t>(std::upper_bound(record_modes_.begin(), record_modes_.end(), m) -
                                      record_modes_.begin());
    };
    record_count_ = records_within(mode_count_);
    const std::size_t held = record_count_ == 0 ? 0 : record_modes_[record_count_ - 1];
    cut_pair_ = held < mode_count_;
    try {
      cl::Kernel& k = launch_->kernel();
      k.setArg(kRecordCount, static_cast<cl_int>(record_count_));
      k.setArg(kBandStarts, cl_int2{{static_cast<cl_int>(records_within(mode_count_ / 4)),
                                     static_cast<cl_int>(records_within(mode_count_ / 2))}});
      k.setArg(kExtraMode, cut_pair_ ? first_of_record_[record_count_] : cl_float4{});
      k.setArg(kTableHalf, static_cast<cl_int>(reach_[mode_count_ - 1]));
    } catch (const cl::Error& e) {
      throw_device_error("cannot change m'", launch_->device_name(), e);
    }
    launch_->set_work(record_count_, mode_count_);
  }

  // The cube for the current m' (a no-op once it covers it).
  void upload_cube() {
    if (mode_radius_[mode_count_ - 1] <= cube_radius_) return;
    try {
      ensure_cube(mode_radius_[mode_count_ - 1]);
    } catch (const cl::Error& e) {
      throw_device_error("cannot upload part 2's spectrum", launch_->device_name(), e);
    }
  }

  cl_float4 record(std::size_t k, Complex weight, bool folded) const {
    const std::array<int, 3> kk = signed_node(dims_, k);
    const cl_short2 kxy{{cl_short(kk[0]), cl_short(kk[1])}}, kzf{{cl_short(kk[2]), cl_short(folded ? 1 : 0)}};
    cl_float4 out;
    out.s[0] = weight.real();
    out.s[1] = weight.imag();
    std::memcpy(&out.s[2], &kxy, 4);
    std::memcpy(&out.s[3], &kzf, 4);
    return out;
  }

  // QueryHooks: the kernel's torque sums are in part 2's frame, about its box centre.
  void finish(const double sums[8], const Eigen::Matrix3d& R, const QueryVariant& variant,
              QueryResult& result) const override {
    fill_result(sums, R, variant, result);
    if (variant.torque) result.torque += (R * c2_).cross(Eigen::Vector3d(sums[2], sums[3], sums[4]));
  }

  // Uploads the part of S2 that interpolation at |w'| <= radius can touch:
  // signed indices |i_a| <= ceil(radius L_a) + 2 (Catmull-Rom reaches 2 beyond floor),
  // sampled periodically. Grown with a margin, so m' changes rarely re-upload.
  void ensure_cube(double radius) {
    if (radius <= cube_radius_) return;
    radius = std::min(radius * 1.25, double(mode_radius_.back()));
    int half[3], n[3];
    for (int a = 0; a < 3; ++a) {
      half[a] = static_cast<int>(std::ceil(radius * length_[a])) + 2;
      n[a] = 2 * half[a] + 2;
    }
    std::vector<Complex> data(static_cast<std::size_t>(n[0]) * n[1] * n[2]);
    auto wrap = [](long i, std::size_t m) { return static_cast<std::size_t>(((i % long(m)) + long(m)) % long(m)); };
    for (int z = 0; z < n[2]; ++z)
      for (int y = 0; y < n[1]; ++y)
        for (int x = 0; x < n[0]; ++x) {
          const std::size_t k = wrap(x - half[0], dims_[0]) +
                                dims_[0] * (wrap(y - half[1], dims_[1]) + dims_[1] * wrap(z - half[2], dims_[2]));
          data[static_cast<std::size_t>(x) + n[0] * (static_cast<std::size_t>(y) + n[1] * z)] = s2_[k];
        }
    cl_float4 scale{{1.0f, 1.0f, 0.0f, 0.0f}};
    if (variant_.half_cube) {
      // Half floats hold |x| <= 65504 with 11 significant bits: scale S2 by 1 / (largest
      // component) so every stored value is at most 1 in magnitude.
      float largest = 0;
      for (const Complex& c : data) largest = std::max({largest, std::abs(c.real()), std::abs(c.imag())});
      if (!(largest > 0) || !std::isfinite(largest)) largest = 1;
      scale.s[0] = largest;
      std::vector<std::uint16_t> halves(2 * data.size());
      const float inv = 1.0f / largest;
      for (std::size_t i = 0; i < data.size(); ++i) {
        halves[2 * i] = float_to_half(data[i].real() * inv);
        halves[2 * i + 1] = float_to_half(data[i].imag() * inv);
      }
      cube_ = cl::Buffer(launch_->context(), CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR,
                         sizeof(std::uint16_t) * halves.size(), halves.data());
    } else {
      cube_ = cl::Buffer(launch_->context(), CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, sizeof(Complex) * data.size(),
                         data.data());
    }
    cl::Kernel& k = launch_->kernel();
    k.setArg(kCube, cube_);
    k.setArg(kCubeDims, cl_int4{{n[0], n[1], n[2], 0}});
    k.setArg(kCubeOffset, cl_int4{{half[0], half[1], half[2], 0}});
    k.setArg(kCubeScale, scale);
    cube_radius_ = radius;
  }

  QueryVariant variant_;
  std::array<std::size_t, 3> dims_;
  Eigen::Vector3d length_, c2_;
  std::vector<int> reach_;          // max |k| of the modes [0, i]: the phase tables' reach
  std::vector<float> mode_radius_;  // |w| of every mode, in order
  std::vector<std::size_t> record_modes_;
  std::vector<cl_float4> first_of_record_;
  // Part 2's spectrum (host), for the cube; the |w| radius the device cube covers.
  std::vector<Complex> s2_;
  double cube_radius_ = -1;
  std::unique_ptr<QueryLaunch> launch_;
  cl::Buffer records_, cube_;
  std::size_t mode_count_ = 0, record_count_ = 0;
  bool cut_pair_ = false;
};

}  // namespace

std::unique_ptr<QueryEngine> make_six_dof_query(const ComputeContext& ctx, const PairSpectra& spectra,
                                                const QueryVariant& variant, const ProgramCacheConfig& cache) {
  return std::make_unique<SixDofQuery>(ctx, spectra, variant, cache);
}

}  // namespace snapfit
