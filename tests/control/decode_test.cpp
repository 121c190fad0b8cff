// decode_request on its own: every way a payload is refused, and the code
// each one gets.
#include <gtest/gtest.h>

#include <string>

#include "knoblab/control/decode.hpp"

namespace knoblab::control {
namespace {

using nlohmann::json;

struct Case {
  std::string name;
  std::string payload;
  ErrorCode code;
  std::string key = {};  // bad_args: expected key path
};

void PrintTo(const Case& c, std::ostream* os) { *os << c.name; }

class DecodeRejects : public ::testing::TestWithParam<Case> {};

TEST_P(DecodeRejects, WithTheRightCode) {
  const Case& c = GetParam();
  const auto decoded = decode_request(c.payload);
  const auto* r = std::get_if<Rejection>(&decoded);
  ASSERT_NE(r, nullptr) << c.name << " was accepted";
  EXPECT_EQ(to_string(r->error.code), to_string(c.code)) << r->error.message;
  EXPECT_FALSE(r->error.message.empty());
  if (c.code == ErrorCode::bad_args) {
    EXPECT_EQ(r->error.key, c.key) << r->error.message;
    EXPECT_NE(r->error.message.find(c.key), std::string::npos) << "message must name the key: " << r->error.message;
  }
}

std::string deep(int levels, char open, char close) {
  return std::string(static_cast<std::size_t>(levels), open) + std::string(static_cast<std::size_t>(levels), close);
}

std::string deep_object(int levels) {
  std::string s;
  for (int i = 0; i < levels; ++i) s += "{\"a\":";
  s += "1";
  s += std::string(static_cast<std::size_t>(levels), '}');
  return s;
}

INSTANTIATE_TEST_SUITE_P(
    AllCodes, DecodeRejects,
    ::testing::Values(
        Case{"empty", "", ErrorCode::bad_frame},
        Case{"lone_continuation_byte", R"({"v":1,"id":1,"cmd":"ping","args":{"x":")" "\x80" R"("}})", ErrorCode::bad_frame},
        Case{"overlong_slash", "{\"v\":1,\"id\":1,\"cmd\":\"\xC0\xAF\"}", ErrorCode::bad_frame},
        Case{"utf16_surrogate", "{\"v\":1,\"id\":1,\"cmd\":\"\xED\xA0\x80\"}", ErrorCode::bad_frame},
        Case{"above_u10ffff", "{\"v\":1,\"id\":1,\"cmd\":\"\xF4\x90\x80\x80\"}", ErrorCode::bad_frame},
        Case{"truncated_sequence_at_end", "{\"v\":1}\xE2\x82", ErrorCode::bad_frame},
        Case{"latin1_byte", "{\"v\":1,\"id\":1,\"cmd\":\"caf\xE9\"}", ErrorCode::bad_frame},
        Case{"deep_array_33", deep(33, '[', ']'), ErrorCode::bad_json},
        Case{"deep_array_100000_unbalanced", std::string(100000, '['), ErrorCode::bad_json},
        Case{"deep_object_40", deep_object(40), ErrorCode::bad_json},
        Case{"truncated_json", R"({"v":1,"id":1,)", ErrorCode::bad_json},
        Case{"single_quotes", "{'v':1}", ErrorCode::bad_json},
        Case{"trailing_garbage", R"({"v":1,"id":1,"cmd":"ping"} x)", ErrorCode::bad_json},
        Case{"nan_literal", R"({"v":1,"id":1,"cmd":"set_params","args":{"B_vel":NaN}})", ErrorCode::bad_json},
        Case{"number_overflow", R"({"v":1,"id":1,"cmd":"set_params","args":{"B_vel":1e400}})", ErrorCode::bad_json},
        Case{"raw_control_char", std::string("{\"v\":1,\"id\":1,\"cmd\":\"pi\0ng\"}", 28), ErrorCode::bad_json},
        Case{"whitespace_only", "   ", ErrorCode::bad_json},
        Case{"array", "[1,2]", ErrorCode::not_an_object},
        Case{"number", "42", ErrorCode::not_an_object},
        Case{"string", R"("ping")", ErrorCode::not_an_object},
        Case{"null", "null", ErrorCode::not_an_object},
        Case{"deep_array_32_is_only_not_an_object", deep(32, '[', ']'), ErrorCode::not_an_object},
        Case{"missing_v", R"({"id":1,"cmd":"ping"})", ErrorCode::unsupported_version},
        Case{"v2", R"({"v":2,"id":1,"cmd":"ping"})", ErrorCode::unsupported_version},
        Case{"v_string", R"({"v":"1","id":1,"cmd":"ping"})", ErrorCode::unsupported_version},
        Case{"v_float", R"({"v":1.0,"id":1,"cmd":"ping"})", ErrorCode::unsupported_version},
        Case{"v0", R"({"v":0,"id":1,"cmd":"ping"})", ErrorCode::unsupported_version},
        Case{"missing_id", R"({"v":1,"cmd":"ping"})", ErrorCode::bad_args, "id"},
        Case{"id_string", R"({"v":1,"id":"1","cmd":"ping"})", ErrorCode::bad_args, "id"},
        Case{"id_float", R"({"v":1,"id":1.5,"cmd":"ping"})", ErrorCode::bad_args, "id"},
        Case{"id_above_int64", R"({"v":1,"id":9223372036854775808,"cmd":"ping"})", ErrorCode::bad_args, "id"},
        Case{"id_huge", R"({"v":1,"id":123456789012345678901234567890,"cmd":"ping"})", ErrorCode::bad_args, "id"},
        Case{"unknown_envelope_key", R"({"v":1,"id":1,"cmd":"ping","arg":{}})", ErrorCode::bad_args, "arg"},
        Case{"event_from_client", R"({"v":1,"event":"state","data":{}})", ErrorCode::bad_args, "data"},
        Case{"missing_cmd", R"({"v":1,"id":1})", ErrorCode::bad_args, "cmd"},
        Case{"cmd_number", R"({"v":1,"id":1,"cmd":7})", ErrorCode::bad_args, "cmd"},
        Case{"args_array", R"({"v":1,"id":1,"cmd":"ping","args":[]})", ErrorCode::bad_args, "args"},
        Case{"args_null", R"({"v":1,"id":1,"cmd":"ping","args":null})", ErrorCode::bad_args, "args"},
        Case{"unknown_arg", R"({"v":1,"id":1,"cmd":"ping","args":{"x":1}})", ErrorCode::bad_args, "x"},
        Case{"missing_required", R"({"v":1,"id":1,"cmd":"set_mode","args":{}})", ErrorCode::bad_args, "mode"},
        Case{"huge_value", R"({"v":1,"id":1,"cmd":"set_params","args":{"M_acc":1e300}})", ErrorCode::bad_args, "M_acc"},
        Case{"huge_integer_value", R"({"v":1,"id":1,"cmd":"hello","args":{"versions":[1],"watchdog_ms":99999999999999999999}})",
             ErrorCode::bad_args, "watchdog_ms"},
        Case{"nested_key", R"({"v":1,"id":1,"cmd":"start_capture","args":{"swept_sine":{"a":0,"b":1,"c":1,"d":"3"},"seconds":1,"knob":"k"}})",
             ErrorCode::bad_args, "swept_sine.d"},
        Case{"unknown_command", R"({"v":1,"id":1,"cmd":"reboot"})", ErrorCode::unknown_command},
        Case{"command_names_are_case_sensitive", R"({"v":1,"id":1,"cmd":"PING"})", ErrorCode::unknown_command},
        Case{"empty_command", R"({"v":1,"id":1,"cmd":""})", ErrorCode::unknown_command}),
    [](const auto& case_info) { return case_info.param.name; });

TEST(Decode, IdIsEchoedWhenReadableEvenIfTheRestIsWrong) {
  for (const char* p : {R"({"v":2,"id":17,"cmd":"ping"})", R"({"v":1,"id":17,"cmd":"nope"})",
                        R"({"v":1,"id":17,"cmd":"set_mode","args":{"mode":"fast"}})"}) {
    const auto d = decode_request(p);
    ASSERT_TRUE(std::holds_alternative<Rejection>(d)) << p;
    EXPECT_EQ(std::get<Rejection>(d).id, std::optional<std::int64_t>(17)) << p;
  }
  const auto d = decode_request("[]");
  EXPECT_EQ(std::get<Rejection>(d).id, std::nullopt);
}

TEST(Decode, ValidRequestKeepsIdCommandAndArgs) {
  const auto d = decode_request(R"({"v":1,"id":-5,"cmd":"set_mode","args":{"mode":"render"}})");
  const auto* r = std::get_if<Request>(&d);
  ASSERT_NE(r, nullptr);
  EXPECT_EQ(r->id, -5);
  EXPECT_EQ(r->command, Command::set_mode);
  EXPECT_EQ(r->args, json({{"mode", "render"}}));
}

TEST(Decode, ArgsMayBeOmittedForCommandsWithoutRequiredArgs) {
  const auto d = decode_request(R"({"v":1,"id":1,"cmd":"get_state"})");
  ASSERT_TRUE(std::holds_alternative<Request>(d));
  EXPECT_EQ(std::get<Request>(d).args, json::object());
}

TEST(Decode, WellFormedUnicodeIsAccepted) {
  // é, €, 𝄞 (4 bytes) and brackets inside strings, which the depth scan must skip
  const std::string knob = "caf\xC3\xA9 \xE2\x82\xAC \xF0\x9D\x84\x9E [[[[{{{{\\\"]]]";
  const std::string p = R"({"v":1,"id":1,"cmd":"start_capture","args":{"torque_sweep":{"a":0,"b":1,"c":0.01,"d":2},"seconds":2,"knob":")" +
                        knob + R"("}})";
  const auto d = decode_request(p);
  ASSERT_TRUE(std::holds_alternative<Request>(d)) << std::get<Rejection>(d).error.message;
}

TEST(Decode, ThirtyTwoLevelsAreAllowedThirtyThreeAreNot) {
  auto payload = [](int extra) {
    std::string nest = std::string(static_cast<std::size_t>(extra), '[') + std::string(static_cast<std::size_t>(extra), ']');
    return R"({"v":1,"id":1,"cmd":"ping","args":{"x":)" + nest + "}}";
  };
  // envelope (1) + args (2) + 30 arrays = 32: parsed, then refused by the schema
  EXPECT_EQ(std::get<Rejection>(decode_request(payload(30))).error.code, ErrorCode::bad_args);
  EXPECT_EQ(std::get<Rejection>(decode_request(payload(31))).error.code, ErrorCode::bad_json);
}

}  // namespace
}  // namespace knoblab::control
