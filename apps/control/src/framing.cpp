#include "knoblab/control/framing.hpp"

#include <cstring>
#include <stdexcept>

#include <nlohmann/json.hpp>

namespace knoblab::control {

std::string encode_frame(std::string_view payload) {
  if (payload.size() > kMaxFramePayload)
    throw std::length_error("frame payload of " + std::to_string(payload.size()) +
                            " bytes exceeds the " + std::to_string(kMaxFramePayload) + " byte limit");
  const auto n = static_cast<std::uint32_t>(payload.size());
  std::string frame;
  frame.reserve(kFrameHeaderBytes + payload.size());
  frame.push_back(static_cast<char>((n >> 24) & 0xFFu));
  frame.push_back(static_cast<char>((n >> 16) & 0xFFu));
  frame.push_back(static_cast<char>((n >> 8) & 0xFFu));
  frame.push_back(static_cast<char>(n & 0xFFu));
  frame.append(payload);
  return frame;
}

std::string encode_json_frame(const nlohmann::json& message) {
  return encode_frame(message.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace));
}

FrameDecoder::FrameDecoder(std::size_t max_payload)
    : max_payload_(max_payload),
      capacity_(kFrameHeaderBytes + max_payload),
      buf_(new char[kFrameHeaderBytes + max_payload]) {}

std::span<char> FrameDecoder::write_area() noexcept {
  if (oversized_) return {};
  // Keep the unread tail at the front so a whole frame always fits.
  if (begin_ > 0) {
    std::memmove(buf_.get(), buf_.get() + begin_, end_ - begin_);
    end_ -= begin_;
    begin_ = 0;
  }
  return {buf_.get() + end_, capacity_ - end_};
}

void FrameDecoder::commit(std::size_t n) noexcept { end_ += n; }

FrameDecoder::Status FrameDecoder::next(std::string_view& payload) noexcept {
  if (oversized_) return Status::Oversized;
  announced_ = 0;
  if (buffered() < kFrameHeaderBytes) return Status::NeedMore;
  const auto* h = reinterpret_cast<const unsigned char*>(buf_.get() + begin_);
  const std::uint32_t n = (std::uint32_t{h[0]} << 24) | (std::uint32_t{h[1]} << 16) |
                          (std::uint32_t{h[2]} << 8) | std::uint32_t{h[3]};
  announced_ = n;
  if (n > max_payload_) {
    oversized_ = true;
    return Status::Oversized;
  }
  if (buffered() < kFrameHeaderBytes + n) return Status::NeedMore;
  payload = std::string_view(buf_.get() + begin_ + kFrameHeaderBytes, n);
  begin_ += kFrameHeaderBytes + n;
  if (begin_ == end_) begin_ = end_ = 0;
  return Status::Frame;
}

}  // namespace knoblab::control
