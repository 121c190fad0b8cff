// knoblab ctl: one request to hapticd over its control socket, printed as
// JSON, or a watch of its events (and telemetry) as JSON lines. A thin shell
// over control::Client: the arguments are checked by the daemon against the
// protocol's schema, so its error messages are the ones a user sees.
#include <signal.h>
#include <sys/stat.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdlib>
#include <iostream>
#include <iterator>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "knoblab/control/client.hpp"
#include "knoblab/control/schema.hpp"
#include "knoblab/control/telemetry_reader.hpp"
#include "knoblab/hapticd/model_file.hpp"

namespace knoblab::cli {

namespace {

using nlohmann::json;
using std::chrono::milliseconds;

constexpr const char* kDefaultSocket = "/run/knoblab/hapticd.sock";
constexpr int kExitErrorReply = 1;
constexpr int kExitUnreachable = 3;
constexpr std::size_t kHelpWidth = 79;

// ---- help: the command list comes from the protocol's schema ----------------

std::string value_hint(const control::ArgSpec& a) {
  using control::ArgType;
  switch (a.type) {
    case ArgType::integer: return "INT";
    case ArgType::number: return "NUM";
    case ArgType::string: return "TEXT";
    case ArgType::boolean: return "true|false";
    case ArgType::label: return "ID";
    case ArgType::integer_list: return "[INT,...]";
    case ArgType::choice_list: return "'[\"NAME\",...]'";
    case ArgType::number_list: return "[NUM,...]";
    case ArgType::object: return "";
    case ArgType::object_list: return "'[{...},...]'";
    case ArgType::choice: {
      std::string out;
      for (const auto c : a.choices) out += (out.empty() ? "" : "|") + std::string(c);
      return out;
    }
  }
  return "?";
}

// key=HINT words, nested keys dotted, optional ones in brackets.
void arg_words(const control::ObjectSchema& schema, const std::string& prefix, std::vector<std::string>& out) {
  for (const auto& a : schema.args) {
    std::vector<std::string> mine;
    const std::string key = prefix + std::string(a.key);
    if (a.type == control::ArgType::object) arg_words(*a.object, key + ".", mine);
    else mine.push_back(key + "=" + value_hint(a));
    if (mine.empty()) continue;
    // An optional object whose keys are all optional is bracketed already.
    const bool any_required =
        a.type != control::ArgType::object ||
        std::any_of(a.object->args.begin(), a.object->args.end(), [](const auto& k) { return k.required; });
    if (!a.required && any_required) {
      mine.front() = "[" + mine.front();
      mine.back() += "]";
    }
    out.insert(out.end(), mine.begin(), mine.end());
  }
}

std::string command_list() {
  const std::string indent(18, ' ');
  std::string out;
  for (const auto& c : control::command_table()) {
    std::string name = "  " + std::string(control::to_string(c.command));
    if (name.size() < indent.size()) name.resize(indent.size(), ' ');
    else name += ' ';  // a long name pushes its summary along
    out += name + std::string(c.summary) + "\n";
    std::vector<std::string> words;
    arg_words(c.args, "", words);
    std::string line = indent;
    for (const auto& w : words) {
      if (line.size() > indent.size() && line.size() + 1 + w.size() > kHelpWidth) {
        out += line + "\n";
        line = indent;
      }
      line += (line.size() > indent.size() ? " " : "") + w;
    }
    if (line.size() > indent.size()) out += line + "\n";
  }
  out.pop_back();  // usage() ends the summary's last line
  return out;
}

std::string ctl_summary() {
  return "Send one request to hapticd and print its result as JSON, or watch its events.\n"
         "\n"
         "  knoblab ctl [--socket PATH] COMMAND [key=value ...]\n"
         "  knoblab ctl [--socket PATH] load_model FILE.json\n"
         "  knoblab ctl [--socket PATH] --json '{\"command\": \"set_mode\", \"args\": {\"mode\": \"render\"}}'\n"
         "  knoblab ctl [--socket PATH] --watch [--events state,fault_latched] [--telemetry] [--count N]\n"
         "\n"
         "A value is JSON when it parses as JSON (numbers, true/false, null, arrays,\n"
         "objects, \"quoted\" strings), else a string: knob=12 sends a number, knob='\"12\"'\n"
         "a string. Dotted keys nest: swept_sine.a=0 sends {\"swept_sine\": {\"a\": 0}}.\n"
         "load_model FILE sends a model file's render model and effects (knoblab fit\n"
         "--render-model, knoblab discrepancy --model-out); effects hapticd cannot render\n"
         "are refused, named, before anything is sent (exit 2).\n"
         "hapticd checks the arguments; ranges and rules are in docs/protocol.md §7.\n"
         "--watch prints one JSON line per event ({\"event\": NAME, \"data\": {...}}) and,\n"
         "with --telemetry, per telemetry record ({\"telemetry\": {...}}), until\n"
         "interrupted (SIGINT/SIGTERM: exit 0) or --count lines.\n"
         "\n"
         "The socket is --socket, else $KNOBLAB_SOCKET, else " +
         std::string(kDefaultSocket) +
         ".\n"
         "Exit status: 0 ok; 1 hapticd answered with an error (printed on stderr);\n"
         "2 usage; 3 hapticd cannot be reached (no socket, not running, connection lost).\n"
         "\n"
         "commands (protocol v1):\n" +
         command_list();
}

// ---- the request: COMMAND key=value ... or --json ----------------------------

struct Request {
  std::string command;
  json args = json::object();
};

// Puts `value` at the dotted `key` inside `args`, making the objects between.
void place(json& args, const std::string& key, json value) {
  json* at = &args;
  for (std::size_t start = 0;;) {
    const auto dot = key.find('.', start);
    const std::string part = key.substr(start, dot == std::string::npos ? std::string::npos : dot - start);
    if (part.empty()) throw UsageError("'" + key + "=': a key part is empty (dots nest: pid.Kp=200)");
    if (dot == std::string::npos) {
      if (at->contains(part)) throw UsageError("'" + key + "' is given twice");
      (*at)[part] = std::move(value);
      return;
    }
    if (!at->contains(part)) (*at)[part] = json::object();
    json& next = (*at)[part];
    if (!next.is_object()) throw UsageError("'" + key + "': '" + part + "' already holds a value that is not an object");
    at = &next;
    start = dot + 1;
  }
}

Request from_words(std::span<const std::string> words) {
  if (words.empty()) throw UsageError("name a COMMAND (see --help), or use --json or --watch");
  // load_model FILE: a model file's render model and effects.
  if (words.size() == 2 && words[0] == "load_model" && words[1].find('=') == std::string::npos) {
    try {
      return {words[0], hapticd::read_model_file_args(words[1])};
    } catch (const hapticd::ModelFileError& e) {
      throw UsageError(std::string("load_model: ") + e.what());
    }
  }
  Request r{words.front(), json::object()};
  for (const auto& w : words.subspan(1)) {
    const auto eq = w.find('=');
    if (eq == std::string::npos) throw UsageError("expected key=value, got '" + w + "'");
    const std::string text = w.substr(eq + 1);
    place(r.args, w.substr(0, eq), json::accept(text) ? json::parse(text) : json(text));
  }
  return r;
}

Request from_json_option(const std::string& text) {
  const json j = json::parse(text, nullptr, false);
  const std::string shape = R"(--json wants {"command": NAME, "args": {...}})";
  if (j.is_discarded()) throw UsageError("--json: not valid JSON; " + shape);
  if (!j.is_object()) throw UsageError(shape);
  for (const auto& [key, value] : j.items())
    if (key != "command" && key != "args") throw UsageError("--json: unknown key '" + key + "'; " + shape);
  if (!j.contains("command") || !j["command"].is_string()) throw UsageError("--json: \"command\" must be a string");
  Request r{j["command"].get<std::string>(), j.value("args", json::object())};
  if (!r.args.is_object()) throw UsageError("--json: \"args\" must be an object");
  return r;
}

// Checked here so the user hears about it as a usage problem, not as a
// transport failure.
void check_sendable(const Request& r) {
  std::string encoded;
  try {
    encoded = control::request_message(1, r.command, r.args).dump();
  } catch (const json::type_error&) {
    throw UsageError("the command and its arguments must be UTF-8 text");
  }
  if (encoded.size() > control::kMaxFramePayload)
    throw UsageError("the request is " + std::to_string(encoded.size()) + " bytes; a frame holds at most " +
                     std::to_string(control::kMaxFramePayload));
}

// ---- talking to hapticd -------------------------------------------------------

struct Unreachable : std::runtime_error {
  using std::runtime_error::runtime_error;
};

std::string socket_path(const Args& args) { return hapticd_socket(args); }

control::Client connect(const std::string& path, milliseconds timeout) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0 && errno == ENOENT)
    throw Unreachable("no control socket at " + path +
                      ": is hapticd running? (--socket PATH or $KNOBLAB_SOCKET name another)");
  try {
    return control::Client(path, timeout);
  } catch (const control::ClientError& e) {
    throw Unreachable(std::string(e.what()) + " (hapticd not running, or not a member of the socket's group?)");
  }
}

