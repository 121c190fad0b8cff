// A store file in a fresh directory under /tmp, removed with it at scope exit.
#pragma once

#include <stdlib.h>

#include <filesystem>
#include <string>

namespace knoblab::hapticd::testing {

struct TempDb {
  std::filesystem::path dir;
  explicit TempDb(const std::string& name = "daemon") {
    std::string tmpl = "/tmp/knoblab-" + name + "-XXXXXX";
    dir = mkdtemp(tmpl.data());
  }
  ~TempDb() { std::filesystem::remove_all(dir); }
  TempDb(const TempDb&) = delete;
  TempDb& operator=(const TempDb&) = delete;
  std::filesystem::path path() const { return dir / "lab.sqlite"; }
};

}  // namespace knoblab::hapticd::testing
