#include "engine/query/rotated_product_query.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <cstring>
#include <mutex>
#include <thread>

#include "core/background_priority.h"
#include "core/subnormal_flush.h"
#include "core/thread_name.h"
#include "engine/query/line_kernel.h"
#include "engine/query/query_launch.h"
#include "engine/query/rotated_product.h"
#include "engine/query/so3_maps.h"
#include "engine/query/translation_lines.h"
#include "engine/runtime/cl_values.h"
#include "engine/spectra/mode_order.h"
#include "snapfit/error.h"

namespace snapfit {
namespace {

// Rotations closer than this (radians) share a product.
constexpr double kSameRotation = 1e-9;
// The worker extrapolates the rotation by at most this angle (radians).
constexpr double kMaxLead = 0.2;

class RotatedProductQuery final : public QueryEngine, private QueryHooks {
 public:
  RotatedProductQuery(const ComputeContext& ctx, const PairSpectra& spectra, QueryVariant variant,
                      const ProgramCacheConfig& cache)
      : variant_(variant), c2_(spectra.part2.centre) {
    if (variant.translation_only) throw Error("the exact rotation is for 6-DOF queries");
    const std::vector<std::size_t> order = mode_order(spectra);
    // Every mode by default: the product costs time in proportion to the m' in use only,
    // so the tuner may go as far as the device's frame allows.
    const std::size_t product_modes =
        variant.product_modes > 0 ? std::min(order.size(), variant.product_modes) : order.size();
    reach_ = mode_reach(spectra.dims, order);
    reach_.resize(product_modes);
    lines_ = build_translation_lines(spectra.dims, order,
                                     variant.fold_conjugate_pairs && spectra.conjugate_pairs() == 1, product_modes);
    product_ = std::make_unique<RotatedProduct>(ctx, spectra, lines_, cache);
    std::string options = " -D TRANSLATION_ONLY -D ROTATED_LINES";
    if (variant.force || variant.torque) options += " -D FORCE";  // the torque needs F (R c2 x F)
    launch_ = std::make_unique<QueryLaunch>(
        ctx, spectra, variant, reach_.back(), "rotated_lines", options,
        SharedQueryArgs{kLinePose, kLinePoses, kLinePoseCount, kLineGroupsPerPose, kLinePartials}, cache,
        static_cast<const QueryHooks*>(this));
    try {
      cl::Kernel& k = launch_->kernel();
      for (Slot& slot : slots_) slot.box = cl::Buffer(ctx.context, CL_MEM_READ_WRITE, product_->box_bytes());
      extras_ = cl::Buffer(ctx.context, CL_MEM_READ_ONLY, sizeof(cl_int4) * (kMaxUnpairedExtras + 1));
      k.setArg(kLineExtras, extras_);
      const Eigen::Vector3d inv = spectra.length.cwiseInverse();
      k.setArg(kLineInvLength, float4_of(inv));
      if (variant.product_update == ProductUpdate::background)
        worker_queue_ = cl::CommandQueue(ctx.context, ctx.device.device, 0);
    } catch (const cl::Error& e) {
      throw Error("cannot set up exact-rotation queries on " + launch_->device_name() + ": " + e.what() + " (error " +
                  std::to_string(e.err()) + ")");
    }
    select(product_modes);
    if (variant.product_update == ProductUpdate::background)
      worker_ = std::thread([this] {
        name_this_thread("snapfit-product");
        const SubnormalFlush flush;  // core/subnormal_flush.h: a pose at rest at the fit
        work();
      });
  }

  ~RotatedProductQuery() override {
    if (worker_.joinable()) {
      {
        std::lock_guard<std::mutex> lock(mutex_);
        stop_ = true;
      }
      wake_.notify_all();
      worker_.join();
    }
  }

  const QueryVariant& variant() const override { return variant_; }
  std::size_t max_modes() const override { return reach_.size(); }
  std::size_t modes() const override { return selection_.modes; }
  std::size_t evaluated_terms() const override { return selection_.nodes + selection_.extras.size(); }

