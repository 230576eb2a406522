#include "engine/maps/full_map.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include "engine/runtime/cl_values.h"
#include "engine/runtime/compute_context.h"
#include "engine/runtime/kernel_sources.h"
#ifdef SNAPFIT_HAVE_FFTW
#include "engine/spectra/fftw_real_inverse.h"
#endif
#ifdef SNAPFIT_HAVE_VKFFT
#include "engine/spectra/vkfft_inverse.h"
#endif
#include "snapfit/error.h"

namespace snapfit {
namespace {

// Low-pass radius: the |w|^2 of the modes-th smallest node (infinite: every mode).
float low_pass_w2(const PairSpectra& spectra, std::size_t modes) {
  const auto& dims = spectra.dims;
  const std::size_t total = dims[0] * dims[1] * dims[2];
  if (modes == 0 || modes >= total) return std::numeric_limits<float>::infinity();
  std::vector<float> w2(total);
  for (std::size_t z = 0; z < dims[2]; ++z)
    for (std::size_t y = 0; y < dims[1]; ++y)
      for (std::size_t x = 0; x < dims[0]; ++x)
        w2[x + dims[0] * (y + dims[1] * z)] =
            float(std::pow(spectra.frequency(0, x), 2) + std::pow(spectra.frequency(1, y), 2) +
                  std::pow(spectra.frequency(2, z), 2));
  std::nth_element(w2.begin(), w2.begin() + (modes - 1), w2.end());
  return w2[modes - 1];
}

}  // namespace

struct TranslationMapper::Slot {
  cl::Buffer result;               // clfft, vkfft: the batch's complex inverse FFTs, on the device
  std::vector<Complex> f;          // clfft, vkfft: the same read back (sized at the first read)
  cl::Buffer poses;                // the batch's poses for the product kernel
  std::vector<cl_float16> pose;    // the same on the host, kept until the write is done
  std::vector<Eigen::Matrix3d> R;  // the batch's rotations
  std::vector<char> collected;     // per member of the batch
  std::size_t count = 0;           // members submitted
  cl::Event read;
  MapOutput output = MapOutput::energy;
  bool pending = false;  // the read is not waited for yet
};

#ifdef SNAPFIT_HAVE_FFTW
struct TranslationMapper::HostFft {
  FftwRealInverse fft;  // one buffer pair per slot
  explicit HostFft(const std::array<std::size_t, 3>& dims) : fft(dims, slots) {}
};
#else
struct TranslationMapper::HostFft {};
#endif

#ifdef SNAPFIT_HAVE_VKFFT
struct TranslationMapper::VkFft {
  VkfftInverse fft;
  VkFft(const ComputeContext& ctx, const std::array<std::size_t, 3>& dims, const cl::Buffer& product,
        const cl::Buffer& map, std::size_t batch)
      : fft(ctx, dims, product, map, batch) {}
};
#else
struct TranslationMapper::VkFft {};
#endif

TranslationMapper::TranslationMapper(const FftLibrary& library, const ComputeContext& ctx, const PairSpectra& spectra,
                                     Interpolation interpolation, std::size_t modes, MapFft fft,
                                     const ProgramCacheConfig& cache, std::size_t batch)
    : ctx_(ctx),
      spectra_(spectra),
      max_w2_(low_pass_w2(spectra, modes)),
      batch_(batch),
      fft_kind_(fft),
      slot_(new Slot[slots]) {
  parse_map_fft(map_fft_name(fft));  // throws for a backend this build lacks
  const auto& dims = spectra.dims;
  const std::size_t total = dims[0] * dims[1] * dims[2];
  const std::size_t half = (dims[0] / 2 + 1) * dims[1] * dims[2];
  if (batch == 0 || (batch > 1 && !map_fft_on_device(fft)))
    throw Error("full map: a batch of " + std::to_string(batch) + " rotations is not supported with " +
                map_fft_name(fft) + " (1 with FFTW's host inverse, 1 or more with a device FFT)");
  if (batch > map_batch_limit(ctx, dims, batch))
    throw Error("full map: a batch of " + std::to_string(batch) + " maps of " + std::to_string(dims[0]) + " x " +
                std::to_string(dims[1]) + " x " + std::to_string(dims[2]) + " does not fit " + ctx.device.info.name +
                "'s memory (at most " + std::to_string(map_batch_limit(ctx, dims, batch)) + ")");
  // Regular order: translation index j' from -floor(N/2) to N - 1 - floor(N/2) per axis;
  // its FFT index is j = j' mod N.
  grid_.spacing = spectra.spacing;
  grid_.dims = Eigen::Vector3i(int(dims[0]), int(dims[1]), int(dims[2]));
  for (int a = 0; a < 3; ++a) grid_.origin[a] = -spectra.spacing * double(dims[a] / 2);
  fft_index_.resize(total);
  for (std::size_t z = 0; z < dims[2]; ++z)
    for (std::size_t y = 0; y < dims[1]; ++y)
      for (std::size_t x = 0; x < dims[0]; ++x) {
        const std::size_t jx = (x + dims[0] - dims[0] / 2) % dims[0], jy = (y + dims[1] - dims[1] / 2) % dims[1],
                          jz = (z + dims[2] - dims[2] / 2) % dims[2];
        fft_index_[x + dims[0] * (y + dims[1] * z)] = jx + dims[0] * (jy + dims[1] * jz);
      }
  try {
    const std::string options = std::string("-cl-std=CL1.2") +
                                (interpolation == Interpolation::tricubic ? " -D TRICUBIC" : "") +
                                (fft == MapFft::fftw && spectra.conjugate_pairs() == 1 ? " -D CONJUGATE_PAIRS" : "");
    kernel_ = cl::Kernel(
        build_program(ctx, "full_map", kernel_source("spectrum_sample") + kernel_source("full_map"), options, cache)
            .program,
        map_fft_on_device(fft) ? "spectrum_product" : "spectrum_product_half");
    auto upload = [&](const std::vector<Complex>& v) {
      return cl::Buffer(ctx.context, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, sizeof(Complex) * v.size(),
                        const_cast<Complex*>(v.data()));
    };
    s1_ = upload(spectra.part1.rho);
    s2_ = upload(spectra.part2.rho);
    const std::size_t product_bytes = sizeof(Complex) * batch * (map_fft_on_device(fft) ? total : half);
    product_ = cl::Buffer(ctx.context, CL_MEM_READ_WRITE, product_bytes);
    // A batch's members past those submitted are transformed too: zeros, not whatever
    // the allocation held.
    ctx.queue.enqueueFillBuffer(product_, Complex(0.0f, 0.0f), 0, product_bytes);
    // One batch of maps per slot: a slot's maps stay on the device until they are collected.
    for (int s = 0; s < slots; ++s) {
      Slot& slot = slot_[s];
      if (map_fft_on_device(fft))
        slot.result = cl::Buffer(ctx.context, CL_MEM_READ_WRITE, sizeof(Complex) * total * batch);
      slot.poses = cl::Buffer(ctx.context, CL_MEM_READ_ONLY, sizeof(cl_float16) * batch);
      slot.pose.resize(batch);
      slot.R.resize(batch);
      slot.collected.resize(batch);
    }
    kernel_.setArg(0, s1_);
    kernel_.setArg(1, s2_);
    kernel_.setArg(2, cl_int4{{int(dims[0]), int(dims[1]), int(dims[2]), 0}});
    kernel_.setArg(3, float4_of(spectra.length));
    kernel_.setArg(5, static_cast<float>(1.0 / (spectra.length.x() * spectra.length.y() * spectra.length.z())));
    kernel_.setArg(6, max_w2_);
    kernel_.setArg(7, product_);
  } catch (const cl::Error& e) {
    throw_device_error("full map failed", ctx.device.info.name, e);
  }
  if (fft == MapFft::clfft) fft_ = std::make_unique<Fft3d>(library, ctx, dims, batch);
#ifdef SNAPFIT_HAVE_VKFFT
  if (fft == MapFft::vkfft) vkfft_ = std::make_unique<VkFft>(ctx, dims, product_, slot_[0].result, batch);
#endif
  if (map_fft_on_device(fft)) {
    device_minima_ = std::make_unique<DeviceMinima>(ctx, dims, slots * int(batch), cache);
    try {
      side_ = cl::CommandQueue(ctx.context, ctx.device.device, 0);
    } catch (const cl::Error& e) {
      throw_device_error("full map failed", ctx.device.info.name, e);
    }
  }
#ifdef SNAPFIT_HAVE_FFTW
  if (fft == MapFft::fftw) host_fft_ = std::make_unique<HostFft>(dims);
#endif
}

TranslationMapper::~TranslationMapper() {
  for (int s = 0; s < slots; ++s)
    if (slot_[s].pending) slot_[s].read.wait();  // the read writes into the slot's host buffer
}

// The products of the slot's batch, one launch: R row-major and the shift R c2 - c1 per
// member (kernels/full_map.cl).
void TranslationMapper::enqueue_product(int slot) {
  Slot& s = slot_[slot];
  for (std::size_t m = 0; m < s.count; ++m) {
    const Eigen::Matrix3d& R = s.R[m];
    const Eigen::Vector3d shift = R * spectra_.part2.centre - spectra_.part1.centre;
    cl_float16& pose = s.pose[m];
    pose = cl_float16{};
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) pose.s[3 * r + c] = static_cast<float>(R(r, c));
    for (int a = 0; a < 3; ++a) pose.s[9 + a] = static_cast<float>(shift[a]);
  }
  ctx_.queue.enqueueWriteBuffer(s.poses, CL_FALSE, 0, sizeof(cl_float16) * s.count, s.pose.data());
  const auto& d = spectra_.dims;
  kernel_.setArg(4, s.poses);
  ctx_.queue.enqueueNDRangeKernel(
      kernel_, cl::NullRange,
      cl::NDRange(map_fft_on_device(fft_kind_) ? d[0] * d[1] * d[2] : (d[0] / 2 + 1) * d[1] * d[2], s.count));
}

