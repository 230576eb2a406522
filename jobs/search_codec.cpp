#include "jobs/search_codec.h"

#include <sstream>

#include "snapfit/error.h"

namespace snapfit {
namespace {

constexpr std::size_t kCandidateValues = 6;

// Reads values in order, and says so when they run out.
struct Reader {
  const std::vector<double>& values;
  std::size_t next = 0;
  double operator()() {
    if (next >= values.size()) throw Error("search: the spectra sent between processes are truncated");
    return values[next++];
  }
};

}  // namespace

std::vector<double> encode_spectra(const PairSpectra& s) {
  std::vector<double> v{double(s.dims[0]), double(s.dims[1]), double(s.dims[2]), s.spacing,
                        s.length.x(),      s.length.y(),      s.length.z()};
  for (const PartSpectrum* p : {&s.part1, &s.part2}) {
    v.insert(v.end(), {p->centre.x(), p->centre.y(), p->centre.z(), p->half_extent.x(), p->half_extent.y(),
                       p->half_extent.z(), double(p->sample_parity), double(p->rho.size())});
    for (const Complex& c : p->rho) v.insert(v.end(), {c.real(), c.imag()});
  }
  return v;
}

PairSpectra decode_spectra(const std::vector<double>& values) {
  Reader read{values};
  PairSpectra s;
  for (int a = 0; a < 3; ++a) s.dims[a] = std::size_t(read());
  s.spacing = read();
  for (int a = 0; a < 3; ++a) s.length[a] = read();
  for (PartSpectrum* p : {&s.part1, &s.part2}) {
    for (int a = 0; a < 3; ++a) p->centre[a] = read();
    for (int a = 0; a < 3; ++a) p->half_extent[a] = read();
    p->sample_parity = int(read());
    const double count = read();
    if (!(count >= 0) || 2 * count > double(values.size() - read.next))
      throw Error("search: the spectra sent between processes are truncated");
    p->rho.resize(std::size_t(count));
    for (Complex& c : p->rho) {
      const double re = read();
      c = Complex(float(re), float(read()));
    }
  }
  return s;
}

std::vector<double> encode_candidates(const std::vector<PoseCandidate>& candidates) {
  std::vector<double> v;
  v.reserve(candidates.size() * kCandidateValues);
  for (const PoseCandidate& c : candidates)
    v.insert(v.end(), {double(c.rotation), double(c.cell), c.energy, c.pose.translation.x(), c.pose.translation.y(),
                       c.pose.translation.z()});
  return v;
}

std::vector<PoseCandidate> decode_candidates(const std::vector<double>& v,
                                             const std::vector<Eigen::Quaterniond>& rotations) {
  std::vector<PoseCandidate> cs;
  for (std::size_t i = 0; i + kCandidateValues <= v.size(); i += kCandidateValues) {
    PoseCandidate c;
    if (!(v[i] >= 0 && v[i] < double(rotations.size()))) {
      std::ostringstream m;
      m << "search: a candidate names rotation " << v[i] << " of " << rotations.size();
      throw Error(m.str());
    }
    c.rotation = std::size_t(v[i]);
    c.cell = std::size_t(v[i + 1]);
    c.energy = v[i + 2];
    c.pose.rotation = rotations[c.rotation];
    c.pose.translation = Eigen::Vector3d(v[i + 3], v[i + 4], v[i + 5]);
    cs.push_back(c);
  }
  return cs;
}

}  // namespace snapfit
