// Schema 3: per-sample loop flags and the biometrics table.
#include <gtest/gtest.h>

#include "knoblab/store/store.hpp"
#include "test_util.hpp"

namespace knoblab::store::test {
namespace {

TEST(Flags, TravelWithEachSample) {
  TempDir dir;
  Store store = Store::open(dir / "s.db");
  NewCapture info;
  info.rate_hz = 10000;
  info.source = "hapticd";
  WriterOptions options;
  options.batch_size = 3;
  CaptureWriter w = store.begin_capture(info, options);
  for (int i = 0; i < 7; ++i) {
    Sample s;
    s.t = i * 1e-4;
    s.flags = static_cast<std::uint32_t>(i % 2 ? interchange::kAmpEnabled
                                               : interchange::kEstopActive | interchange::kFaultLatched);
    w.append(s);
  }
  w.finish();
  const interchange::Capture c = store.load_samples(w.capture_id());
  ASSERT_EQ(c.flags.size(), 7u);
  EXPECT_EQ(c.flags[0], interchange::kEstopActive | interchange::kFaultLatched);
  EXPECT_EQ(c.flags[1], interchange::kAmpEnabled);
  EXPECT_EQ(c.flags[6], interchange::kEstopActive | interchange::kFaultLatched);
}

TEST(Biometrics, AppendAndLoadInOrderAndRefuseDuplicates) {
  TempDir dir;
  Store store = Store::open(dir / "s.db");
  NewCapture info;
  info.rate_hz = 10000;
  info.source = "hapticd";
  CaptureWriter w = store.begin_capture(info);
  const std::vector<BiometricSample> a = {{2, 0.0625, 1e-6, -2e-6, 3e-6}, {1, 0.03125, 4e-6, 5e-6, 6e-6}};
  store.append_biometrics(w.capture_id(), a);
  const auto back = store.load_biometrics(w.capture_id());
  ASSERT_EQ(back.size(), 2u);
  EXPECT_EQ(back[0].seq, 1);
  EXPECT_EQ(back[1].emg_depressor, -2e-6);
  // A repeated sequence number is refused, and the whole batch with it.
  const std::vector<BiometricSample> dup = {{3, 0.09375, 0, 0, 0}, {2, 0.0625, 0, 0, 0}};
  EXPECT_THROW(store.append_biometrics(w.capture_id(), dup), StoreError);
  EXPECT_EQ(store.load_biometrics(w.capture_id()).size(), 2u);
  w.finish();
}

}  // namespace
}  // namespace knoblab::store::test