// f(t_j) = sum_k P_k e^{2 pi i k.j / N} into the slot's maps, the whole batch (FFTW's
// runs on the host).
void TranslationMapper::enqueue_fft(int slot) {
  if (fft_kind_ == MapFft::clfft) fft_->enqueue(FftDirection::inverse, product_, slot_[slot].result);
#ifdef SNAPFIT_HAVE_VKFFT
  if (fft_kind_ == MapFft::vkfft) vkfft_->fft.enqueue(product_, slot_[slot].result);
#endif
}

void TranslationMapper::enqueue_read(int slot, cl::Event* done) {
  Slot& s = slot_[slot];
  if (map_fft_on_device(fft_kind_)) {
    if (s.output == MapOutput::minima) {
      // One in-order queue: the last list's read completes after the others.
      for (std::size_t m = 0; m < s.count; ++m)
        device_minima_->enqueue_read(ctx_.queue, minima_list(slot, m), m + 1 == s.count ? done : nullptr);
      return;
    }
    s.f.resize(fft_index_.size() * batch_);  // allocates at the first read only
    ctx_.queue.enqueueReadBuffer(s.result, CL_FALSE, 0, sizeof(Complex) * fft_index_.size() * s.count, s.f.data(),
                                 nullptr, done);
    return;
  }
#ifdef SNAPFIT_HAVE_FFTW
  const FftwRealInverse& host = host_fft_->fft;
  ctx_.queue.enqueueReadBuffer(product_, CL_FALSE, 0, sizeof(Complex) * host.half_count(), host.half(slot), nullptr,
                               done);
#endif
}

