#include "scheduler/haptics/parallel_contact.h"

#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <thread>
#include <vector>

#include "core/subnormal_flush.h"
#include "core/thread_name.h"

namespace snapfit {
namespace {

// Shares per thread: finer than one per thread, so that a thread whose shares hold
// little of the contact takes more of them (the contact is concentrated in space).
constexpr std::size_t kSharesPerThread = 4;

// Helper threads that, with the caller, take the contact's shares in turn each frame
// (whoever is free takes the next). Each share's sum goes to its own slot and the slots
// are added in order, so the result does not depend on which thread took which share.
// The caller waits for the shares taken, not for every helper to wake: on a busy machine
// a helper woken late finds the frame's shares gone (each ticket names its frame, so a
// late helper cannot take a share of a later frame with an earlier pose).
class ContactTeam {
 public:
  ContactTeam(std::shared_ptr<const RigidContactModel> model, unsigned threads, ContactShareFunction share)
      : model_(std::move(model)), share_(share), shares_(threads * kSharesPerThread), results_(shares_) {
    helpers_.reserve(threads - 1);
    for (unsigned i = 1; i < threads; ++i)
      helpers_.emplace_back([this] {
        name_this_thread("snapfit-contact");
        const SubnormalFlush flush;  // as in the loop's own thread (run_haptic_loop)
        serve();
      });
  }
  ~ContactTeam() {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      stop_ = true;
    }
    wake_.notify_all();
    for (std::thread& t : helpers_) t.join();
  }
  ContactTeam(const ContactTeam&) = delete;
  ContactTeam& operator=(const ContactTeam&) = delete;

  ContactWrench evaluate(const Pose& pose) {
    std::uint64_t frame = 0;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      pose_ = pose;
      frame = ++frame_;
      finished_.store(0, std::memory_order_relaxed);
      ticket_.store(frame << 32, std::memory_order_release);
    }
    wake_.notify_all();
    take_shares(frame, pose);
    // The shares helpers took: each takes one share's time at most.
    while (finished_.load(std::memory_order_acquire) < shares_) std::this_thread::yield();
    ContactWrench sum = results_[0];
    for (std::size_t i = 1; i < shares_; ++i) add_contact_share(sum, results_[i]);
    finish_contact(*model_, sum);
    return sum;
  }

 private:
  // Takes shares of `frame` while any are left: a ticket is the frame (high 32 bits) and
  // the next share's index.
  void take_shares(std::uint64_t frame, const Pose& pose) {
    std::uint64_t ticket = ticket_.load(std::memory_order_acquire);
    while ((ticket >> 32) == (frame & 0xffffffffu) && (ticket & 0xffffffffu) < shares_) {
      if (!ticket_.compare_exchange_weak(ticket, ticket + 1, std::memory_order_acq_rel)) continue;
      const std::size_t s = ticket & 0xffffffffu;
      results_[s] = share_(*model_, pose, s, shares_);
      finished_.fetch_add(1, std::memory_order_release);
      ticket = ticket_.load(std::memory_order_acquire);
    }
  }

  void serve() {
    std::uint64_t seen = 0;
    while (true) {
      Pose pose;
      std::uint64_t frame = 0;
      {
        std::unique_lock<std::mutex> lock(mutex_);
        wake_.wait(lock, [&] { return stop_ || frame_ != seen; });
        if (stop_) return;
        seen = frame = frame_;
        pose = pose_;
      }
      take_shares(frame, pose);
    }
  }

  std::shared_ptr<const RigidContactModel> model_;
  ContactShareFunction share_;
  std::size_t shares_;
  std::vector<ContactWrench> results_;  // one per share, written by the thread that took it
  std::atomic<std::uint64_t> ticket_{0};
  std::atomic<std::size_t> finished_{0};  // shares of the current frame finished
  std::vector<std::thread> helpers_;
  std::mutex mutex_;
  std::condition_variable wake_;
  Pose pose_;
  std::uint64_t frame_ = 0;
  bool stop_ = false;
};

}  // namespace

unsigned contact_threads_for(const RigidContactModel& model, unsigned max_threads) {
  const std::size_t points = model.part1_samples.points.size() + model.part2_samples.points.size();
  if (points < 16384) return 1;
  const unsigned cap = max_threads ? max_threads : 4;
  return std::clamp(std::thread::hardware_concurrency(), 1u, cap);
}

std::function<ContactWrench(const Pose&)> contact_evaluator(std::shared_ptr<const RigidContactModel> model,
                                                            unsigned threads, ContactShareFunction share) {
  if (!model) return nullptr;
  if (threads == 0) threads = contact_threads_for(*model);
  if (threads <= 1)
    return [model, share](const Pose& pose) {
      ContactWrench c = share(*model, pose, 0, 1);
      finish_contact(*model, c);
      return c;
    };
  auto team = std::make_shared<ContactTeam>(std::move(model), threads, share);
  return [team](const Pose& pose) { return team->evaluate(pose); };
}

}  // namespace snapfit
