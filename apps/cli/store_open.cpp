#include "store_open.hpp"

namespace knoblab::cli {

store::Store open_store_to_read(const std::string& path) {
  store::OpenOptions o;
  o.read_only = true;
  return store::Store::open(path, o);
}

store::Store open_store_to_add(const std::string& path) {
  store::OpenOptions o;
  o.create = false;
  return store::Store::open(path, o);
}

}  // namespace knoblab::cli
