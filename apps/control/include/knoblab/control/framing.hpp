// Length-prefixed framing: 4-byte big-endian payload length, then payload.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <string_view>

#include <nlohmann/json_fwd.hpp>

#include "knoblab/control/protocol.hpp"

namespace knoblab::control {

// Header + payload. Throws std::length_error above kMaxFramePayload.
std::string encode_frame(std::string_view payload);
// Serialises compactly (invalid UTF-8 in strings is replaced, never thrown)
// and frames. Throws std::length_error if the result exceeds a frame.
std::string encode_json_frame(const nlohmann::json& message);

// Splits a byte stream into frames. Its buffer is fixed at one maximal
// frame, so a peer can never make it grow: read() into write_area(), commit()
// what arrived, then take frames with next() until it says NeedMore.
class FrameDecoder {
 public:
  enum class Status { NeedMore, Frame, Oversized };

  explicit FrameDecoder(std::size_t max_payload = kMaxFramePayload);

  std::span<char> write_area() noexcept;
  void commit(std::size_t n) noexcept;

  // Frame: `payload` views the frame's bytes until the next write_area().
  // Oversized: the header announced more than max_payload; the stream cannot
  // be resynchronised, so the decoder stays in that state.
  Status next(std::string_view& payload) noexcept;

  std::size_t buffered() const noexcept { return end_ - begin_; }
  // The length of the announced frame, once its header is in (else 0).
  std::uint32_t announced_length() const noexcept { return announced_; }

 private:
  std::size_t max_payload_;
  std::size_t capacity_;
  std::unique_ptr<char[]> buf_;
  std::size_t begin_ = 0, end_ = 0;
  std::uint32_t announced_ = 0;
  bool oversized_ = false;
};

}  // namespace knoblab::control
