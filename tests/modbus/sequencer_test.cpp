// Exactly-once delivery from repeated reads of the biometrics ring.
#include <gtest/gtest.h>

#include <vector>

#include "knoblab/modbus/sample_sequencer.hpp"

namespace knoblab::modbus {
namespace {

// The box's ring after it has taken samples 1..latest.
BiometricsSnapshot box_after(std::uint32_t latest) {
  BiometricsSnapshot s;
  s.latest_counter = latest;
  for (std::uint32_t c = latest > bio::kRingSize ? latest - bio::kRingSize + 1 : 1; c <= latest && c != 0; ++c) {
    s.ring[c % bio::kRingSize].counter = c;
  }
  return s;
}

std::vector<std::uint32_t> counters(const SampleSequencer::Batch& b) {
  std::vector<std::uint32_t> out;
  for (std::size_t i = 0; i < b.count; ++i) out.push_back(b.samples[i].counter);
  return out;
}

TEST(Sequencer, NothingBeforeTheFirstSample) {
  SampleSequencer q;
  EXPECT_EQ(q.accept(box_after(0)).count, 0u);
  EXPECT_FALSE(q.has_last());
}

TEST(Sequencer, FirstReadYieldsOnlyTheNewestThenEachSampleOnce) {
  SampleSequencer q;
  EXPECT_EQ(counters(q.accept(box_after(5))), (std::vector<std::uint32_t>{5}));
  EXPECT_EQ(q.accept(box_after(5)).count, 0u);  // polled again before the next sample
  EXPECT_EQ(counters(q.accept(box_after(6))), (std::vector<std::uint32_t>{6}));
  EXPECT_EQ(counters(q.accept(box_after(9))), (std::vector<std::uint32_t>{7, 8, 9}));  // a late poll
  EXPECT_EQ(q.missed(), 0u);
}

TEST(Sequencer, GapsLongerThanTheRingAreCountedMissed) {
  SampleSequencer q;
  q.accept(box_after(10));
  const auto b = q.accept(box_after(30));
  EXPECT_EQ(b.count, bio::kRingSize);
  EXPECT_EQ(b.samples[0].counter, 30u - bio::kRingSize + 1);
  EXPECT_EQ(q.missed(), 20u - bio::kRingSize);
}

TEST(Sequencer, CounterGoingBackwardsIsARestart) {
  SampleSequencer q;
  q.accept(box_after(100));
  EXPECT_EQ(counters(q.accept(box_after(3))), (std::vector<std::uint32_t>{3}));
  EXPECT_EQ(q.restarts(), 1u);
  EXPECT_EQ(counters(q.accept(box_after(4))), (std::vector<std::uint32_t>{4}));
}

TEST(Sequencer, CounterWrapIsNotARestart) {
  SampleSequencer q;
  BiometricsSnapshot s;
  s.latest_counter = 0xFFFFFFFFu;
  s.ring[0xFFFFFFFFu % bio::kRingSize].counter = 0xFFFFFFFFu;
  q.accept(s);
  s.latest_counter = 1;  // the box went …FFFF, 0, 1; we poll at 1
  s.ring[0].counter = 0;
  s.ring[1].counter = 1;
  EXPECT_EQ(counters(q.accept(s)), (std::vector<std::uint32_t>{0, 1}));
  EXPECT_EQ(q.restarts(), 0u);
}

TEST(Sequencer, TornRecordsAreNotDelivered) {
  SampleSequencer q;
  q.accept(box_after(8));
  auto s = box_after(10);
  s.ring[9 % bio::kRingSize].counter = 1;  // slot not rewritten yet
  EXPECT_EQ(counters(q.accept(s)), (std::vector<std::uint32_t>{10}));
  EXPECT_EQ(q.missed(), 1u);
}

}  // namespace
}  // namespace knoblab::modbus
