// The command table drives validation: these tests walk the table itself,
// so every key of every command is covered, including ones added later.
#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "knoblab/control/schema.hpp"

namespace knoblab::control {
namespace {

using nlohmann::json;

// A value that passes `spec` (for building arguments around the key under test).
json valid_value(const ArgSpec& spec) {
  switch (spec.type) {
    case ArgType::integer: return static_cast<std::int64_t>(spec.range.lo);
    case ArgType::number: return (spec.range.lo + spec.range.hi) / 2;
    case ArgType::string:
    case ArgType::label: return "k";
    case ArgType::boolean: return true;
    case ArgType::choice: return spec.choices.front();
    case ArgType::integer_list: return json::array({static_cast<std::int64_t>(spec.range.lo)});
    case ArgType::choice_list: return json::array({spec.choices.front()});
    case ArgType::number_list: {
      // Strictly increasing, enough elements: valid as knots too.
      json a = json::array();
      for (int i = 0; i < static_cast<int>(std::max(spec.size.lo, 1.0)); ++i) a.push_back(spec.range.lo + i);
      return a;
    }
    case ArgType::object: {
      json o = json::object();
      for (const auto& a : spec.object->args) o[std::string(a.key)] = valid_value(a);
      return o;
    }
    case ArgType::object_list: {
      ArgSpec one = spec;
      one.type = ArgType::object;
      return json::array({valid_value(one)});
    }
  }
  return nullptr;
}

bool accepts_type(ArgType t, const json& v) {
  switch (t) {
    case ArgType::integer: return v.is_number_integer();
    case ArgType::number: return v.is_number();
    case ArgType::string: return v.is_string();
    case ArgType::boolean: return v.is_boolean();
    case ArgType::choice: return v.is_string();
    case ArgType::label: return v.is_string() || v.is_number_integer();
    case ArgType::integer_list:
    case ArgType::choice_list:
    case ArgType::number_list:
    case ArgType::object_list: return v.is_array();
    case ArgType::object: return v.is_object();
  }
  return false;
}

struct KeyUnderTest {
  Command command;
  std::string path;  // "pid.Kp", "position[0].f_vel.x"
  json::json_pointer pointer;
  const ArgSpec* spec;
  std::vector<const ArgSpec*> parents;
};

// Keys inside a list of objects are tested in its first element.
void collect(Command c, const ObjectSchema& schema, const std::string& prefix, json::json_pointer ptr,
             std::vector<const ArgSpec*> parents, std::vector<KeyUnderTest>& out) {
  for (const auto& a : schema.args) {
    const std::string key(a.key);
    out.push_back({c, prefix + key, ptr / key, &a, parents});
    if (a.type == ArgType::object || a.type == ArgType::object_list) {
      auto p = parents;
      p.push_back(&a);
      const bool list = a.type == ArgType::object_list;
      collect(c, *a.object, prefix + key + (list ? "[0]." : "."), list ? ptr / key / 0 : ptr / key, p, out);
    }
  }
}

std::vector<KeyUnderTest> every_key() {
  std::vector<KeyUnderTest> out;
  for (const auto& c : command_table()) collect(c.command, c.args, "", json::json_pointer(), {}, out);
  return out;
}

// The command's example with `key` set to `value` (parents filled in validly).
json args_with(const KeyUnderTest& k, const json& value) {
  json args = json::parse(command_spec(k.command).example_args);
  json::json_pointer ptr;
  for (const ArgSpec* p : k.parents) {
    ptr /= std::string(p->key);
    if (!args.contains(ptr)) args[ptr] = valid_value(*p);
    if (p->type == ArgType::object_list) ptr /= 0;
  }
  args[k.pointer] = value;
  return args;
}

void expect_refused(const KeyUnderTest& k, const json& args, const std::string& why) {
  const auto p = validate_args(args, command_spec(k.command).args);
  ASSERT_TRUE(p.has_value()) << to_string(k.command) << " accepted " << why << ": " << args.dump();
  EXPECT_EQ(p->key, k.path) << to_string(k.command) << " " << why << ": " << p->problem;
}

TEST(Schema, EveryExampleIsValid) {
  for (const auto& c : command_table()) {
    const json args = json::parse(c.example_args);
    const auto p = validate_args(args, c.args);
    EXPECT_FALSE(p.has_value()) << to_string(c.command) << ": " << p->key << " " << p->problem;
  }
}

TEST(Schema, TableCoversEveryCommandOnce) {
  ASSERT_EQ(command_table().size(), kCommandCount);
  for (std::size_t i = 0; i < kCommandCount; ++i)
    EXPECT_EQ(command_table()[i].command, static_cast<Command>(i));
}

TEST(Schema, WrongTypeForEveryArgumentIsRefusedNamingTheKey) {
  const std::vector<json> candidates = {nullptr, true, 1, 1.5, "s", json::array(), json::object(),
                                        json::array({1}), json::array({"x"}), -1};
  std::size_t refused = 0;
  for (const auto& k : every_key())
    for (const auto& v : candidates)
      if (!accepts_type(k.spec->type, v)) {
        expect_refused(k, args_with(k, v), "a wrong type " + v.dump() + " for " + k.path);
        ++refused;
      }
  EXPECT_GT(refused, 200u);
}

TEST(Schema, ValuesOutsideTheirRangeAreRefused) {
  for (const auto& k : every_key()) {
    const ArgSpec& s = *k.spec;
    const double margin = std::max(1e-9, (s.range.hi - s.range.lo) * 1e-6);
    switch (s.type) {
      case ArgType::number:
        expect_refused(k, args_with(k, s.range.lo - margin), "below range");
        expect_refused(k, args_with(k, s.range.hi + margin), "above range");
        // The bounds themselves pass (a group rule may still object, about another key).
        for (const double bound : {s.range.lo, s.range.hi}) {
          const auto p = validate_args(args_with(k, bound), command_spec(k.command).args);
          EXPECT_TRUE(!p || p->key != k.path) << k.path << " = " << bound << ": " << p->problem;
        }
        break;
      case ArgType::integer:
        expect_refused(k, args_with(k, static_cast<std::int64_t>(s.range.lo) - 1), "below range");
        expect_refused(k, args_with(k, static_cast<std::int64_t>(s.range.hi) + 1), "above range");
        break;
      case ArgType::string:
      case ArgType::label:
        expect_refused(k, args_with(k, ""), "empty");
        expect_refused(k, args_with(k, std::string(static_cast<std::size_t>(s.size.hi) + 1, 'x')), "too long");
        break;
      case ArgType::choice: expect_refused(k, args_with(k, "no-such-choice"), "unknown choice"); break;
      case ArgType::integer_list:
        expect_refused(k, args_with(k, json::array({static_cast<std::int64_t>(s.range.hi) + 1})), "element above range");
        expect_refused(k, args_with(k, json::array({1.5})), "non-integer element");
        break;
      case ArgType::choice_list: expect_refused(k, args_with(k, json::array({"no-such-choice"})), "unknown element"); break;
      case ArgType::number_list: {
        json above = valid_value(s);
        above.back() = s.range.hi + margin;
        expect_refused(k, args_with(k, above), "element above range");
        json text = valid_value(s);
        text.back() = "1";
        expect_refused(k, args_with(k, text), "non-number element");
        expect_refused(k, args_with(k, json::array()), "too few elements");
        break;
      }
      case ArgType::object_list: {
        const auto p = validate_args(args_with(k, json::array({1})), command_spec(k.command).args);
        ASSERT_TRUE(p) << k.path << " accepted an element that is not an object";
        EXPECT_EQ(p->key, k.path + "[0]") << "the problem names the element";
        break;
      }
      case ArgType::boolean:
      case ArgType::object: break;
    }
  }
}

// A tab in a knob's name once reached the store thread, which threw and took
// hapticd down: every text is refused at the protocol, naming its key.
TEST(Schema, EveryTextWithAControlCharacterIsRefusedNamingTheKey) {
  int texts = 0;
  for (const auto& k : every_key()) {
    if (k.spec->type != ArgType::string && k.spec->type != ArgType::label) continue;
    ++texts;
    for (const std::string& bad : std::vector<std::string>{"a\tb", "a\nb", std::string("a\0b", 3), "a\x7f", "\x1b[2J"}) {
      const auto p = validate_args(args_with(k, bad), command_spec(k.command).args);
      ASSERT_TRUE(p) << k.path << " accepted " << json(bad).dump();
      EXPECT_EQ(p->key, k.path);
      EXPECT_NE(p->problem.find("one line of text"), std::string::npos) << p->problem;
    }
    // Text beyond ASCII is still text.
    const auto p = validate_args(args_with(k, "\u00e4\u2013\u65cb"), command_spec(k.command).args);
    EXPECT_TRUE(!p || p->key != k.path) << k.path << ": " << p->problem;
  }
  EXPECT_GE(texts, 4);
}

TEST(Schema, UnknownKeysAreRefusedAtEveryLevel) {
  for (const auto& c : command_table()) {
    json args = json::parse(c.example_args);
    args["zz_typo"] = 1;
    const auto p = validate_args(args, c.args);
    ASSERT_TRUE(p) << to_string(c.command);
    EXPECT_EQ(p->key, "zz_typo");
  }
  json capture = json::parse(command_spec(Command::start_capture).example_args);
  capture["swept_sine"]["e"] = 1;
  const auto p = validate_args(capture, command_spec(Command::start_capture).args);
  ASSERT_TRUE(p);
  EXPECT_EQ(p->key, "swept_sine.e");
}

TEST(Schema, EveryRequiredKeyIsRequired) {
  for (const auto& k : every_key()) {
    if (!k.spec->required) continue;
    json args = args_with(k, valid_value(*k.spec));
    args[k.pointer.parent_pointer()].erase(k.pointer.back());
    expect_refused(k, args, "without required " + k.path);
  }
}

std::optional<std::string> refusal(Command c, const std::string& args) {
  const auto p = validate_args(json::parse(args), command_spec(c).args);
  return p ? std::optional(p->key) : std::nullopt;
}

TEST(Schema, GroupRules) {
  const std::string model = R"("M_acc":1e-5,"B_vel":0,"A_pos":0,"P_pos":1)";
  EXPECT_EQ(refusal(Command::load_model, "{" + model + R"(,"dv":0.1})"), "D_neg");
  EXPECT_EQ(refusal(Command::load_model, "{" + model + R"(,"dv":0.1,"D_neg":0.01,"D_pos":0.01})"), std::nullopt);
  EXPECT_EQ(refusal(Command::load_model, "{" + model + R"(,"B_vm":0.1})"), "K_vm");
  EXPECT_EQ(refusal(Command::load_model, "{" + model + R"(,"effects":{"spring":{"centre_rad":0.1}}})"), "effects.spring.stiffness_Nm_per_rad")
      << "a spring needs a stiffness";
  EXPECT_EQ(refusal(Command::load_model, "{" + model + R"(,"effects":{"backlash":{"width":0.01}}})"),
            "effects.backlash")
      << "the renderer renders no play";
  EXPECT_EQ(refusal(Command::set_params, R"({"effects":{"stribeck":{"static_excess_Nm":0.002,"stribeck_velocity_rad_s":0.1}}})"), std::nullopt);
  EXPECT_EQ(refusal(Command::set_params, "{}"), "M_acc") << "set_params needs at least one key";
  EXPECT_EQ(refusal(Command::set_params, R"({"D_pos":0.01})"), std::nullopt) << "partial updates need no group";
  EXPECT_EQ(refusal(Command::start_capture, R"({"seconds":1,"knob":"k"})"), "swept_sine");
  EXPECT_EQ(refusal(Command::start_capture,
                    R"({"seconds":1,"knob":"k","swept_sine":{"a":0,"b":1,"c":1,"d":1},"torque_sweep":{"a":0,"b":1,"c":0.01,"d":1}})"),
            "swept_sine");
  EXPECT_EQ(refusal(Command::load_tiles, R"({"position":[{"theta_min":0,"theta_max":1}]})"), "position[0].f_pos")
      << "a tile needs at least one curve";
  EXPECT_EQ(refusal(Command::load_tiles,
                    R"({"time":[{"duration":1,"f_vel":{"x":[0,1],"y":[0,0]}},{"duration":1,"f_acc":{"x":[0],"y":[0]}}]})"),
            "time[1].f_acc.x")
      << "a problem deep in a list names its element";
  EXPECT_EQ(refusal(Command::load_tiles, "{}"), std::nullopt) << "{} clears the tiles";
  EXPECT_EQ(refusal(Command::load_tiles,
                    R"({"position":[{"theta_min":0,"theta_max":1,"torque_of_velocity":{"x":[-1,1],"y":[-0.001,0.001]}}],)"
                    R"("time":[{"duration":1,"torque":{"x":[0,1],"y":[0,0.01]}}]})"),
            std::nullopt)
      << "a torque curve alone makes a tile";
  EXPECT_EQ(refusal(Command::load_tiles, R"({"position":[{"theta_min":0,"theta_max":1,"mass":{"x":[0,1]}}]})"),
            "position[0].mass.y");
  EXPECT_EQ(refusal(Command::load_tiles, R"({"time":[{"duration":1,"mass":{"x":[0,1],"y":[0,0]}}]})"), "time[0].mass")
      << "mass is a position tile's";
}

// docs/protocol.md carries the table rendered by schema_markdown() between
// two markers. Run with KNOBLAB_UPDATE_PROTOCOL_DOC=1 to rewrite it.
TEST(Schema, ProtocolDocumentMatchesTheTable) {
  const std::string begin = "<!-- BEGIN GENERATED: command reference (schema_markdown) -->\n";
  const std::string end = "<!-- END GENERATED -->";
  std::ifstream in(KNOBLAB_PROTOCOL_DOC);
  ASSERT_TRUE(in) << "cannot read " << KNOBLAB_PROTOCOL_DOC;
  std::stringstream ss;
  ss << in.rdbuf();
  std::string doc = ss.str();
  const auto b = doc.find(begin);
  const auto e = doc.find(end);
  ASSERT_NE(b, std::string::npos) << "marker missing: " << begin;
  ASSERT_NE(e, std::string::npos) << "marker missing: " << end;
  const std::string current = doc.substr(b + begin.size(), e - b - begin.size());
  const std::string wanted = "\n" + schema_markdown();
  if (current != wanted && std::getenv("KNOBLAB_UPDATE_PROTOCOL_DOC")) {
    doc.replace(b + begin.size(), e - b - begin.size(), wanted);
    std::ofstream(KNOBLAB_PROTOCOL_DOC) << doc;
    GTEST_SKIP() << "rewrote the command reference in " << KNOBLAB_PROTOCOL_DOC;
  }
  EXPECT_EQ(current, wanted) << "docs/protocol.md is out of step with the command table; "
                                "rerun this test with KNOBLAB_UPDATE_PROTOCOL_DOC=1";
}

}  // namespace
}  // namespace knoblab::control
