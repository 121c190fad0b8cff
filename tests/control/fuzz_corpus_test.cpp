// The checked-in corpus (tests/control/corpus, made by make_corpus.py):
// each file goes down one connection; MANIFEST says what must come back.
// Afterwards the server must still answer a well-behaved client.
#include <fstream>
#include <sstream>

#include "test_support.hpp"

namespace knoblab::control::test {
namespace {

struct CorpusEntry {
  std::string file;
  std::vector<std::string> replies;
  bool closes = false;
  std::size_t handler_calls = 0;
};

std::vector<CorpusEntry> load_manifest() {
  std::ifstream in(std::string(KNOBLAB_CONTROL_CORPUS_DIR) + "/MANIFEST");
  std::vector<CorpusEntry> out;
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream ls(line);
    CorpusEntry e;
    std::string replies, after;
    ls >> e.file >> replies >> after >> e.handler_calls;
    std::istringstream rs(replies);
    for (std::string r; std::getline(rs, r, ',');)
      if (r != "-") e.replies.push_back(r);
    e.closes = after == "closed";
    out.push_back(e);
  }
  return out;
}

std::string read_file(const std::string& name) {
  std::ifstream in(std::string(KNOBLAB_CONTROL_CORPUS_DIR) + "/" + name, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

class FuzzCorpus : public ServerTest {
 protected:
  void configure(ServerConfig& c) override { c.partial_frame_timeout = 300ms; }
};

TEST_F(FuzzCorpus, EveryFileGetsItsExpectedReplies) {
  const auto corpus = load_manifest();
  ASSERT_GE(corpus.size(), 30u) << "MANIFEST missing or short";
  for (const auto& entry : corpus) {
    SCOPED_TRACE(entry.file);
    const std::string bytes = read_file(entry.file);
    ASSERT_FALSE(bytes.empty()) << "cannot read " << entry.file;
    const std::size_t calls_before = handler.request_count();

    RawConnection raw(config.socket_path);
    raw.send_bytes(bytes);  // may fail part-way once the server has closed: fine
    std::vector<json> replies;
    if (entry.closes) {
      replies = raw.read_until_closed(3s);
      EXPECT_TRUE(raw.closed()) << "connection should have been closed";
    } else {
      for (std::size_t i = 0; i < entry.replies.size(); ++i)
        if (auto m = raw.read_message(3s)) replies.push_back(std::move(*m));
      EXPECT_FALSE(raw.read_message(30ms).has_value()) << "more replies than expected";
      // Still open and in step: a ping gets its own answer.
      ASSERT_TRUE(raw.send_bytes(request_frame(424242, "ping")));
      const auto pong = raw.read_message(2s);
      ASSERT_TRUE(pong.has_value()) << "connection should have stayed open";
      EXPECT_EQ((*pong)["id"], 424242);
      EXPECT_EQ(outcome(*pong), "ok");
    }
    std::vector<std::string> codes;
    for (const auto& r : replies) {
      codes.push_back(outcome(r));
      EXPECT_EQ(r["v"], 1);
    }
    EXPECT_EQ(codes, entry.replies);
    EXPECT_EQ(handler.request_count() - calls_before, entry.handler_calls);
    expect_server_answers();
  }
}

}  // namespace
}  // namespace knoblab::control::test
