#include <gtest/gtest.h>

#include <cstring>
#include <random>
#include <string>

#include "knoblab/control/framing.hpp"

namespace knoblab::control {
namespace {

void feed(FrameDecoder& d, std::string_view bytes) {
  while (!bytes.empty()) {
    auto area = d.write_area();
    ASSERT_FALSE(area.empty());
    const auto n = std::min(area.size(), bytes.size());
    std::memcpy(area.data(), bytes.data(), n);
    d.commit(n);
    bytes.remove_prefix(n);
  }
}

TEST(Framing, HeaderIsBigEndianLength) {
  const std::string f = encode_frame("abc");
  ASSERT_EQ(f.size(), 7u);
  EXPECT_EQ(f.substr(0, 4), std::string("\0\0\0\3", 4));
  EXPECT_EQ(f.substr(4), "abc");
  const std::string big = encode_frame(std::string(0xFE01, 'x'));
  EXPECT_EQ(big.substr(0, 4), std::string("\0\0\xFE\x01", 4));
}

TEST(Framing, EncodeRefusesPayloadAboveLimit) {
  EXPECT_NO_THROW(encode_frame(std::string(kMaxFramePayload, 'x')));
  EXPECT_THROW(encode_frame(std::string(kMaxFramePayload + 1, 'x')), std::length_error);
}

TEST(Framing, DecoderReassemblesFramesSplitAnywhere) {
  std::string stream;
  for (int i = 0; i < 50; ++i) stream += encode_frame(std::string(static_cast<std::size_t>(i * 37), char('a' + i % 26)));
  std::mt19937 rng(7);
  FrameDecoder d;
  int got = 0;
  for (std::size_t pos = 0; pos < stream.size();) {
    const std::size_t n = std::min<std::size_t>(stream.size() - pos, 1 + rng() % 300);
    feed(d, std::string_view(stream).substr(pos, n));
    pos += n;
    std::string_view payload;
    while (d.next(payload) == FrameDecoder::Status::Frame) {
      EXPECT_EQ(payload.size(), static_cast<std::size_t>(got * 37));
      EXPECT_EQ(payload.find_first_not_of(char('a' + got % 26)), std::string_view::npos);
      ++got;
    }
  }
  EXPECT_EQ(got, 50);
  EXPECT_EQ(d.buffered(), 0u);
}

TEST(Framing, OversizedIsKnownFromTheHeaderAlone) {
  FrameDecoder d;
  feed(d, std::string("\x00\x01\x00\x01", 4));  // 65537
  std::string_view payload;
  EXPECT_EQ(d.next(payload), FrameDecoder::Status::Oversized);
  EXPECT_EQ(d.announced_length(), 65537u);
  EXPECT_TRUE(d.write_area().empty()) << "an oversized stream accepts no more bytes";
  EXPECT_EQ(d.next(payload), FrameDecoder::Status::Oversized) << "and stays oversized";
}

TEST(Framing, LargestFrameFitsAndBufferNeverGrowsBeyondIt) {
  FrameDecoder d;
  EXPECT_EQ(d.write_area().size(), kFrameHeaderBytes + kMaxFramePayload);
  feed(d, encode_frame(std::string(kMaxFramePayload, 'y')));
  std::string_view payload;
  ASSERT_EQ(d.next(payload), FrameDecoder::Status::Frame);
  EXPECT_EQ(payload.size(), kMaxFramePayload);
}

TEST(Framing, ZeroLengthFrameIsAFrame) {
  FrameDecoder d;
  feed(d, std::string("\0\0\0\0", 4) + encode_frame("x"));
  std::string_view payload = "unchanged";
  ASSERT_EQ(d.next(payload), FrameDecoder::Status::Frame);
  EXPECT_TRUE(payload.empty());
  ASSERT_EQ(d.next(payload), FrameDecoder::Status::Frame);
  EXPECT_EQ(payload, "x");
  EXPECT_EQ(d.next(payload), FrameDecoder::Status::NeedMore);
}

}  // namespace
}  // namespace knoblab::control
