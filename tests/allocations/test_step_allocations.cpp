// After its first steps, a step allocates nothing on the heap: every node, particle and scratch
// array keeps its capacity from step to step. This binary replaces the global operator new with a
// counting one, so the assertion covers the solver and every library it calls (Eigen, the
// standard library, OpenMP's runtime).
#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <new>
#include <string>

#include "fragmpm/mpm/solver.hpp"
#include "fragmpm/pipeline/scene.hpp"

namespace {
std::atomic<long long> allocations{0};
}  // namespace

void* operator new(std::size_t size) {
  allocations.fetch_add(1, std::memory_order_relaxed);
  if (void* p = std::malloc(size ? size : 1)) return p;
  throw std::bad_alloc();
}
void* operator new[](std::size_t size) {
  return operator new(size);
}
void* operator new(std::size_t size, std::align_val_t align) {
  allocations.fetch_add(1, std::memory_order_relaxed);
  const std::size_t a = static_cast<std::size_t>(align);
  if (void* p = std::aligned_alloc(a, (size + a - 1) / a * a)) return p;
  throw std::bad_alloc();
}
void* operator new[](std::size_t size, std::align_val_t align) {
  return operator new(size, align);
}
void operator delete(void* p) noexcept {
  std::free(p);
}
void operator delete[](void* p) noexcept {
  std::free(p);
}
void operator delete(void* p, std::size_t) noexcept {
  std::free(p);
}
void operator delete[](void* p, std::size_t) noexcept {
  std::free(p);
}
void operator delete(void* p, std::align_val_t) noexcept {
  std::free(p);
}
void operator delete[](void* p, std::align_val_t) noexcept {
  std::free(p);
}
void operator delete(void* p, std::size_t, std::align_val_t) noexcept {
  std::free(p);
}
void operator delete[](void* p, std::size_t, std::align_val_t) noexcept {
  std::free(p);
}

namespace {

using fragmpm::mpm::Solver;

/// Heap allocations during steps 10-20 of the scene (after 10 steps that size every array).
long long allocations_in_steps_10_to_20(const std::string& scene) {
  Solver<2> solver(fragmpm::pipeline::load_scene(std::string(FRAGMPM_SOURCE_DIR) + "/" + scene));
  for (int k = 0; k < 10; ++k) EXPECT_FALSE(solver.step().has_value());
  const long long before = allocations.load();
  for (int k = 0; k < 10; ++k) EXPECT_FALSE(solver.step().has_value());
  return allocations.load() - before;
}

}  // namespace

// Partitioned (three bodies with surface flags), thermal (conduction, friction and structural
// heating), three walls (two contact walls, one fixed) and a traction load.
TEST(StepAllocations, PartitionedThermalSceneWithWallsAndLoadsAllocatesNothing) {
  EXPECT_EQ(allocations_in_steps_10_to_20("scenes/paper/disk-squish-coupled.toml"), 0);
}

// Damage with Weibull strengths and traction loads (the Brazilian disk).
TEST(StepAllocations, DamagingSceneAllocatesNothing) {
  EXPECT_EQ(allocations_in_steps_10_to_20("scenes/paper/brazilian.toml"), 0);
}

// The phase-field stage keeps its node, band and matrix arrays from step to step. (Eigen's
// conjugate gradients take four work vectors of the unknowns' length inside each solve from
// Eigen's aligned allocator, which calls malloc, not operator new: this counter does not see
// them.)
TEST(StepAllocations, PhaseFieldSceneAllocatesNothingThroughNew) {
  EXPECT_EQ(allocations_in_steps_10_to_20("scenes/verify/phase-field-bar.toml"), 0);
}

// The counter sees allocations at all (a test that cannot fail is no test).
TEST(StepAllocations, CounterCountsAVectorAllocation) {
  const long long before = allocations.load();
  auto* v = new std::string(100, 'x');
  EXPECT_GE(allocations.load() - before, 1);
  delete v;
}
