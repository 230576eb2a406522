// The query engine's real-time path (engine/query/query_engine.h): after set_modes, a query
// makes no heap allocation. Counted with a replaced global operator new around 1,000
// queries on the shipped peg-and-hole parts, 6-DOF (tricubic, with torque),
// translation-only and the exact product (background), single poses and batches no
// larger than an earlier one.
#include <atomic>
#include <cstdlib>
#include <doctest/doctest.h>
#include <new>
#include <vector>

#include "engine/query/query_engine.h"
#include "tests/allocation_count.h"
#include "tests/stability_support.h"

// Allocations made by a thread while counting is on (tests/allocation_count.h; the OpenCL
// runtime's own worker threads are not the frame's thread and are not counted).
thread_local bool snapfit::test::counting_allocations = false;
std::atomic<long> snapfit::test::allocations{0};

namespace {

using snapfit::test::CountAllocations;

void* counted_alloc(std::size_t size) {
  if (snapfit::test::counting_allocations) snapfit::test::allocations.fetch_add(1, std::memory_order_relaxed);
  if (void* p = std::malloc(size ? size : 1)) return p;
  throw std::bad_alloc();
}

void* counted_aligned_alloc(std::size_t size, std::align_val_t align) {
  if (snapfit::test::counting_allocations) snapfit::test::allocations.fetch_add(1, std::memory_order_relaxed);
  const std::size_t a = static_cast<std::size_t>(align);
  if (void* p = std::aligned_alloc(a, (size + a - 1) / a * a)) return p;
  throw std::bad_alloc();
}

}  // namespace

void* operator new(std::size_t size) { return counted_alloc(size); }
void* operator new[](std::size_t size) { return counted_alloc(size); }
void* operator new(std::size_t size, const std::nothrow_t&) noexcept {
  try {
    return counted_alloc(size);
  } catch (...) {
    return nullptr;
  }
}
void* operator new[](std::size_t size, const std::nothrow_t& tag) noexcept { return operator new(size, tag); }
void* operator new(std::size_t size, std::align_val_t align) { return counted_aligned_alloc(size, align); }
void* operator new[](std::size_t size, std::align_val_t align) { return counted_aligned_alloc(size, align); }
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }
void operator delete(void* p, std::align_val_t) noexcept { std::free(p); }
void operator delete[](void* p, std::align_val_t) noexcept { std::free(p); }
void operator delete(void* p, std::size_t, std::align_val_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t, std::align_val_t) noexcept { std::free(p); }

namespace snapfit {

TEST_CASE("query engine: the allocation counter sees a plain new") {
  CountAllocations count;
  auto* p = new std::vector<int>(10);
  delete p;
  CHECK(count.count() == 2);  // the vector and its storage
}

TEST_CASE("query engine: no heap allocation per query after set_modes, 6-DOF and translation-only") {
  Scene scene = test::small_peg_hole_scene();
  for (const bool translation : {false, true}) {
    CAPTURE(translation);
    if (translation) {
      scene.motion = Motion::translation;
      scene.outputs.torque = false;
    }
    const AssemblyPair pair = test::build_small_pair(scene);
    auto engine = make_query_engine(test::test_context(), pair.spectra,
                                    query_variant_for(scene, Interpolation::tricubic), test::test_program_cache());
    const Pose assembled = *scene.assembled_pose;
    std::vector<Pose> batch;
    for (int i = 0; i < 8; ++i) batch.push_back(test::pose_at(assembled.translation + Eigen::Vector3d(0.1 * i, 0, 1)));
    std::vector<QueryResult> results(batch.size());
    for (const std::size_t modes : {std::size_t(1000), std::size_t(4096), engine->max_modes()}) {
      CAPTURE(modes);
      engine->set_modes(modes);
      engine->query_batch(batch.data(), batch.size(), results.data());  // the batch scratch, once
      double sum = 0;
      CountAllocations count;
      for (int i = 0; i < 1000; ++i) {
        Pose pose = assembled;
        pose.translation.z() += 0.002 * i;
        const QueryResult r = engine->query(pose);
        REQUIRE(r.flags == query_ok);
        sum += r.energy;
      }
      for (int i = 0; i < 10; ++i) engine->query_batch(batch.data(), batch.size() - i % 4, results.data());
      CHECK(count.count() == 0);
      CHECK(std::isfinite(sum));
    }
  }
}

TEST_CASE("query engine: no heap allocation per query on the exact product's frame path, the part turning") {
  const Scene scene = test::small_peg_hole_scene();
  const AssemblyPair pair = test::build_small_pair(scene);
  QueryVariant variant = query_variant_for(scene, Interpolation::tricubic);
  variant.rotation = RotationMethod::exact_product;
  variant.product_update = ProductUpdate::background;  // the worker thread's own allocations are not counted
  auto engine = make_query_engine(test::test_context(), pair.spectra, variant, test::test_program_cache());
  engine->set_modes(4096);
  const Pose assembled = *scene.assembled_pose;
  engine->query(assembled);  // the first product
  double sum = 0;
  CountAllocations count;
  for (int i = 0; i < 1000; ++i) {
    Pose pose = assembled;
    pose.translation.z() += 0.002 * i;
    pose.rotation = Eigen::Quaterniond(Eigen::AngleAxisd(1e-4 * i, Eigen::Vector3d::UnitX())) * assembled.rotation;
    const QueryResult r = engine->query(pose);
    REQUIRE(r.flags == query_ok);
    sum += r.energy;
  }
  CHECK(count.count() == 0);
  CHECK(std::isfinite(sum));
}

}  // namespace snapfit