void TranslationMapper::submit(int slot, const Eigen::Matrix3d* R, std::size_t count, MapOutput output) {
  if (slot < 0 || slot >= slots || count == 0 || count > batch_)
    throw Error("full map: " + std::to_string(count) + " rotations into slot " + std::to_string(slot) + " (slots 0-" +
                std::to_string(slots - 1) + ", 1 to " + std::to_string(batch_) + " rotations each)");
  Slot& s = slot_[slot];
  try {
    if (s.pending) s.read.wait();  // uncollected maps are dropped
    s.pending = false;
    s.count = count;
    std::copy(R, R + count, s.R.begin());
    std::fill(s.collected.begin(), s.collected.end(), 0);
    s.output = output;
    enqueue_product(slot);
    enqueue_fft(slot);
    if (map_fft_on_device(fft_kind_) && output == MapOutput::minima)
      for (std::size_t m = 0; m < count; ++m)
        device_minima_->enqueue_reduce(ctx_.queue, minima_list(slot, m), s.result, aliasing_box(s.R[m]),
                                       m * fft_index_.size());
    enqueue_read(slot, &s.read);
    ctx_.queue.flush();
  } catch (const cl::Error& e) {
    throw_device_error("full map failed", ctx_.device.info.name, e);
  }
  s.pending = true;
}

