// Seeded random abuse: random bytes, mutated valid frames, random splits of
// a stream across writes, abrupt disconnects mid-frame. The server must
// answer only with well-formed replies, stay up, keep serving a
// well-behaved client, and never pass an invalid request to the handler
// (RecordingHandler re-checks every request; ServerTest::TearDown asserts).
#include <sys/socket.h>

#include <random>
#include <thread>

#include "knoblab/control/client.hpp"
#include "knoblab/control/decode.hpp"
#include "knoblab/control/schema.hpp"
#include "test_support.hpp"

namespace knoblab::control::test {
namespace {

using Rng = std::mt19937_64;

std::size_t pick(Rng& rng, std::size_t n) { return std::uniform_int_distribution<std::size_t>(0, n - 1)(rng); }

std::string random_bytes(Rng& rng, std::size_t n) {
  std::string s(n, '\0');
  for (auto& c : s) c = static_cast<char>(rng() & 0xFF);
  return s;
}

// A valid request frame for a random command (the table's examples).
std::string random_valid_frame(Rng& rng, std::int64_t id) {
  const auto& spec = command_table()[pick(rng, command_table().size())];
  return request_frame(id, to_string(spec.command), json::parse(spec.example_args));
}

void mutate(Rng& rng, std::string& s) {
  if (s.empty()) {
    s = random_bytes(rng, 1 + pick(rng, 8));
    return;
  }
  const std::size_t at = pick(rng, s.size());
  switch (pick(rng, 7)) {
    case 0: s[at] = static_cast<char>(s[at] ^ (1 << pick(rng, 8))); break;         // flip a bit
    case 1: s[at] = static_cast<char>(rng() & 0xFF); break;                         // replace a byte
    case 2: s.insert(at, random_bytes(rng, 1 + pick(rng, 16))); break;             // insert junk
    case 3: s.erase(at, 1 + pick(rng, 16)); break;                                  // delete a run
    case 4: s.insert(at, s.substr(pick(rng, s.size()), 1 + pick(rng, 32))); break;  // duplicate a run
    case 5: s.resize(at); break;                                                    // truncate
    case 6: {                                                                       // swap in a token
      static const char* tokens[] = {"null", "[]", "{}", "\"\"", "-1", "1e999", "true", "\"\\u0000\"", "0.5", "\xff"};
      s.insert(at, tokens[pick(rng, std::size(tokens))]);
      break;
    }
  }
}

// Every server message must parse as v1 and be a reply (nobody subscribed).
void expect_well_formed(const std::vector<json>& messages) {
  for (const auto& m : messages) {
    try {
      const auto parsed = parse_server_message(m);
      EXPECT_TRUE(std::holds_alternative<ReplyMessage>(parsed)) << m.dump();
    } catch (const std::exception& e) {
      ADD_FAILURE() << e.what() << ": " << m.dump();
    }
  }
}

class FuzzRandom : public ServerTest {
 protected:
  void configure(ServerConfig& c) override {
    c.partial_frame_timeout = 300ms;
    if (std::getenv("KNOBLAB_CONTROL_LOG")) c.log = [](std::string_view l) { std::fprintf(stderr, "server: %.*s\n", int(l.size()), l.data()); };
  }
  void SetUp() override {
    ServerTest::SetUp();
    good = std::make_unique<Client>(config.socket_path);
  }
  void TearDown() override {
    EXPECT_TRUE(good->request("ping").ok) << "the long-lived client lost its server";
    good.reset();
    expect_server_answers();
    ServerTest::TearDown();
  }
  // Send, half-close, collect every reply until the server closes.
  std::vector<json> exchange(const std::string& bytes) {
    RawConnection raw(config.socket_path);
    raw.send_bytes(bytes);
    raw.shutdown_write();
    auto replies = raw.read_until_closed(3s);
    EXPECT_TRUE(raw.closed()) << "server kept a half-closed connection open";
    return replies;
  }
  std::unique_ptr<Client> good;
};

TEST(FuzzDecode, NeverThrowsAndOnlyAcceptsWhatTheSchemaAccepts) {
  Rng rng(0xC0FFEE);
  std::size_t accepted = 0;
  for (int i = 0; i < 30000; ++i) {
    std::string payload;
    if (i % 6 == 0) {
      payload = random_bytes(rng, pick(rng, 256));
    } else {
      payload = random_valid_frame(rng, i).substr(kFrameHeaderBytes);
      for (std::size_t m = 1 + pick(rng, 3); m > 0; --m) mutate(rng, payload);
    }
    std::variant<Request, Rejection> d;
    ASSERT_NO_THROW(d = decode_request(payload)) << "case " << i;
    if (const auto* r = std::get_if<Request>(&d)) {
      ++accepted;
      EXPECT_FALSE(validate_args(r->args, command_spec(r->command).args).has_value()) << payload;
    } else {
      EXPECT_FALSE(std::get<Rejection>(d).error.message.empty());
    }
  }
  EXPECT_GT(accepted, 100u) << "mutations should leave some requests valid";
}

TEST_F(FuzzRandom, RandomBytes) {
  Rng rng(1);
  for (int i = 0; i < 150; ++i) {
    SCOPED_TRACE("case " + std::to_string(i));
    std::string body = random_bytes(rng, pick(rng, 2000));
    // Half the cases carry a plausible length header, to get past framing.
    if (i % 2) body = header_only(static_cast<std::uint32_t>(pick(rng, body.size() + 16))) + body;
    expect_well_formed(exchange(body));
    if (i % 25 == 0) {
      ASSERT_TRUE(good->request("ping").ok);
    }
  }
}

TEST_F(FuzzRandom, MutatedValidFrames) {
  Rng rng(2);
  for (int i = 0; i < 300; ++i) {
    SCOPED_TRACE("case " + std::to_string(i));
    std::string stream;
    for (std::size_t f = 1 + pick(rng, 4); f > 0; --f) stream += random_valid_frame(rng, i);
    for (std::size_t m = 1 + pick(rng, 4); m > 0; --m) mutate(rng, stream);
    expect_well_formed(exchange(stream));
    if (i % 50 == 0) {
      ASSERT_TRUE(good->request("ping").ok);
    }
  }
}

TEST_F(FuzzRandom, FramesSplitAcrossRandomWrites) {
  Rng rng(3);
  for (int i = 0; i < 60; ++i) {
    SCOPED_TRACE("case " + std::to_string(i));
    // Known frames with known answers, in a known order.
    std::string stream;
    std::vector<std::string> expected;
    for (int f = 0; f < 20; ++f) {
      switch (pick(rng, 4)) {
        case 0: stream += request_frame(f, "get_state"); expected.push_back("ok"); break;
        case 1: stream += request_frame(f, "set_mode", {{"mode", "nope"}}); expected.push_back("bad_args"); break;
        case 2: stream += raw_frame("{\"v\":1,"); expected.push_back("bad_json"); break;
        case 3: stream += random_valid_frame(rng, f); expected.push_back("ok"); break;
      }
    }
    RawConnection raw(config.socket_path);
    for (std::size_t pos = 0; pos < stream.size();) {
      const std::size_t n = std::min(stream.size() - pos, 1 + pick(rng, 64));
      ASSERT_TRUE(raw.send_bytes(std::string_view(stream).substr(pos, n)));
      pos += n;
      if (pick(rng, 4) == 0) std::this_thread::sleep_for(std::chrono::microseconds(pick(rng, 300)));
    }
    std::vector<std::string> got;
    int last_id = -1;
    for (std::size_t k = 0; k < expected.size(); ++k) {
      const auto m = raw.read_message(2s);
      ASSERT_TRUE(m.has_value()) << "reply " << k << " missing";
      got.push_back(outcome(*m));
      if ((*m)["id"].is_number_integer()) {
        EXPECT_GT((*m)["id"].get<int>(), last_id) << "replies out of order";
        last_id = (*m)["id"].get<int>();
      }
    }
    EXPECT_EQ(got, expected);
  }
}

TEST_F(FuzzRandom, AbruptDisconnectsMidFrame) {
  Rng rng(4);
  std::string stream;
  for (int f = 0; f < 8; ++f) stream += random_valid_frame(rng, f);
  for (int i = 0; i < 200; ++i) {
    {
      RawConnection raw(config.socket_path);
      raw.send_bytes(std::string_view(stream).substr(0, pick(rng, stream.size())));
      if (pick(rng, 2)) raw.shutdown_write();
    }  // closed without reading the replies
    if (i % 10 == 9) {
      // Two round trips: the server accepts this batch in the round that
      // answers the first ping and has reaped it by the second.
      ASSERT_TRUE(good->request("ping").ok);
      ASSERT_TRUE(good->request("ping").ok);
    }
  }
  EXPECT_EQ(server->stats().clients_refused, 0u) << "closed connections must free their slots";
}

}  // namespace
}  // namespace knoblab::control::test
