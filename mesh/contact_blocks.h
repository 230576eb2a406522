#pragma once
// A part's contact samples (mesh/contact_samples.h) regrouped for the rigid contact's
// per-frame evaluation: small blocks of nearby points, and groups of nearby blocks, so
// that a broad phase skips a group, then a block, whose sphere lies clear of the other
// part. Each point is stored in single precision as its offset from its block's centre,
// one array per coordinate: offsets keep single precision's round-off relative to a
// block's size, not the part's; separate arrays let the per-point transform vectorize.
#include <cstddef>
#include <vector>

#include "mesh/contact_samples.h"
#include "mesh/shell_chunk.h"

namespace snapfit {

// The most points in a block: the evaluation keeps a block's per-point state on the stack.
constexpr std::size_t kMaxBlockPoints = 64;

struct ContactBlocks {
  std::vector<float> x, y, z;      // offset from the block's centre, scene units
  std::vector<float> area;         // scene units^2 each point stands for
  std::vector<ShellChunk> blocks;  // centre and radius in the part's frame; [begin, end) in the arrays
  std::vector<ShellChunk> groups;  // the same over blocks: [begin, end) in `blocks`
  std::size_t size() const { return x.size(); }
};

// The samples in blocks of cubes `block_size` across (scene units), split further so that
// none holds more than kMaxBlockPoints, in groups of cubes `group_size` across. Throws
// snapfit::Error for a size that is not positive.
ContactBlocks build_contact_blocks(const ContactSamples& samples, double block_size, double group_size);

}  // namespace snapfit