// JSON for people and scripts alike: invalid UTF-8 from the daemon is
// replaced rather than fatal.
template <typename Json>
std::string dump(const Json& j, int indent = -1) {
  return j.dump(indent, ' ', false, Json::error_handler_t::replace);
}

void print_error(const std::string& command, const control::Error& e) {
  std::cerr << "knoblab ctl: " << command << ": " << control::to_string(e.code) << ": " << e.message << "\n";
}

int request_once(const std::string& path, const Request& r, milliseconds timeout) {
  control::Client client = connect(path, timeout);
  control::Reply reply;
  try {
    reply = client.request(r.command, r.args);
  } catch (const control::ClientError& e) {
    throw Unreachable(std::string(e.what()));
  }
  if (!reply.ok) {
    print_error(r.command, reply.error);
    return kExitErrorReply;
  }
  std::cout << dump(reply.result, 2) << "\n";
  return 0;
}

// ---- --watch --------------------------------------------------------------------

volatile std::sig_atomic_t g_stop = 0;
void on_stop_signal(int) { g_stop = 1; }

// SIGINT/SIGTERM end the watch cleanly; the previous handlers come back after.
class StopSignals {
 public:
  StopSignals() {
    g_stop = 0;
    struct sigaction sa {};
    sa.sa_handler = on_stop_signal;
    sigemptyset(&sa.sa_mask);
    ::sigaction(SIGINT, &sa, &old_int_);
    ::sigaction(SIGTERM, &sa, &old_term_);
  }
  ~StopSignals() {
    ::sigaction(SIGINT, &old_int_, nullptr);
    ::sigaction(SIGTERM, &old_term_, nullptr);
  }
  StopSignals(const StopSignals&) = delete;
  StopSignals& operator=(const StopSignals&) = delete;
  bool requested() const { return g_stop != 0; }

