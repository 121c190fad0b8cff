// A store on read-only media (a write-protected card, a read-only mount) can
// still be listed, inspected and exported.
#include <gtest/gtest.h>

#include <fcntl.h>
#include <sched.h>
#include <sys/mount.h>
#include <sys/wait.h>
#include <unistd.h>

#include "process.hpp"

namespace knoblab::test {
namespace {

constexpr int kCannotMount = 77;

// Runs knoblab ARGS in a child whose own mount namespace has `dir` as a
// read-only tmpfs holding a copy of `store` (as dir/lab.sqlite). Returns the
// exit code, or kCannotMount where mount namespaces are not allowed.
int run_on_read_only_media(const std::filesystem::path& dir, const std::filesystem::path& store,
                           std::vector<std::string> args, const std::filesystem::path& out) {
  const pid_t pid = fork();
  if (pid == 0) {
    if (unshare(CLONE_NEWNS) != 0) _exit(kCannotMount);
    // Keep our mounts to ourselves; in a chroot "/" may not be a mount point,
    // and then its propagation is already the outer namespace's business.
    (void)mount(nullptr, "/", nullptr, MS_REC | MS_PRIVATE, nullptr);
    if (mount("tmpfs", dir.c_str(), "tmpfs", 0, "size=64m") != 0) _exit(kCannotMount);
    std::error_code ec;
    std::filesystem::copy_file(store, dir / "lab.sqlite", ec);
    if (ec || mount("tmpfs", dir.c_str(), "tmpfs", MS_REMOUNT | MS_RDONLY, nullptr) != 0) _exit(kCannotMount);
    const int fd = open(out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    dup2(fd, 1);
    dup2(fd, 2);
    std::vector<char*> argv{const_cast<char*>(KNOBLAB_CLI_PATH)};
    for (auto& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    execv(KNOBLAB_CLI_PATH, argv.data());
    _exit(127);
  }
  int status = 0;
  waitpid(pid, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

TEST(ReadOnlyMedia, AStoreOnAReadOnlyMountIsListedInspectedAndExported) {
  ScratchDir scratch;
  const auto store = scratch / "lab.sqlite";
  const RunResult sim = run_knoblab({"simulate", "--knob", "subtle-detents", "--seconds", "1", "--db", store.string()});
  ASSERT_EQ(sim.exit_code, 0) << sim.err;
  const auto media = scratch / "card";
  std::filesystem::create_directory(media);
  const auto db = (media / "lab.sqlite").string();
  const auto out = scratch / "out.txt";

  int rc = run_on_read_only_media(media, store, {"list", "--db", db}, out);
  if (rc == kCannotMount) GTEST_SKIP() << "no mount namespace here (needs root)";
  EXPECT_EQ(rc, 0) << read_file(out);
  EXPECT_NE(read_file(out).find("subtle-detents"), std::string::npos) << read_file(out);

  rc = run_on_read_only_media(media, store, {"inspect", "--capture", "1", "--db", db, "--json"}, out);
  EXPECT_EQ(rc, 0) << read_file(out);
  EXPECT_NE(read_file(out).find("\"samples\":5000"), std::string::npos) << read_file(out);

  // The export goes to writable /tmp; only the store is on the card.
  const auto csv = scratch / "capture.csv";
  rc = run_on_read_only_media(media, store, {"export", "1", "--db", db, "--out", csv.string()}, out);
  EXPECT_EQ(rc, 0) << read_file(out);
  EXPECT_TRUE(std::filesystem::exists(csv));

  // Adding to it fails with a clear error, not a crash.
  rc = run_on_read_only_media(media, store, {"import", csv.string(), "--db", db}, out);
  EXPECT_EQ(rc, 1) << read_file(out);
  EXPECT_NE(read_file(out).find("lab.sqlite"), std::string::npos) << read_file(out);
}

}  // namespace
}  // namespace knoblab::test
