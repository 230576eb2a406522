#include "cli/search_ranks.h"

#include <algorithm>
#include <cstring>

#include "snapfit/error.h"

#ifdef SNAPFIT_WITH_MPI
#define OMPI_SKIP_MPICXX 1  // the C API only
#include <mpi.h>
#endif

namespace snapfit::cli {
namespace {

#ifdef SNAPFIT_WITH_MPI
void check(int status, const char* what) {
  if (status != MPI_SUCCESS) throw Error(std::string("MPI: ") + what + " failed");
}

#endif

}  // namespace

SearchRanks::SearchRanks() {
#ifdef SNAPFIT_WITH_MPI
  check(MPI_Init(nullptr, nullptr), "MPI_Init");
  MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
  MPI_Comm_size(MPI_COMM_WORLD, &size_);
  MPI_Comm node;
  check(MPI_Comm_split_type(MPI_COMM_WORLD, MPI_COMM_TYPE_SHARED, rank_, MPI_INFO_NULL, &node), "splitting by node");
  MPI_Comm_rank(node, &local_rank_);
  MPI_Comm_free(&node);
#endif
}

SearchRanks::~SearchRanks() {
#ifdef SNAPFIT_WITH_MPI
  MPI_Finalize();
#endif
}

void SearchRanks::checkpoint(const std::string& error) {
#ifdef SNAPFIT_WITH_MPI
  if (size_ > 1) {
    // The lowest failed rank (size_ when none), then its message, sent by it alone.
    const int mine = error.empty() ? size_ : rank_;
    int failed = size_;
    check(MPI_Allreduce(&mine, &failed, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD), "agreeing on failures");
    if (failed == size_) return;
    int length = failed == rank_ ? int(error.size()) : 0;
    check(MPI_Bcast(&length, 1, MPI_INT, failed, MPI_COMM_WORLD), "sending a failure");
    std::string message = failed == rank_ ? error : std::string(std::size_t(length), ' ');
    check(MPI_Bcast(message.data(), length, MPI_CHAR, failed, MPI_COMM_WORLD), "sending a failure");
    if (!root()) throw OtherRankFailed{};
    throw Error("rank " + std::to_string(failed) + " of " + std::to_string(size_) + " failed: " + message);
  }
#endif
  if (!error.empty()) throw Error(error);
}

std::vector<double> SearchRanks::gather(const std::vector<double>& mine) {
#ifdef SNAPFIT_WITH_MPI
  if (size_ > 1) {
    const int count = int(mine.size());
    std::vector<int> counts(static_cast<std::size_t>(size_)), offsets(static_cast<std::size_t>(size_));
    check(MPI_Gather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, MPI_COMM_WORLD), "gathering counts");
    std::vector<double> all;
    if (root()) {
      for (int r = 1; r < size_; ++r) offsets[r] = offsets[r - 1] + counts[r - 1];
      all.resize(std::size_t(offsets.back() + counts.back()));
    }
    check(MPI_Gatherv(mine.data(), count, MPI_DOUBLE, all.data(), counts.data(), offsets.data(), MPI_DOUBLE, 0,
                      MPI_COMM_WORLD),
          "gathering results");
    return all;
  }
#endif
  return mine;
}

void SearchRanks::broadcast(std::vector<double>& values) {
#ifdef SNAPFIT_WITH_MPI
  if (size_ > 1) {
    unsigned long long n = values.size();
    check(MPI_Bcast(&n, 1, MPI_UNSIGNED_LONG_LONG, 0, MPI_COMM_WORLD), "broadcasting a count");
    values.resize(std::size_t(n));
    check(MPI_Bcast(values.data(), int(n), MPI_DOUBLE, 0, MPI_COMM_WORLD), "broadcasting values");
  }
#else
  (void)values;
#endif
}

}  // namespace snapfit::cli
