#include "scheduler/parallel_contact.h"

#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <mutex>
#include <thread>
#include <vector>

namespace snapfit {
namespace {

// Shares per thread: finer than one per thread, so that a thread whose shares hold
// little of the contact takes more of them (the contact is concentrated in space).
constexpr std::size_t kSharesPerThread = 4;

// Helper threads that, with the caller, take the contact's shares in turn each frame
// (whoever is free takes the next). Each share's sum goes to its own slot and the slots
// are added in order, so the result does not depend on which thread took which share.
class ContactTeam {
 public:
  ContactTeam(std::shared_ptr<const RigidContactModel> model, unsigned threads, ContactShareFunction share)
      : model_(std::move(model)), share_(share), shares_(threads * kSharesPerThread), results_(shares_) {
    helpers_.reserve(threads - 1);
    for (unsigned i = 1; i < threads; ++i) helpers_.emplace_back([this] { serve(); });
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
    {
      std::lock_guard<std::mutex> lock(mutex_);
      pose_ = pose;
      next_share_.store(0);
      pending_ = helpers_.size();
      ++generation_;
    }
    wake_.notify_all();
    take_shares(pose);
    {
      std::unique_lock<std::mutex> lock(mutex_);
      done_.wait(lock, [&] { return pending_ == 0; });
    }
    ContactWrench sum = results_[0];
    for (std::size_t i = 1; i < shares_; ++i) add_contact_share(sum, results_[i]);
    finish_contact(*model_, sum);
    return sum;
  }

 private:
  void take_shares(const Pose& pose) {
    for (std::size_t s = next_share_.fetch_add(1); s < shares_; s = next_share_.fetch_add(1))
      results_[s] = share_(*model_, pose, s, shares_);
  }

  void serve() {
    std::size_t seen = 0;
    while (true) {
      Pose pose;
      {
        std::unique_lock<std::mutex> lock(mutex_);
        wake_.wait(lock, [&] { return stop_ || generation_ != seen; });
        if (stop_) return;
        seen = generation_;
        pose = pose_;
      }
      take_shares(pose);
      bool last = false;
      {
        std::lock_guard<std::mutex> lock(mutex_);
        last = --pending_ == 0;
      }
      if (last) done_.notify_one();
    }
  }

  std::shared_ptr<const RigidContactModel> model_;
  ContactShareFunction share_;
  std::size_t shares_;
  std::vector<ContactWrench> results_;  // one per share, written by the thread that took it
  std::atomic<std::size_t> next_share_{0};
  std::vector<std::thread> helpers_;
  std::mutex mutex_;
  std::condition_variable wake_, done_;
  Pose pose_;
  std::size_t generation_ = 0, pending_ = 0;
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