// Same aliasing rule as the pose queries (engine/pose_query.cpp), per axis: the
// translation t aliases when |t + R c2 - c1| + reach > L on some axis.
void TranslationMapper::aliasing_mask(const Eigen::Matrix3d& R, std::array<std::vector<char>, 3>& inside) const {
  const Eigen::Vector3d shift = R * spectra_.part2.centre - spectra_.part1.centre;
  const Eigen::Vector3d reach = spectra_.part1.half_extent + R.cwiseAbs() * spectra_.part2.half_extent;
  for (int a = 0; a < 3; ++a) {
    inside[a].resize(std::size_t(grid_.dims[a]));
    for (int i = 0; i < grid_.dims[a]; ++i)
      inside[a][i] = std::abs(grid_.origin[a] + grid_.spacing * i + shift[a]) + reach[a] <= spectra_.length[a];
  }
}

// The mask as a box: |t_i + shift| + reach <= L holds on an interval of i, since t_i grows
// with i.
MapBox TranslationMapper::aliasing_box(const Eigen::Matrix3d& R) {
  aliasing_mask(R, inside_);
  MapBox box;
  for (int a = 0; a < 3; ++a) {
    const auto& in = inside_[a];
    const auto first = std::find(in.begin(), in.end(), 1);
    if (first == in.end()) return MapBox{};  // empty
    const auto last = std::find(in.rbegin(), in.rend(), 1).base() - 1;
    if (std::find(first, last, 0) != last)
      throw Error("full map: the aliasing mask on axis " + std::to_string(a) + " is not an interval");
    box.lo[a] = int(first - in.begin());
    box.hi[a] = int(last - in.begin());
  }
  return box;
}

