// The contact history cache: values survive exactly one step unless refreshed, keys are unordered id pairs,
// lookups stay correct under heavy probing, the hinted lookup agrees with the hashed one, and entries()/restore()
// round-trip in a deterministic order.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "contact/contact_cache.h"

// The store is generic in what it keeps per pair; one double here.
using ContactCache = polyfloe::contact::HistoryStore<double>;
using polyfloe::contact::make_key;

TEST(ContactCache, ValuesLiveOneStepUnlessRefreshed) {
  ContactCache c;
  EXPECT_EQ(c.previous(make_key(1, 2)), 0.0);
  c.store(make_key(2, 1), 0.5);  // order of the ids does not matter
  c.store(make_key(3, 4), -1.5);
  c.end_step();
  EXPECT_EQ(c.previous(make_key(1, 2)), 0.5);
  EXPECT_EQ(c.previous(make_key(4, 3)), -1.5);
  EXPECT_EQ(c.previous(make_key(1, 3)), 0.0);
  c.store(make_key(1, 2), 0.7);  // only this pair is still touching
  c.end_step();
  EXPECT_EQ(c.previous(make_key(1, 2)), 0.7);
  EXPECT_EQ(c.previous(make_key(3, 4)), 0.0);
  EXPECT_EQ(c.size(), 1u);
}

TEST(ContactCache, TensOfThousandsOfPairsReadBackAndEntriesComeSortedAndRestoreExactly) {
  std::mt19937_64 rng(5);
  ContactCache c;
  std::vector<std::pair<std::uint64_t, std::uint64_t>> keys;
  for (int i = 0; i < 50000; ++i) keys.emplace_back(rng() % 100000, 100000 + rng() % 100000);
  std::sort(keys.begin(), keys.end());
  keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
  for (std::size_t i = 0; i < keys.size(); ++i) c.store(make_key(keys[i].first, keys[i].second), 1.0 + i);
  c.end_step();
  for (std::size_t i = 0; i < keys.size(); ++i) ASSERT_EQ(c.previous(make_key(keys[i].second, keys[i].first)), 1.0 + i);
  EXPECT_EQ(c.previous(make_key(200001, 200002)), 0.0);
  const auto e = c.entries();
  ASSERT_EQ(e.size(), keys.size());
  for (std::size_t i = 1; i < e.size(); ++i)
    EXPECT_TRUE(e[i - 1].first.lo < e[i].first.lo ||
                (e[i - 1].first.lo == e[i].first.lo && e[i - 1].first.hi < e[i].first.hi));
  ContactCache d;
  d.restore(e);
  for (std::size_t i = 0; i < keys.size(); i += 97)
    EXPECT_EQ(d.previous(make_key(keys[i].first, keys[i].second)), 1.0 + i);
  EXPECT_EQ(d.entries(), e);
}

// The hinted lookup gives what the hashed one gives, whatever the hint: pairs in last step's order (the hint
// follows), shuffled, dropped and new pairs, and hints past the end.
TEST(ContactCache, HintedLookupAgreesWithTheHashedOne) {
  std::mt19937_64 rng(11);
  ContactCache c;
  std::vector<std::pair<std::uint64_t, std::uint64_t>> keys;
  for (int i = 0; i < 3000; ++i) keys.emplace_back(i, 5000 + rng() % 5000);
  for (std::size_t i = 0; i < keys.size(); ++i) c.store(make_key(keys[i].first, keys[i].second), 0.25 * i);
  c.end_step();
  std::size_t hint = 0;
  for (std::size_t i = 0; i < keys.size(); ++i) {
    ASSERT_EQ(c.previous(make_key(keys[i].first, keys[i].second), hint), 0.25 * i);
    ASSERT_EQ(hint, i + 1);  // in order: every lookup is the hinted entry
  }
  std::vector<std::size_t> order(keys.size() + 500);
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;  // i >= keys.size(): pairs never stored
  std::shuffle(order.begin(), order.end(), rng);
  for (std::size_t h0 : {std::size_t{0}, std::size_t{1234}, keys.size(), keys.size() + 77}) {
    hint = h0;
    for (std::size_t i : order) {
      const auto k = i < keys.size() ? make_key(keys[i].first, keys[i].second) : make_key(20000 + i, 30000 + i);
      const double want = i < keys.size() ? 0.25 * i : 0.0;
      ASSERT_EQ(c.previous(k, hint), want);
      ASSERT_EQ(c.previous(k), want);
    }
  }
}

TEST(ContactCache, StoresByPlaceAndGenerations) {
  // A caller that kept where it stored each pair reads last step's value by that place (no lookup); the generation
  // tells it whether the previous stores are the ones it made: one more per step, and a restore changes it too.
  ContactCache c;
  const std::uint64_t g0 = c.generation();
  const auto room = c.store_slots(3);
  room[0] = {make_key(1, 2), 0.25};
  room[1] = {make_key(5, 3), -0.5};
  room[2] = {make_key(7, 9), 2.0};
  c.end_step();
  EXPECT_EQ(c.generation(), g0 + 1);
  EXPECT_EQ(c.stored(0), 0.25);
  EXPECT_EQ(c.stored(1), -0.5);
  EXPECT_EQ(c.stored(2), 2.0);
  c.prepare_lookups();  // the index, built once; the lookups agree with the places
  EXPECT_EQ(c.previous(make_key(3, 5)), -0.5);
  c.store(make_key(9, 7), 1.0);
  c.end_step();
  EXPECT_EQ(c.generation(), g0 + 2);
  EXPECT_EQ(c.stored(0), 1.0);
  EXPECT_EQ(c.previous(make_key(7, 9)), 1.0);  // the index is rebuilt after a step, without being asked
  EXPECT_EQ(c.previous(make_key(1, 2)), 0.0);
  const auto entries = c.entries();
  ContactCache d;
  d.restore({{make_key(1, 2), 4.0}});
  d.restore(entries);
  EXPECT_EQ(d.generation(), 2u);
  EXPECT_EQ(d.previous(make_key(7, 9)), 1.0);
  EXPECT_EQ(d.previous(make_key(1, 2)), 0.0);
}
