#pragma once
// Where part 2 fits part 1 over all rotations, as `snapfit search` does it: one full
// translational energy map per rotation of a uniform grid of SO(3) (the correlation of
// Behandish & Ilies 2016 eq. 10 at every translation at once, one inverse FFT per
// rotation), the lowest minima of every map merged, and each of the best refined by a
// local 6-DOF descent of the energy and, with the scene's rigid contact, of the
// potential the haptic loop renders (haptic_loop.h), where the parts rest touching.
//
// The rotations can be shared among processes (MPI ranks in the tool): each maps its
// share on its own device, and process 0 merges, refines and returns the poses.
//
//   snapfit::SearchRequest request;
//   request.rotations = 500;
//   snapfit::SearchResult r = snapfit::search(snapfit::load_scene("scenes/default.json"), request);
//   // r.top[0].refined.pose: the best fit found
#include <Eigen/Geometry>
#include <array>
#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "snapfit/pose.h"
#include "snapfit/query.h"
#include "snapfit/scene.h"

namespace snapfit {

// The processes that share one search. search(scene, request) runs in one process;
// several implement this over their transport (the tool: MPI_COMM_WORLD).
class SearchExchange {
 public:
  virtual ~SearchExchange() = default;
  virtual int rank() const = 0;
  virtual int size() const = 0;
  virtual int local_rank() const = 0;  // among the processes on this machine (picks the device)
  // Every process calls it at the same point with its error ("" when it did fine). When
  // any failed, each throws: process 0 a snapfit::Error naming the lowest failed process
  // and its message, the others an exception of the implementation's choice.
  virtual void checkpoint(const std::string& error) = 0;
  // Every process's values concatenated in rank order, on process 0 (empty elsewhere).
  virtual std::vector<double> gather(const std::vector<double>& mine) = 0;
  // Process 0's values on every process.
  virtual void broadcast(std::vector<double>& values) = 0;
};

struct SearchPlan {
  std::size_t rotations = 0, base_cells = 0, psi_steps = 0;  // the grid: base directions x turns
  double step_deg = 0, covering_radius_deg = 0;
  std::array<std::size_t, 3> map_dims{};  // translations per map
  double spacing = 0;                     // between translations, scene units
  int processes = 1;
  std::string map_fft;            // the inverse FFT and why ("clfft x8 (per map: ...)")
  bool minima_on_device = false;  // each map reduced on the device to a short list, else read back
};

struct SearchRequest {
  std::optional<double> step_deg;        // the grid's spacing (default 30 degrees)
  std::optional<std::size_t> rotations;  // about this many rotations instead of step_deg
  std::size_t top = 10;                  // poses returned
  std::size_t per_rotation = 4;          // lowest minima kept per map
  // The OpenCL device of each process: process r takes entry (local rank mod count);
  // empty: as AssemblyOptions::device "".
  std::vector<std::string> devices;
  Interpolation interpolation = Interpolation::trilinear;  // the rotated spectrum in the maps
  std::size_t modes = 0;                                   // low-pass: about this many modes in the maps; 0: all
  std::size_t refine_modes = 65536;                        // modes of the refining queries
  std::size_t refine_queries = 200;                        // queries per refined pose at most
  // The maps' inverse FFT: "auto" (the fastest, measured once per device and size and
  // cached), "clfft", "fftw" or "vkfft" (those this build has: map_ffts_in_this_build).
  std::string map_fft = "auto";
  std::size_t map_batch = 0;  // rotations per batch on a device FFT; 0: measured with "auto", else 1
  bool progress = false;      // a progress bar on stderr (process 0)
  // Process 0, once the maps are ready to run: what the search is about to do.
  std::function<void(const SearchPlan&)> on_plan;
  std::function<void(const std::string&)> note;  // cache messages; default: stderr
};

struct RefinedPose {
  std::string error;    // the refinement failed (the other fields are unset)
  Pose energy_minimum;  // the descent of the energy from the map's pose
  double energy_minimum_energy = 0;
  std::size_t queries = 0;
  // With the scene's rigid contact: the descent of the rendered potential (the energy
  // times the loop's gain plus the contact) from the energy minimum, where the parts
  // rest touching; without it, the energy minimum.
  bool rendered = false;
  Pose pose;
  double energy = 0;  // at `pose`
  double potential_j = 0;
  std::size_t newton_steps = 0;
  std::size_t modes = 0;  // m' of the refining queries
};

struct FoundPose {
  std::size_t rotation = 0;  // index into SearchResult::rotations
  Pose pose;                 // the map's minimum
  double energy = 0;
  RefinedPose refined;
};

struct SearchResult {  // on process 0; the other processes return an empty result
  SearchPlan plan;
  std::vector<Eigen::Quaterniond> rotations;   // the grid, base direction by direction, turn fastest
  std::vector<double> best_energy;             // per rotation: the lowest energy of its map
  std::vector<FoundPose> top;                  // by increasing map energy
  std::vector<std::size_t> process_rotations;  // per process: rotations mapped
  std::vector<double> process_seconds;         // per process: time of its maps
  std::string map_fft;                         // the inverse FFT's name ("clfft", "fftw", "vkfft")
  std::size_t map_batch = 1;                   // rotations per batch
};

// Throws snapfit::Error for an invalid request, a scene, part, device or FFT that fails
// (on any process, named), before the maps or at the next point all processes meet.
SearchResult search(const Scene& scene, const SearchRequest& request, SearchExchange& exchange);
SearchResult search(const Scene& scene, const SearchRequest& request = {});  // one process

// The names SearchRequest::map_fft takes besides "auto": the inverse FFTs this build has,
// "clfft" first (always built), then "fftw" and "vkfft" where CMake found them.
std::vector<std::string> map_ffts_in_this_build();

}  // namespace snapfit
