#include "engine/maps/device_minima.h"

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <limits>

#include "engine/runtime/compute_context.h"
#include "engine/runtime/kernel_sources.h"
#include "snapfit/error.h"

namespace snapfit {
namespace {

// The counters before the list (kernels/map_minima.cl): length, lowest E > 0, infinities.
constexpr std::size_t kHeader = 4;
constexpr cl_uint kNoPositive = 0xffffffffu;
// What a slot's counters are reset to: static, since the write does not block.
const cl_uint kHeaderReset[kHeader] = {0, kNoPositive, 0, 0};

std::size_t env_size(const char* name, std::size_t fallback) {
  const char* v = std::getenv(name);
  return v && *v ? static_cast<std::size_t>(std::strtoull(v, nullptr, 10)) : fallback;
}

float as_float(cl_uint u) {
  float f;
  std::memcpy(&f, &u, sizeof f);
  return f;
}

}  // namespace

DeviceMinima::DeviceMinima(const ComputeContext& ctx, const std::array<std::size_t, 3>& dims, int slots,
                           const ProgramCacheConfig& cache)
    : ctx_(ctx), dims_(dims) {
  const std::size_t total = dims[0] * dims[1] * dims[2];
  if (total == 0 || total > std::size_t(std::numeric_limits<int>::max()) || slots < 1)
    throw Error("map minima: a map of " + std::to_string(dims[0]) + " x " + std::to_string(dims[1]) + " x " +
                std::to_string(dims[2]) + " points in " + std::to_string(slots) + " slots is not supported");
  const std::size_t bound = ((dims[0] + 1) / 2) * ((dims[1] + 1) / 2) * ((dims[2] + 1) / 2);
  capacity_ = std::max<std::size_t>(1, env_size("SNAPFIT_MINIMA_CAPACITY", bound));
  read_entries_ = std::min(read_entries_, capacity_);
  try {
    kernel_ = cl::Kernel(build_program(ctx, "map_minima", kernel_source("map_minima"), "-cl-std=CL1.2", cache).program,
                         "map_local_minima");
    const std::size_t kernel_max = kernel_.getWorkGroupInfo<CL_KERNEL_WORK_GROUP_SIZE>(ctx.device.device);
    const std::size_t item_max = ctx.device.device.getInfo<CL_DEVICE_MAX_WORK_ITEM_SIZES>().at(0);
    wg_ = std::max<std::size_t>(1, std::min({env_size("SNAPFIT_MINIMA_WG", 64), kernel_max, item_max}));
    for (int s = 0; s < slots; ++s)
      lists_.emplace_back(ctx.context, CL_MEM_READ_WRITE, sizeof(cl_uint) * (kHeader + 2 * capacity_));
    kernel_.setArg(1, cl_int4{{int(dims[0]), int(dims[1]), int(dims[2]), 0}});
    kernel_.setArg(4, cl_uint(std::min<std::size_t>(capacity_, std::numeric_limits<cl_uint>::max())));
  } catch (const cl::Error& e) {
    throw_device_error("map minima failed", ctx.device.info.name, e);
  }
  host_.assign(std::size_t(slots), std::vector<cl_uint>(kHeader + 2 * capacity_));
  read_.assign(std::size_t(slots), 0);
}

void DeviceMinima::enqueue_reduce(const cl::CommandQueue& queue, int slot, const cl::Buffer& f, const MapBox& box,
                                  std::size_t offset) {
  const cl::Buffer& list = lists_.at(std::size_t(slot));
  try {
    queue.enqueueWriteBuffer(list, CL_FALSE, 0, sizeof kHeaderReset, kHeaderReset);
    kernel_.setArg(0, f);
    kernel_.setArg(2, cl_int4{{box.lo[0], box.lo[1], box.lo[2], 0}});
    kernel_.setArg(3, cl_int4{{box.hi[0], box.hi[1], box.hi[2], 0}});
    kernel_.setArg(5, list);
    kernel_.setArg(6, cl_ulong(offset));
    queue.enqueueNDRangeKernel(kernel_, cl::NullRange,
                               cl::NDRange((dims_[0] + wg_ - 1) / wg_ * wg_, dims_[1], dims_[2]),
                               cl::NDRange(wg_, 1, 1));
  } catch (const cl::Error& e) {
    throw_device_error("map minima failed", ctx_.device.info.name, e);
  }
}

void DeviceMinima::enqueue_read(const cl::CommandQueue& queue, int slot, cl::Event* done) {
  std::vector<cl_uint>& host = host_.at(std::size_t(slot));
  read_[std::size_t(slot)] = read_entries_;
  try {
    queue.enqueueReadBuffer(lists_[std::size_t(slot)], CL_FALSE, 0, sizeof(cl_uint) * (kHeader + 2 * read_entries_),
                            host.data(), nullptr, done);
  } catch (const cl::Error& e) {
    throw_device_error("map minima failed", ctx_.device.info.name, e);
  }
}

bool DeviceMinima::finish(const cl::CommandQueue& side, int slot, const GridSpec& grid, std::size_t count,
                          double separation, std::vector<MapMinimum>& minima, float& best) {
  std::vector<cl_uint>& host = host_.at(std::size_t(slot));
  const std::size_t length = host[0];
  ++stats_.maps;
  stats_.longest = std::max(stats_.longest, length);
  if (host[2] != 0) {
    ++stats_.infinities;
    return false;
  }
  if (length > capacity_) {
    ++stats_.overflows;
    return false;
  }
  const std::size_t have = read_[std::size_t(slot)];
  if (length > have) {
    // The rest of the list, and longer reads from now on (maps of one search have lists
    // of similar lengths).
    ++stats_.long_lists;
    try {
      side.enqueueReadBuffer(lists_[std::size_t(slot)], CL_TRUE, sizeof(cl_uint) * (kHeader + 2 * have),
                             sizeof(cl_uint) * 2 * (length - have), host.data() + kHeader + 2 * have);
    } catch (const cl::Error& e) {
      throw_device_error("map minima failed", ctx_.device.info.name, e);
    }
    while (read_entries_ < length) read_entries_ *= 2;
    read_entries_ = std::min(read_entries_, capacity_);
  }
  // The lowest finite E: the first in grid order of the lowest (kernels/map_minima.cl),
  // as engine/maps/rotation_search.cpp takes it from the whole map.
  candidates_.clear();
  const cl_uint* entry = host.data() + kHeader;
  std::size_t lowest = 0;
  for (std::size_t k = 0; k < length; ++k) {
    const float e = as_float(entry[2 * k]);
    const std::size_t g = entry[2 * k + 1];
    const float low = as_float(entry[2 * lowest]);
    if (k == 0 || e < low || (e == low && g < entry[2 * lowest + 1])) lowest = k;
    if (e < 0) candidates_.push_back({g, grid.point(g), e});
  }
  if (length > 0)
    best = as_float(entry[2 * lowest]);
  else
    best = host[1] == kNoPositive ? std::numeric_limits<float>::quiet_NaN() : as_float(host[1]);
  thin_minima(candidates_, count, separation, minima);
  return true;
}

}  // namespace snapfit
