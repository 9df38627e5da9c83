#include "settings/layer.h"

namespace raycast {

std::optional<std::string> parse_given(const setting& row, std::string_view text, std::string source, given& g) {
  g.source = std::move(source);
  return parse_value(row, text, g.v, g.tokens);
}

std::optional<setting_error> check_groups(const settings& s) {
  const std::span<const setting> table = input_table();
  for (size_t a = 0; a < table.size(); ++a) {
    if (table[a].group == 0 || !s.has(table[a].id)) continue;
    for (size_t b = a + 1; b < table.size(); ++b) {
      if (table[b].group != table[a].group || !s.has(table[b].id)) continue;
      const given& later = *s[table[b].id];
      // Spelled as the source spells them: a file's keys, else the options.
      const bool file = !later.where.empty() || later.source == table[b].file_key;
      const auto spell = [&](const setting& r) {
        return std::string(file ? r.file_key.substr(r.file_key.find('.') + 1) : r.option);
      };
      return setting_error{&table[b], later.source,
                           "give " + spell(table[a]) + " or " + spell(table[b]) + ", not both" + later.where};
    }
  }
  return std::nullopt;
}

void merge(settings& base, const settings& over) {
  const std::span<const setting> table = input_table();
  for (const setting& row : table) {
    if (!over.has(row.id) || row.group == 0) continue;
    for (const setting& other : table)
      if (other.group == row.group) base[other.id].reset();
  }
  for (size_t k = 0; k < setting_count; ++k)
    if (over.at[k]) base.at[k] = over.at[k];
}

}  // namespace raycast