void TranslationMapper::finish_map(int slot, std::size_t member, std::vector<float>& energy, MapStageSeconds* stages) {
  Slot& s = slot_[slot];
  auto t0 = std::chrono::steady_clock::now();
  // Re f at FFT index j: real[j] (fftw) or f[j].real() (clfft, vkfft).
  const float* real = nullptr;
  const Complex* f = s.f.data() + member * fft_index_.size();
#ifdef SNAPFIT_HAVE_FFTW
  if (fft_kind_ == MapFft::fftw) {
    host_fft_->fft.execute(slot);  // Re f = inverse FFT of the Hermitian part (kernels/full_map.cl)
    real = host_fft_->fft.real(slot);
    if (stages) {
      const auto t1 = std::chrono::steady_clock::now();
      stages->fft = std::chrono::duration<double>(t1 - t0).count();
      t0 = t1;
    }
  }
#endif
  aliasing_mask(s.R[member], inside_);
  const auto& inside = inside_;
  energy.resize(fft_index_.size());
  const float nan = std::numeric_limits<float>::quiet_NaN();
  std::size_t g = 0;
  for (int z = 0; z < grid_.dims.z(); ++z)
    for (int y = 0; y < grid_.dims.y(); ++y) {
      const bool row = inside[2][z] && inside[1][y];
      if (real)
        for (int x = 0; x < grid_.dims.x(); ++x, ++g) energy[g] = row && inside[0][x] ? -real[fft_index_[g]] : nan;
      else
        for (int x = 0; x < grid_.dims.x(); ++x, ++g) energy[g] = row && inside[0][x] ? -f[fft_index_[g]].real() : nan;
    }
  if (stages) stages->host = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// Waits for the slot's read once, and marks the member collected.
void TranslationMapper::wait_for(int slot, std::size_t member) {
  Slot& s = slot_[slot];
  if (slot < 0 || slot >= slots || member >= s.count || s.collected[member])
    throw Error("full map: slot " + std::to_string(slot) + " has no map " + std::to_string(member) + " submitted");
  if (s.pending) {
    try {
      s.read.wait();
    } catch (const cl::Error& e) {
      throw_device_error("full map failed", ctx_.device.info.name, e);
    }
    s.pending = false;
  }
  s.collected[member] = 1;
}

void TranslationMapper::collect(int slot, std::vector<float>& energy, std::size_t member) {
  if (slot >= 0 && slot < slots && map_fft_on_device(fft_kind_) && slot_[slot].output == MapOutput::minima)
    throw Error("full map: slot " + std::to_string(slot) + " was submitted for its minima (collect_minima)");
  wait_for(slot, member);
  finish_map(slot, member, energy, nullptr);
}

// map_minima and the lowest finite E on the whole map, on the host.
void TranslationMapper::host_minima(int slot, std::size_t member, std::size_t count, double separation,
                                    MapMinimaResult& out, MapStageSeconds* stages) {
  finish_map(slot, member, energy_, stages);
  const auto t0 = std::chrono::steady_clock::now();
  map_minima(grid_, energy_, count, separation, out);
  ++counts_.on_host;
  if (stages) stages->minima = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

void TranslationMapper::collect_minima(int slot, std::size_t count, double separation, MapMinimaResult& out,
                                       std::size_t member) {
  wait_for(slot, member);
  Slot& s = slot_[slot];
  if (!map_fft_on_device(fft_kind_) || s.output != MapOutput::minima) {
    host_minima(slot, member, count, separation, out, nullptr);
    return;
  }
  if (device_minima_->finish(side_, minima_list(slot, member), grid_, count, separation, out.minima, out.best)) {
    ++counts_.on_device;
    return;
  }
  // The list overflowed or E was infinite: the member's map is still on the device.
  ++counts_.fallbacks;
  const std::size_t n = fft_index_.size();
  s.f.resize(n * batch_);
  try {
    side_.enqueueReadBuffer(s.result, CL_TRUE, sizeof(Complex) * n * member, sizeof(Complex) * n,
                            s.f.data() + n * member);
  } catch (const cl::Error& e) {
    throw_device_error("full map failed", ctx_.device.info.name, e);
  }
  host_minima(slot, member, count, separation, out, nullptr);
}

MapMinimaCounts TranslationMapper::minima_counts() const {
  MapMinimaCounts c = counts_;
  if (device_minima_) {
    c.longest = device_minima_->stats().longest;
    c.long_lists = device_minima_->stats().long_lists;
  }
  return c;
}

// A stopwatch of consecutive stages: each call gives the seconds since the last.
class StageLap {
 public:
  double operator()() {
    const auto now = std::chrono::steady_clock::now();
    const double s = std::chrono::duration<double>(now - last_).count();
    last_ = now;
    return s;
  }

 private:
  std::chrono::steady_clock::time_point last_ = std::chrono::steady_clock::now();
};

void TranslationMapper::time_product_and_fft(const Eigen::Matrix3d& R, MapStageSeconds& t, StageLap& lap) {
  for (int s = 0; s < slots; ++s)
    if (slot_[s].pending) slot_[s].read.wait();
  slot_[0].pending = slot_[1].pending = false;
  Slot& s = slot_[0];
  s.count = 1;
  s.R[0] = R;
  std::fill(s.collected.begin(), s.collected.end(), 0);
  ctx_.queue.finish();
  lap();
  enqueue_product(0);
  ctx_.queue.finish();
  t.product = lap();
  if (map_fft_on_device(fft_kind_)) {
    enqueue_fft(0);
    ctx_.queue.finish();
    t.fft = lap();
  }
}

MapStageSeconds TranslationMapper::time_stages(const Eigen::Matrix3d& R, std::vector<float>& energy) {
  MapStageSeconds t;
  StageLap lap;
  try {
    time_product_and_fft(R, t, lap);
    slot_[0].output = MapOutput::energy;
    cl::Event read;
    enqueue_read(0, &read);
    read.wait();
    t.read = lap();
  } catch (const cl::Error& e) {
    throw_device_error("full map failed", ctx_.device.info.name, e);
  }
  slot_[0].collected[0] = 1;
  finish_map(0, 0, energy, &t);
  return t;
}

MapStageSeconds TranslationMapper::time_minima_stages(const Eigen::Matrix3d& R, std::size_t count, double separation,
                                                      MapMinimaResult& out) {
  if (!map_fft_on_device(fft_kind_)) {
    MapStageSeconds t = time_stages(R, energy_);
    StageLap lap;
    map_minima(grid_, energy_, count, separation, out);
    t.minima = lap();
    return t;
  }
  MapStageSeconds t;
  StageLap lap;
  Slot& s = slot_[0];
  try {
    time_product_and_fft(R, t, lap);
    s.output = MapOutput::minima;
    device_minima_->enqueue_reduce(ctx_.queue, minima_list(0, 0), s.result, aliasing_box(R));
    ctx_.queue.finish();
    t.reduce = lap();
    enqueue_read(0, &s.read);
    s.read.wait();
    t.read = lap();
  } catch (const cl::Error& e) {
    throw_device_error("full map failed", ctx_.device.info.name, e);
  }
  s.pending = true;
  collect_minima(0, count, separation, out);
  t.minima = lap();
  return t;
}

TranslationMap TranslationMapper::map(const Eigen::Matrix3d& R) {
  TranslationMap out;
  out.grid = grid_;
  submit(0, R);
  collect(0, out.energy);
  return out;
}

std::size_t map_batch_limit(const ComputeContext& ctx, const std::array<std::size_t, 3>& dims, std::size_t wanted) {
  const double map_bytes = double(sizeof(Complex)) * double(dims[0]) * double(dims[1]) * double(dims[2]);
  const double largest = double(ctx.device.device.getInfo<CL_DEVICE_MAX_MEM_ALLOC_SIZE>());
  const double global = double(ctx.device.device.getInfo<CL_DEVICE_GLOBAL_MEM_SIZE>());
  const double fits = std::min(largest / map_bytes, global / (4.0 * 3.0 * map_bytes));
  return std::max<std::size_t>(1, std::min(wanted, fits < 1 ? std::size_t(1) : std::size_t(fits)));
}

TranslationMap translational_energy_map(const FftLibrary& library, const ComputeContext& ctx,
                                        const PairSpectra& spectra, const Eigen::Matrix3d& R,
                                        Interpolation interpolation, std::size_t modes,
                                        const ProgramCacheConfig& cache) {
  const auto start = std::chrono::steady_clock::now();
  TranslationMapper mapper(library, ctx, spectra, interpolation, modes, MapFft::clfft, cache);
  TranslationMap map = mapper.map(R);
  map.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return map;
}

}  // namespace snapfit
