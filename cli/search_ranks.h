#pragma once
// The processes of one `snapfit search`: the MPI ranks when snapfit was built with MPI
// (SNAPFIT_WITH_MPI) and started by mpirun, else one process. Failures are agreed on at
// checkpoints, so a rank that fails ends every rank with a message naming it instead
// of leaving the others waiting in a collective.
#include <string>
#include <vector>

#include "snapfit/search.h"

namespace snapfit::cli {

// Thrown on the ranks other than 0 when some rank failed (rank 0 reports it).
struct OtherRankFailed {};

class SearchRanks final : public SearchExchange {
 public:
  SearchRanks();   // MPI_Init when built with MPI (a process not started by mpirun is rank 0 of 1)
  ~SearchRanks();  // MPI_Finalize
  SearchRanks(const SearchRanks&) = delete;
  SearchRanks& operator=(const SearchRanks&) = delete;

  int rank() const override { return rank_; }
  int size() const override { return size_; }
  int local_rank() const override { return local_rank_; }  // among the ranks of this node
  bool root() const { return rank_ == 0; }

  // Every rank calls it at the same point with its error ("" when it did fine). When any
  // rank failed, rank 0 throws snapfit::Error "rank R of N failed: <its error>" (the
  // lowest failed rank) and the others throw OtherRankFailed.
  void checkpoint(const std::string& error) override;
  // The values of every rank, concatenated in rank order, on rank 0 (empty elsewhere).
  std::vector<double> gather(const std::vector<double>& mine) override;
  // Rank 0's values on every rank.
  void broadcast(std::vector<double>& values) override;

 private:
  int rank_ = 0, size_ = 1, local_rank_ = 0;
};

}  // namespace snapfit::cli