  void set_modes(std::size_t m) override {
    const std::size_t clamped = std::clamp<std::size_t>(m, 1, max_modes());
    pending_modes_ = 0;
    if (clamped == selection_.modes) {
      target_modes_.store(clamped);
      return;
    }
    select(clamped);
  }

  // Background: a larger m' is the worker's to make a product for (the frame never
  // waits for one); the frame takes it when a product covering it is published.
  void request_modes(std::size_t m) override {
    const std::size_t clamped = std::clamp<std::size_t>(m, 1, max_modes());
    if (variant_.product_update != ProductUpdate::background || clamped <= selection_.modes) {
      set_modes(clamped);
      return;
    }
    pending_modes_ = clamped;
    target_modes_.store(clamped);
  }

  QueryResult query(const Pose& pose) override {
    QueryResult result;
    query_batch(&pose, 1, &result);
    return result;
  }

  using QueryEngine::query_batch;
  void query_batch(const Pose* poses, std::size_t count, QueryResult* results) override {
    if (variant_.product_update == ProductUpdate::each_query) {
      // Exact at every pose: one product per rotation, the poses in runs of one rotation.
      for (std::size_t first = 0; first < count;) {
        std::size_t end = first + 1;
        const Eigen::Quaterniond& q = poses[first].rotation;
        while (end < count && poses[end].rotation.coeffs() == q.coeffs()) ++end;
        if (poses[first].is_finite() && std::abs(q.norm() - 1.0) < 1e-3)
          make_product(q.normalized().toRotationMatrix(), selection_.modes, 0, launch_->queue());
        use_slot(0);
        launch_->evaluate(poses + first, end - first, results + first);
        first = end;
      }
      return;
    }
    // Background: the latest product; the worker hears of the pose for the next one.
    if (pending_modes_ > 0) take_pending_modes();
    int slot = published_.load();
    for (;;) {
      in_use_.store(slot);
      const int again = published_.load();
      if (again == slot) break;
      slot = again;
    }
    if (slot < 0) {  // no product yet: make the first one here (once)
      in_use_.store(-1);
      std::lock_guard<std::mutex> lock(product_mutex_);
      if (published_.load() < 0) {
        make_product(poses[0].rotation.normalized().toRotationMatrix(), selection_.modes, 0, launch_->queue());
        publish(0);
      }
      slot = published_.load();
      in_use_.store(slot);
    }
    use_slot(slot);
    launch_->evaluate(poses, count, results);
    in_use_.store(-1);
    if (count > 0 && poses[count - 1].is_finite()) tell_worker(poses[count - 1]);
  }

 private:
  struct Slot {
    cl::Buffer box;
    Eigen::Matrix3d R0 = Eigen::Matrix3d::Identity();
    std::size_t modes = 0;  // the product holds the first `modes` modes
    bool valid = false;
  };

  // The requested m' once the published product covers it (request_modes); never waits.
  // Every product made after the request covers it too (target_modes_).
  void take_pending_modes() {
    if (published_modes_.load() < pending_modes_) return;
    const std::size_t modes = pending_modes_;
    pending_modes_ = 0;
    select(modes, false);
  }

  // Makes slot `index` the product queries read (under product_mutex_).
  void publish(int index) {
    published_modes_.store(slots_[index].modes);
    published_.store(index);
  }

