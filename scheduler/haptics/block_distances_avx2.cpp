// block_distances four points at a time with AVX2: the transform and fractions in double,
// the cell arithmetic of FineDistanceView::node in 32-bit lanes; brick_of_cell and the
// corners are read point by point (AVX2's gathers were slower), the distances as
// FineDistanceView::value.
#include <climits>

#include "scheduler/haptics/block_distances.h"

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#include <immintrin.h>
#define SNAPFIT_BLOCK_DISTANCES_AVX2 1
#endif

namespace snapfit {

#ifdef SNAPFIT_BLOCK_DISTANCES_AVX2

bool block_distances_avx2_supported() { return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma"); }

namespace {

// The most fine cells a block's centre is lifted by: relative cells stay below 2^13,
// where the 16-bit multiply-shift below divides exactly.
constexpr int kMaxLift = 2048;

// What a lane's brick_of_cell read gives off the grid (neither a brick nor a code).
constexpr std::int32_t kOffGrid = INT_MIN;

// floor(a / b) for b > 0.
int floor_divide(int a, int b) { return a >= 0 ? a / b : -((-a + b - 1) / b); }

// The lane's fine cell must lie in [0, cells): `cell > -1 && cells > cell`.
__attribute__((target("avx2,fma"))) inline __m128i within(__m128i cell, __m128i cells) {
  return _mm_and_si128(_mm_cmpgt_epi32(cell, _mm_set1_epi32(-1)), _mm_cmpgt_epi32(cells, cell));
}

}  // namespace

__attribute__((target("avx2,fma"))) bool block_distances_avx2(const ContactBlocks& points, const ShellChunk& block,
                                                              const double to_fine[9],
                                                              const Eigen::Vector3d& centre_grid,
                                                              const SignedDistanceGrid& grid,
                                                              const FineDistanceView& view, BlockDistances& out) {
  const double per_spacing = 1 / grid.fine_spacing();
  const Eigen::Vector3d local = (centre_grid - grid.origin) * per_spacing;
  if (!(local.array().abs() < 1e9).all()) return false;
  const int lift = int(block.radius * per_spacing) + 2;
  const int r = view.refine();
  const std::size_t side = view.side();
  // 32-bit lanes hold brick_of_cell's index.
  if (lift > kMaxLift || r > 8 || double(view.coarse_xy()) * (double(view.fine_cells(2)) / r + 1) >= INT_MAX)
    return block_distances_portable(points, block, to_fine, centre_grid, grid, view, out);

  // As the portable form, with `base` on a coarse cell's lowest fine cell: a point's
  // coarse cell is base_coarse + c / r and its fine cell within it c mod r, c its fine
  // cell relative to base (0 <= c < 2^13: c / r = (c * ceil(2^16 / r)) >> 16).
  int base[3], base_coarse[3];
  double rest[3];
  for (int a = 0; a < 3; ++a) {
    base_coarse[a] = floor_divide(floor_to_int(local[a]) - lift, r);
    base[a] = base_coarse[a] * r, rest[a] = local[a] - base[a];
  }
  const __m256d m0 = _mm256_set1_pd(to_fine[0]), m1 = _mm256_set1_pd(to_fine[1]), m2 = _mm256_set1_pd(to_fine[2]),
                m3 = _mm256_set1_pd(to_fine[3]), m4 = _mm256_set1_pd(to_fine[4]), m5 = _mm256_set1_pd(to_fine[5]),
                m6 = _mm256_set1_pd(to_fine[6]), m7 = _mm256_set1_pd(to_fine[7]), m8 = _mm256_set1_pd(to_fine[8]);
  const __m256d rest_x = _mm256_set1_pd(rest[0]), rest_y = _mm256_set1_pd(rest[1]), rest_z = _mm256_set1_pd(rest[2]);
  const __m128i divide = _mm_set1_epi32((65536 + r - 1) / r), refine = _mm_set1_epi32(r);
  const __m128i base_x = _mm_set1_epi32(base[0]), base_y = _mm_set1_epi32(base[1]), base_z = _mm_set1_epi32(base[2]);
  const __m128i coarse_x = _mm_set1_epi32(base_coarse[0]), coarse_y = _mm_set1_epi32(base_coarse[1]),
                coarse_z = _mm_set1_epi32(base_coarse[2]);
  const __m128i cells_x = _mm_set1_epi32(int(view.fine_cells(0))), cells_y = _mm_set1_epi32(int(view.fine_cells(1))),
                cells_z = _mm_set1_epi32(int(view.fine_cells(2)));
  const __m128i stride_y = _mm_set1_epi32(int(view.coarse_x())), stride_z = _mm_set1_epi32(int(view.coarse_xy()));
  const __m128i node_y = _mm_set1_epi32(int(side)), node_z = _mm_set1_epi32(int(side * side));

  const std::size_t n = block.end - block.begin;
  const float *x = points.x.data() + block.begin, *y = points.y.data() + block.begin,
              *z = points.z.data() + block.begin;
  for (std::size_t i = 0; i < n; i += 4) {
    // Four points' offsets (the last group padded with the centre).
    __m128 xs, ys, zs;
    if (i + 4 <= n) {
      xs = _mm_loadu_ps(x + i), ys = _mm_loadu_ps(y + i), zs = _mm_loadu_ps(z + i);
    } else {
      alignas(16) float px[4] = {}, py[4] = {}, pz[4] = {};
      for (std::size_t l = 0; i + l < n; ++l) px[l] = x[i + l], py[l] = y[i + l], pz[l] = z[i + l];
      xs = _mm_load_ps(px), ys = _mm_load_ps(py), zs = _mm_load_ps(pz);
    }
    const __m256d dx = _mm256_cvtps_pd(xs), dy = _mm256_cvtps_pd(ys), dz = _mm256_cvtps_pd(zs);
    const __m256d u = _mm256_fmadd_pd(m2, dz, _mm256_fmadd_pd(m1, dy, _mm256_fmadd_pd(m0, dx, rest_x)));
    const __m256d v = _mm256_fmadd_pd(m5, dz, _mm256_fmadd_pd(m4, dy, _mm256_fmadd_pd(m3, dx, rest_y)));
    const __m256d w = _mm256_fmadd_pd(m8, dz, _mm256_fmadd_pd(m7, dy, _mm256_fmadd_pd(m6, dx, rest_z)));
    const __m128i ci = _mm256_cvttpd_epi32(u), cj = _mm256_cvttpd_epi32(v), ck = _mm256_cvttpd_epi32(w);
    const __m256d fx = _mm256_sub_pd(u, _mm256_cvtepi32_pd(ci)), fy = _mm256_sub_pd(v, _mm256_cvtepi32_pd(cj)),
                  fz = _mm256_sub_pd(w, _mm256_cvtepi32_pd(ck));
    _mm256_storeu_pd(out.fx + i, fx), _mm256_storeu_pd(out.fy + i, fy), _mm256_storeu_pd(out.fz + i, fz);

    // The coarse cell and the fine cell within it (FineDistanceView::node).
    const __m128i qi = _mm_srli_epi32(_mm_mullo_epi32(ci, divide), 16),
                  qj = _mm_srli_epi32(_mm_mullo_epi32(cj, divide), 16),
                  qk = _mm_srli_epi32(_mm_mullo_epi32(ck, divide), 16);
    const __m128i si = _mm_sub_epi32(ci, _mm_mullo_epi32(qi, refine)),
                  sj = _mm_sub_epi32(cj, _mm_mullo_epi32(qj, refine)),
                  sk = _mm_sub_epi32(ck, _mm_mullo_epi32(qk, refine));
    const __m128i on = _mm_and_si128(within(_mm_add_epi32(ci, base_x), cells_x),
                                     _mm_and_si128(within(_mm_add_epi32(cj, base_y), cells_y),
                                                   within(_mm_add_epi32(ck, base_z), cells_z)));
    const __m128i cell = _mm_add_epi32(_mm_add_epi32(qi, coarse_x),
                                       _mm_add_epi32(_mm_mullo_epi32(_mm_add_epi32(qj, coarse_y), stride_y),
                                                     _mm_mullo_epi32(_mm_add_epi32(qk, coarse_z), stride_z)));
    alignas(16) std::int32_t lane_cell[4], lane_on[4], lane_sub[4];
    _mm_store_si128(reinterpret_cast<__m128i*>(lane_cell), cell);
    _mm_store_si128(reinterpret_cast<__m128i*>(lane_on), on);
    _mm_store_si128(reinterpret_cast<__m128i*>(lane_sub),
                    _mm_add_epi32(si, _mm_add_epi32(_mm_mullo_epi32(sj, node_y), _mm_mullo_epi32(sk, node_z))));
    // Each lane's brick (scalar reads: gathers were slower), its cell's corners fetched ahead.
    for (std::size_t l = 0; l < 4 && i + l < n; ++l) {
      const std::int32_t brick = lane_on[l] ? view.brick_of_cell()[lane_cell[l]] : kOffGrid;
      const std::int16_t* node =
          brick >= 0 ? view.bricks() + std::size_t(brick) * view.brick_nodes() + lane_sub[l] : nullptr;
      if (node) view.prefetch(node);
      out.node[i + l] = node, out.outside[i + l] = brick == kCoarseOutside;
    }
  }
  for (std::size_t i = 0; i < n; ++i)
    if (out.node[i]) out.phi[i] = view.value(out.node[i], out.fx[i], out.fy[i], out.fz[i]);
  return true;
}

#else

bool block_distances_avx2_supported() { return false; }

bool block_distances_avx2(const ContactBlocks& points, const ShellChunk& block, const double to_fine[9],
                          const Eigen::Vector3d& centre_grid, const SignedDistanceGrid& grid,
                          const FineDistanceView& view, BlockDistances& out) {
  return block_distances_portable(points, block, to_fine, centre_grid, grid, view, out);
}

#endif

}  // namespace snapfit
