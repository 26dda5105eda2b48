// No heap allocation in the step once it is warm: a jammed pack (4 contacts per floe, contact history, every drift
// term, walls) stepped with 1 and 2 threads allocates nothing after the first steps have sized the scratch
// (counted by replacing the global operator new of this test executable).
#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <new>

#include "dense_pack.h"
#include "dynamics/world.h"
#include "forcing/analytic_fields.h"

namespace {
std::atomic<long> g_allocations{0};
}

// The replacements pair malloc with free; GCC, seeing both inlined at -O2, takes the free in operator delete for a
// mismatch with the operator new of the call site.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"
#endif

void* operator new(std::size_t n) {
  g_allocations.fetch_add(1, std::memory_order_relaxed);
  if (void* p = std::malloc(n ? n : 1)) return p;
  throw std::bad_alloc();
}
void* operator new[](std::size_t n) {
  g_allocations.fetch_add(1, std::memory_order_relaxed);
  if (void* p = std::malloc(n ? n : 1)) return p;
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }

using namespace polyfloe;

namespace {

long allocations_in_steps(int threads) {
  const tsupport::Pack pack = tsupport::make_pack(400, tsupport::PackSpec{}, 3u);
  dynamics::WorldSettings ws;
  ws.drift.ocean = forcing::make_field(forcing::FieldSpec::uniform({0.2, 0.05}));
  ws.drift.wind = forcing::make_field(forcing::FieldSpec::uniform({8.0, 6.0}));
  ws.contact.friction = 0.3;
  dynamics::World w(ws);
  w.set_threads(threads);
  for (const auto& d : pack.bodies) w.add_body(d);
  const double dt = w.shortest_contact_duration(1.0) / 40.0;
  w.compute_forces(0.0);
  const long cold = g_allocations.load();
  w.step(dt);
  EXPECT_GT(g_allocations.load(), cold) << "the first step sizes its scratch: the counter must see it";
  for (int k = 0; k < 20; ++k) w.step(dt);  // warm: scratch sized, contact history filled
  EXPECT_GT(w.contacts().size(), pack.bodies.size()) << "the pack must be jammed";
  const long before = g_allocations.load();
  for (int k = 0; k < 200; ++k) w.step(dt);
  return g_allocations.load() - before;
}

}  // namespace

TEST(StepAllocation, WarmStepAllocatesNothingOneThread) { EXPECT_EQ(allocations_in_steps(1), 0); }

TEST(StepAllocation, WarmStepAllocatesNothingTwoThreads) { EXPECT_EQ(allocations_in_steps(2), 0); }
