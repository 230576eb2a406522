#include "engine/query/split_query.h"

#include <chrono>
#include <condition_variable>
#include <mutex>
#include <thread>

#include "core/background_priority.h"
#include "core/subnormal_flush.h"
#include "core/thread_name.h"
#include "engine/query/near_field.h"
#include "engine/query/query_engine.h"
#include "engine/query/so3_maps.h"
#include "snapfit/error.h"

namespace snapfit {
namespace {

// The near part at one pose, and the error its first-order form had at that pose when
// carried from the evaluation before.
struct NearSnapshot {
  Eigen::Vector3d t0 = Eigen::Vector3d::Zero();
  Eigen::Matrix3d R0 = Eigen::Matrix3d::Identity();
  NearWrench near;
  ErrorEstimate staleness;
};

// The near part's first-order form about the snapshot's pose, at (t, R).
NearWrench carried(const NearSnapshot& s, const Eigen::Vector3d& t, const Eigen::Matrix3d& R) {
  const Eigen::Vector3d theta = rotation_log(R * s.R0.transpose());
  NearWrench w;
  w.energy = s.near.energy - s.near.force.dot(t - s.t0) - s.near.torque.dot(theta);
  w.force = s.near.force;
  w.torque = left_jacobian_inverse(theta).transpose() * s.near.torque;
  return w;
}

class SplitQuery final : public QueryEngine {
 public:
  SplitQuery(const ComputeContext& ctx, const PairSpectra& spectra, const QueryVariant& variant,
             const ProgramCacheConfig& cache)
      : variant_(variant), near_(spectra.near) {
    if (variant.translation_only) throw Error("the near-far split is for 6-DOF queries");
    if (!near_)
      throw Error(
          "the near-far split needs spectra made with a near field (a 6-DOF pair whose spectra come from both "
          "grids, PairOptions::near_field)");
    QueryVariant far = variant;
    far.near_far = false;
    far_ = make_query_engine(ctx, far_spectra(spectra, *near_), far, cache);
    if (variant.product_update == ProductUpdate::background)
      worker_ = std::thread([this] {
        name_this_thread("snapfit-near");
        const SubnormalFlush flush;  // core/subnormal_flush.h: a pose at rest at the fit
        work();
      });
  }

  ~SplitQuery() override {
    if (worker_.joinable()) {
      {
        std::lock_guard<std::mutex> lock(pose_mutex_);
        stop_ = true;
      }
      wake_.notify_all();
      worker_.join();
    }
  }

  const QueryVariant& variant() const override { return variant_; }
  std::size_t max_modes() const override { return far_->max_modes(); }
  std::size_t modes() const override { return far_->modes(); }
  std::size_t evaluated_terms() const override { return far_->evaluated_terms(); }
  void set_modes(std::size_t m) override { far_->set_modes(m); }
  void request_modes(std::size_t m) override { far_->request_modes(m); }

  QueryResult query(const Pose& pose) override {
    QueryResult result;
    query_batch(&pose, 1, &result);
    return result;
  }

  using QueryEngine::query_batch;
  void query_batch(const Pose* poses, std::size_t count, QueryResult* results) override {
    far_->query_batch(poses, count, results);
    for (std::size_t i = 0; i < count; ++i)
      if (results[i].flags == query_ok) add_near(poses[i], results[i]);
  }

 private:
  void add_near(const Pose& pose, QueryResult& r) {
    const Eigen::Matrix3d R = pose.rotation.normalized().toRotationMatrix();
    NearWrench n;
    if (variant_.product_update == ProductUpdate::each_query) {
      const auto start = std::chrono::steady_clock::now();
      n = near_wrench(*near_, pose);
      r.seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    } else {
      tell_worker(pose);
      if (!refresh_snapshot()) {
        // No near part yet (the first few ms): the far part alone, which nothing vouches for.
        r.error_estimate.energy += std::abs(r.energy);
        r.error_estimate.force += r.force.norm();
        r.error_estimate.torque += r.torque.norm();
        return;
      }
      n = carried(frame_snapshot_, pose.translation, R);
      n.left_out = frame_snapshot_.near.left_out;
      r.error_estimate.energy += frame_snapshot_.staleness.energy;
      r.error_estimate.force += frame_snapshot_.staleness.force;
      r.error_estimate.torque += frame_snapshot_.staleness.torque;
    }
    // What the near part's kept nodes leave out.
    r.error_estimate.energy += n.left_out.energy;
    r.error_estimate.force += n.left_out.force;
    r.error_estimate.torque += n.left_out.torque;
    r.energy += n.energy;
    r.force += n.force;
    r.torque += n.torque;
  }

  // The frame's copy of the worker's latest snapshot; false until the worker has made
  // one (the frame never waits for it).
  bool refresh_snapshot() {
    std::unique_lock<std::mutex> lock(snapshot_mutex_, std::try_to_lock);
    if (lock.owns_lock() && published_) {
      frame_snapshot_ = snapshot_;
      have_frame_snapshot_ = true;
    }
    return have_frame_snapshot_;
  }

  void tell_worker(const Pose& pose) {
    std::unique_lock<std::mutex> lock(pose_mutex_, std::try_to_lock);
    if (!lock.owns_lock()) return;  // the worker is reading it: the next frame tells
    latest_ = pose;
    ++pose_seq_;
    lock.unlock();
    wake_.notify_one();
  }

  // For each new pose queried: the near part there, published with the error the
  // previous snapshot's first-order form had at it.
  void work() {
    unsigned seen = 0;
    for (;;) {
      yield_to_the_frame();
      Pose pose;
      {
        std::unique_lock<std::mutex> lock(pose_mutex_);
        wake_.wait_for(lock, std::chrono::milliseconds(5), [&] { return stop_ || pose_seq_ != seen; });
        if (stop_) return;
        if (pose_seq_ == seen) continue;
        seen = pose_seq_;
        pose = latest_;
      }
      NearSnapshot previous;
      bool have_previous = false;
      {
        std::lock_guard<std::mutex> lock(snapshot_mutex_);
        previous = snapshot_;
        have_previous = published_;
      }
      const Eigen::Matrix3d R = pose.rotation.normalized().toRotationMatrix();
      if (have_previous && previous.t0 == pose.translation && previous.R0 == R) continue;  // held still
      NearSnapshot s;
      s.t0 = pose.translation;
      s.R0 = R;
      s.near = near_wrench(*near_, pose);
      if (have_previous) {
        const NearWrench was = carried(previous, s.t0, R);
        s.staleness.energy = std::abs(s.near.energy - was.energy);
        s.staleness.force = (s.near.force - was.force).norm();
        s.staleness.torque = (s.near.torque - was.torque).norm();
      }
      std::lock_guard<std::mutex> lock(snapshot_mutex_);
      snapshot_ = s;
      published_ = true;
    }
  }

  QueryVariant variant_;
  std::shared_ptr<const NearField> near_;
  std::unique_ptr<QueryEngine> far_;
  // Background mode.
  NearSnapshot frame_snapshot_;
  bool have_frame_snapshot_ = false;
  std::mutex snapshot_mutex_, pose_mutex_;
  NearSnapshot snapshot_;
  bool published_ = false;
  Pose latest_;
  unsigned pose_seq_ = 0;
  bool stop_ = false;
  std::condition_variable wake_;
  std::thread worker_;
};

}  // namespace

std::unique_ptr<QueryEngine> make_split_query(const ComputeContext& ctx, const PairSpectra& spectra,
                                              const QueryVariant& variant, const ProgramCacheConfig& cache) {
  return std::make_unique<SplitQuery>(ctx, spectra, variant, cache);
}

}  // namespace snapfit
