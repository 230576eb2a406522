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

// PairSpectra as doubles: header, then both parts' centres, extents, parities and spectra.
std::vector<double> pack(const PairSpectra& s) {
  std::vector<double> v{double(s.dims[0]), double(s.dims[1]), double(s.dims[2]), s.spacing,
                        s.length.x(),      s.length.y(),      s.length.z()};
  for (const PartSpectrum* p : {&s.part1, &s.part2}) {
    v.insert(v.end(), {p->centre.x(), p->centre.y(), p->centre.z(), p->half_extent.x(), p->half_extent.y(),
                       p->half_extent.z(), double(p->sample_parity), double(p->rho.size())});
    for (const Complex& c : p->rho) v.insert(v.end(), {c.real(), c.imag()});
  }
  return v;
}

void unpack(const std::vector<double>& v, PairSpectra& s) {
  std::size_t i = 0;
  for (int a = 0; a < 3; ++a) s.dims[a] = std::size_t(v[i++]);
  s.spacing = v[i++];
  for (int a = 0; a < 3; ++a) s.length[a] = v[i++];
  for (PartSpectrum* p : {&s.part1, &s.part2}) {
    for (int a = 0; a < 3; ++a) p->centre[a] = v[i++];
    for (int a = 0; a < 3; ++a) p->half_extent[a] = v[i++];
    p->sample_parity = int(v[i++]);
    p->rho.resize(std::size_t(v[i++]));
    for (Complex& c : p->rho) {
      c = Complex(float(v[i]), float(v[i + 1]));
      i += 2;
    }
    p->deconvolved.clear();
    p->deconvolved_width = 0;
  }
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

void SearchRanks::checkpoint(const std::string& error) const {
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

std::vector<double> SearchRanks::gather(const std::vector<double>& mine) const {
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

void SearchRanks::broadcast(PairSpectra& spectra) const {
#ifdef SNAPFIT_WITH_MPI
  if (size_ > 1) {
    std::vector<double> v;
    if (root()) v = pack(spectra);
    unsigned long long n = v.size();
    check(MPI_Bcast(&n, 1, MPI_UNSIGNED_LONG_LONG, 0, MPI_COMM_WORLD), "sending the spectra");
    v.resize(std::size_t(n));
    check(MPI_Bcast(v.data(), int(n), MPI_DOUBLE, 0, MPI_COMM_WORLD), "sending the spectra");
    if (!root()) unpack(v, spectra);
  }
#else
  (void)spectra;
#endif
}

}  // namespace snapfit::cli