  // Selects and uploads the lines and extras for m' = modes. With `remake`, a published
  // product covering fewer modes is remade at once (the worker's rule remakes it too);
  // one covering at least the m' in use covers a smaller one, so a step down never waits.
  void select(std::size_t modes, bool remake = true) {
    const bool more = modes > selection_.modes;
    select_lines(lines_, modes, selection_);
    try {
      upload_line_selection(*launch_, selection_, reach_[modes - 1], records_, line_capacity_);
      // The extras as box nodes (the product holds their values).
      std::array<cl_int4, kMaxUnpairedExtras + 1> extras{};
      for (std::size_t e = 0; e < selection_.extras.size(); ++e) {
        const ExtraMode& x = selection_.extras[e];
        std::int16_t kxy[2], kzc[2];
        std::memcpy(kxy, &x.kxy, 4);
        std::memcpy(kzc, &x.kzc, 4);
        extras[e] = cl_int4{{static_cast<cl_int>(box_node(lines_, kxy[0], kxy[1], kzc[0])), x.kxy, x.kzc, 0}};
      }
      if (!selection_.extras.empty())
        launch_->queue().enqueueWriteBuffer(extras_, CL_TRUE, 0, sizeof(cl_int4) * selection_.extras.size(),
                                            extras.data());
    } catch (const cl::Error& e) {
      throw Error("cannot change m' on " + launch_->device_name() + ": " + e.what() + " (error " +
                  std::to_string(e.err()) + ")");
    }
    launch_->set_work(selection_.nodes, modes);
    target_modes_.store(modes);
    if (variant_.product_update == ProductUpdate::background && remake && more) {
      // A published product that covers fewer modes is remade now for the new m'.
      std::lock_guard<std::mutex> lock(product_mutex_);
      const int slot = published_.load();
      if (slot >= 0 && slots_[slot].modes < modes) {
        const int target = free_slot();
        make_product(slots_[slot].R0, modes, target, launch_->queue());
        publish(target);
      }
    }
  }

  // The product for R0 and the first `modes` modes into slot `index` (each_query: only
  // when it is not there yet).
  void make_product(const Eigen::Matrix3d& R0, std::size_t modes, int index, cl::CommandQueue& queue) {
    Slot& slot = slots_[index];
    if (variant_.product_update == ProductUpdate::each_query && slot.valid && slot.modes >= modes &&
        rotation_log(R0 * slot.R0.transpose()).norm() <= kSameRotation)
      return;
    product_->compute(queue, R0, std::max(modes, target_modes_.load()), slot.box);
    slot.R0 = R0;
    slot.modes = std::max(modes, target_modes_.load());
    slot.valid = true;
  }

  void use_slot(int index) {
    current_ = &slots_[index];
    try {
      launch_->kernel().setArg(kLineWeights, current_->box);
    } catch (const cl::Error& e) {
      throw Error("pose query failed on " + launch_->device_name() + ": " + e.what());
    }
  }

  // A slot neither published nor in use by a query.
  int free_slot() const {
    const int published = published_.load(), in_use = in_use_.load();
    for (int i = 0; i < int(slots_.size()); ++i)
      if (i != published && i != in_use) return i;
    return 0;  // unreachable with three slots
  }

  // QueryHooks: dtheta = log(R R0^T) in the pose's s0-s2; the torque from the rotation
  // sums, the exact derivative of the first-order energy.
  void encode(const Eigen::Matrix3d& R, cl_float16& packed) const override {
    const Eigen::Vector3d dtheta = rotation_log(R * current_->R0.transpose());
    for (int a = 0; a < 3; ++a) packed.s[a] = static_cast<float>(dtheta[a]);
  }
  void finish(const double sums[8], const Eigen::Matrix3d& R, const QueryVariant& variant,
              QueryResult& result) const override {
    result.score = {sums[0], sums[1]};
    result.energy = -sums[0];
    const Eigen::Vector3d force(sums[2], sums[3], sums[4]);
    if (variant.force) result.force = force;
    if (variant.torque) {
      const Eigen::Vector3d dtheta = rotation_log(R * current_->R0.transpose());
      result.torque = left_jacobian_inverse(dtheta).transpose() * Eigen::Vector3d(sums[5], sums[6], sums[7]) +
                      (R * c2_).cross(force);
    }
  }

  // Background: the frame's latest pose for the worker (a sequence lock: no waiting).
  void tell_worker(const Pose& pose) {
    const double now = std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
    const unsigned seq = pose_seq_.load();
    pose_seq_.store(seq + 1);  // odd: writing
    std::atomic_thread_fence(std::memory_order_release);
    latest_rotation_ = pose.rotation.normalized();
    latest_time_ = now;
    std::atomic_thread_fence(std::memory_order_release);
    pose_seq_.store(seq + 2);
    wake_.notify_one();
  }