 private:
  struct sigaction old_int_ {}, old_term_ {};
};

json event_names(const std::string& list) {
  json names = json::array();
  for (std::size_t start = 0; start <= list.size();) {
    auto comma = list.find(',', start);
    if (comma == std::string::npos) comma = list.size();
    std::string name = list.substr(start, comma - start);
    name.erase(0, name.find_first_not_of(' '));
    name.erase(name.find_last_not_of(' ') + 1);
    if (!name.empty()) names.push_back(name);
    start = comma + 1;
  }
  if (names.empty()) throw UsageError("--events wants a comma-separated list of event names, e.g. state,fault_latched");
  return names;
}

// Watch lines keep their keys in the documented order (what a person reads
// first), unlike the sorted keys of the replies.
using Line = nlohmann::ordered_json;

Line telemetry_line(const control::TelemetryRecord& r, std::uint64_t sequence) {
  static constexpr const char* kModes[] = {"idle", "render", "capture", "calibrate"};
  const Line mode = r.mode < std::size(kModes) ? Line(kModes[r.mode]) : Line(r.mode);
  return {{"telemetry",
           {{"seq", sequence}, {"t", r.t}, {"theta", r.theta}, {"omega", r.omega}, {"torque", r.torque},
            {"torque_min", r.torque_min}, {"torque_max", r.torque_max}, {"command", r.command},
            {"mode", mode}, {"fault_bits", r.fault_bits}}}};
}

