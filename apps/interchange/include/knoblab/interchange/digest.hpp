// SHA-256 digests that name the input of a stored result (its provenance):
// the bytes of a CSV file, or a capture's samples as the store holds them.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>

#include "knoblab/interchange/capture.hpp"

namespace knoblab::interchange {

// 64 lowercase hex digits.
std::string sha256_hex(std::string_view bytes);

// Of the file's bytes, as `sha256sum FILE` prints it. Throws
// std::runtime_error naming the file when it cannot be read.
std::string file_sha256(const std::filesystem::path& path);

// Of the samples alone (no metadata), so a capture hashes the same however
// its comments or status change. The bytes hashed: the line
// "knoblab samples v1: t theta omega alpha torque[ command] flags\n" (command
// only when the capture has it), then per row t, θ, ω, α, τ (and the command)
// as IEEE-754 binary64 little-endian, −0 written as +0 (sqlite keeps no sign
// of zero), and the row's flags as a little-endian uint32 (0 when the capture
// has none). docs/store.md gives an example.
std::string samples_sha256(const Capture& capture);

}  // namespace knoblab::interchange