  bool read_pose(Eigen::Quaterniond& q, double& time, unsigned& seq) {
    for (int tries = 0; tries < 100; ++tries) {
      const unsigned before = pose_seq_.load();
      if (before & 1u) continue;
      std::atomic_thread_fence(std::memory_order_acquire);
      q = latest_rotation_;
      time = latest_time_;
      std::atomic_thread_fence(std::memory_order_acquire);
      if (pose_seq_.load() == before) {
        seq = before;
        return true;
      }
    }
    return false;
  }

  // The worker: for each new pose, the rotation a product made now will be needed at
  // (the last rotation carried on at the measured rate for the time a product takes),
  // made into a free slot and published. Each round starts by yielding to the frame
  // (SCHED_IDLE), before any product is made.
  void work() {
    unsigned seen = 0;
    Eigen::Quaterniond previous = Eigen::Quaterniond::Identity();
    double previous_time = 0, product_seconds = 0;
    bool have_previous = false;
    for (;;) {
      yield_to_the_frame();
      {
        std::unique_lock<std::mutex> lock(mutex_);
        wake_.wait_for(lock, std::chrono::milliseconds(5), [&] { return stop_ || pose_seq_.load() != seen; });
        if (stop_) return;
      }
      Eigen::Quaterniond q;
      double time = 0;
      unsigned seq = 0;
      if (!read_pose(q, time, seq) || seq == seen) continue;
      seen = seq;
      Eigen::Vector3d lead = Eigen::Vector3d::Zero();
      if (have_previous && time > previous_time) {
        const Eigen::Vector3d rate =
            rotation_log(q.toRotationMatrix() * previous.toRotationMatrix().transpose()) / (time - previous_time);
        lead = rate * product_seconds;
        if (lead.norm() > kMaxLead) lead *= kMaxLead / lead.norm();
      }
      previous = q;
      previous_time = time;
      have_previous = true;
      const Eigen::Matrix3d predicted = rotation_exp(lead) * q.toRotationMatrix();
      std::lock_guard<std::mutex> lock(product_mutex_);
      const int published = published_.load();
      if (published >= 0 && slots_[published].modes >= target_modes_.load() &&
          rotation_log(predicted * slots_[published].R0.transpose()).norm() <= kSameRotation)
        continue;
      const int target = free_slot();
      const auto start = std::chrono::steady_clock::now();
      try {
        make_product(predicted, target_modes_.load(), target, worker_queue_);
      } catch (const Error&) {
        continue;  // the frame keeps the last product; the next pose tries again
      }
      product_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      publish(target);
    }
  }

  QueryVariant variant_;
  Eigen::Vector3d c2_;
  std::vector<int> reach_;  // max |k| of the modes [0, i]
  TranslationLines lines_;
  LineSelection selection_;
  std::unique_ptr<RotatedProduct> product_;
  std::unique_ptr<QueryLaunch> launch_;
  cl::Buffer records_, extras_;
  std::size_t line_capacity_ = 0;
  std::array<Slot, 3> slots_;
  const Slot* current_ = &slots_[0];
  std::atomic<int> published_{-1}, in_use_{-1};
  std::atomic<std::size_t> target_modes_{0};
  std::size_t pending_modes_ = 0;  // requested, waiting for a product that covers it (0: none)
  std::atomic<std::size_t> published_modes_{0};  // the modes the published product covers
  // Background mode.
  cl::CommandQueue worker_queue_;
  std::thread worker_;
  std::mutex mutex_, product_mutex_;
  std::condition_variable wake_;
  bool stop_ = false;
  std::atomic<unsigned> pose_seq_{0};
  Eigen::Quaterniond latest_rotation_ = Eigen::Quaterniond::Identity();
  double latest_time_ = 0;
};

}  // namespace

std::unique_ptr<QueryEngine> make_rotated_product_query(const ComputeContext& ctx, const PairSpectra& spectra,
                                                        const QueryVariant& variant, const ProgramCacheConfig& cache) {
  return std::make_unique<RotatedProductQuery>(ctx, spectra, variant, cache);
}

}  // namespace snapfit
