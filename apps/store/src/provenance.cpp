// The provenance columns of fits and discrepancy results (schema 7).
#include <string>

#include "internal.hpp"

namespace knoblab::store::detail {

void check_provenance(sqlite::Connection& db, const Provenance& p, std::string_view what) {
  const std::string where = std::string(what) + " provenance: ";
  if (p.tool_version.empty()) throw StoreError(where + "tool_version is empty");
  bool hex = p.input_sha256.size() == 64;
  for (const char c : p.input_sha256) hex = hex && ((c >= '0' && c <= '9') || (c >= 'a' && c <= 'f'));
  if (!hex)
    throw StoreError(where + "input_sha256 must be 64 lowercase hex digits, got '" + p.input_sha256 + "'");
  // json_type() fails on malformed JSON, hence CASE, which tries it only on valid JSON.
  auto st = db.prepare("SELECT CASE WHEN json_valid(?1) THEN json_type(?1) = 'object' ELSE 0 END");
  st.bind_text(1, p.options);
  const bool object = st.step() && st.column_int(0) == 1;
  st.reset();
  if (!object) throw StoreError(where + "options must be a JSON object, got '" + p.options + "'");
}

void bind_provenance(sqlite::Statement& st, int first, const std::optional<Provenance>& p) {
  if (!p) {
    for (int k = 0; k < 3; ++k) st.bind_null(first + k);
    return;
  }
  st.bind_text(first, p->tool_version).bind_text(first + 1, p->input_sha256).bind_text(first + 2, p->options);
}

std::optional<Provenance> read_provenance(const sqlite::Statement& st, int first) {
  if (st.is_null(first)) return std::nullopt;  // the schema keeps the three NULL together
  return Provenance{st.column_text(first), st.column_text(first + 1), st.column_text(first + 2)};
}

}  // namespace knoblab::store::detail