int watch(const Args& args, const std::string& path, milliseconds timeout) {
  const json events = event_names(args.get("events").value_or("*"));
  const long long count = args.integer("count", 0);
  if (args.has("count") && count < 1) throw UsageError("--count wants a positive integer");
  const bool telemetry = args.has("telemetry");
  if (!args.positionals().empty() || args.has("json")) throw UsageError("--watch takes no COMMAND and no --json");

  const StopSignals stop;
  control::Client client = connect(path, timeout);
  std::optional<control::TelemetryReader> reader;
  try {
    control::HelloOptions hello;
    hello.client_name = "knoblab-ctl";
    client.hello(hello);
    json sub = {{"events", events}};
    if (telemetry) sub["telemetry"] = true;
    const control::Reply reply = client.request("subscribe", sub);
    if (!reply.ok) {
      print_error("subscribe", reply.error);
      return kExitErrorReply;
    }
    std::string watching = dump(reply.result.value("events", json::array()));
    if (telemetry) {
      const std::string shm = reply.result.value("telemetry_shm", "");
      if (shm.empty()) throw std::runtime_error("hapticd keeps no telemetry ring (start it with --telemetry NAME)");
      reader.emplace(shm, control::TelemetryReader::Start::newest);
      watching += " and telemetry (" + shm + ")";
    }
    std::cerr << "knoblab ctl: watching " << watching << " on " << path << "; Ctrl-C stops\n";
  } catch (const control::RemoteError& e) {
    print_error("hello", e.error());
    return kExitErrorReply;
  } catch (const control::ClientError& e) {
    throw Unreachable(e.what());
  }

  long long printed = 0;
  // True once --count lines are out.
  const auto emit = [&](const Line& line) {
    std::cout << dump(line) << "\n" << std::flush;
    return count > 0 && ++printed >= count;
  };
  std::vector<control::TelemetryRecord> records(256);
  // Short waits: a signal does not cut a wait short, and telemetry needs polling.
  const milliseconds wait = reader ? milliseconds(20) : milliseconds(200);
  try {
    while (!stop.requested()) {
      if (const auto e = client.wait_event(wait)) {
        if (emit({{"event", e->name}, {"data", Line(e->data)}})) return 0;
        continue;
      }
      if (!reader) continue;
      for (auto got = reader->read(records); got.count > 0 && !stop.requested(); got = reader->read(records)) {
        if (got.lost > 0 && emit({{"telemetry_lost", got.lost}})) return 0;
        for (std::size_t i = 0; i < got.count; ++i)
          if (emit(telemetry_line(records[i], got.first_sequence + i))) return 0;
      }
    }
  } catch (const control::ClientError& e) {
    throw Unreachable(std::string("lost hapticd: ") + e.what());
  }
  return 0;
}

}  // namespace

const CommandSpec kCtlSpec{
    "ctl", "[--socket PATH] (COMMAND [key=value ...] | load_model FILE | --json JSON | --watch [--events LIST] [--telemetry])",
    ctl_summary(),
    {{"socket", true, "hapticd's control socket (default $KNOBLAB_SOCKET, else /run/knoblab/hapticd.sock)"},
     {"json", true, "the request as {\"command\": NAME, \"args\": {...}}", "REQUEST"},
     {"timeout", true, "seconds to wait for hapticd's reply (default 5)"},
     {"watch", false, "print events as JSON lines until interrupted"},
     {"events", true, "--watch: comma-separated event names (default *, all)", "LIST"},
     {"telemetry", false, "--watch: also print the telemetry ring's records"},
     {"count", true, "--watch: stop after this many lines", "N"}},
    0, 4096, false,
    {"knoblab ctl get_state", "knoblab ctl load_model M_acc=1.3e-5 B_vel=2e-4 A_pos=0.01 P_pos=0.05",
     "knoblab ctl --watch --events state,fault_latched"}};

int run_ctl(const Args& args) {
  const double seconds = args.number("timeout", 5.0);
  if (!(seconds > 0 && seconds <= 3600)) throw UsageError("--timeout wants seconds in (0, 3600]");
  const milliseconds timeout(std::max(1LL, static_cast<long long>(seconds * 1000.0 + 0.5)));
  const std::string path = socket_path(args);
  try {
    if (args.has("watch")) return watch(args, path, timeout);
    if (args.has("events") || args.has("telemetry") || args.has("count"))
      throw UsageError("--events, --telemetry and --count go with --watch");
    Request r;
    if (const auto text = args.get("json")) {
      if (!args.positionals().empty()) throw UsageError("--json carries the whole request; no COMMAND or key=value with it");
      r = from_json_option(*text);
    } else {
      r = from_words(args.positionals());
    }
    check_sendable(r);
    return request_once(path, r, timeout);
  } catch (const Unreachable& e) {
    std::cerr << "knoblab ctl: cannot reach hapticd: " << e.what() << "\n";
    return kExitUnreachable;
  }
}

std::string hapticd_socket(const Args& args) {
  if (auto s = args.get("socket")) return *s;
  if (const char* env = std::getenv("KNOBLAB_SOCKET"); env && *env) return env;
  return kDefaultSocket;
}

}  // namespace knoblab::cli
