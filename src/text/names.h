// A name that is not one of a list: the message every front end gives for
// it ("'wrld' is not one of sky, ..., world; did you mean world?"), with
// the nearest name suggested when one is near enough to be a slip.
#pragma once
#include <algorithm>
#include <cctype>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace raycast {

// The edit distance of a and b, ignoring case: insertions, deletions,
// substitutions and swaps of two neighbours (a typed "sampels") cost one each.
inline size_t edit_distance(std::string_view a, std::string_view b) {
  const auto same = [](char x, char y) {
    return std::tolower(static_cast<unsigned char>(x)) == std::tolower(static_cast<unsigned char>(y));
  };
  const size_t n = b.size() + 1;
  std::vector<size_t> prev2(n), prev(n), row(n);
  for (size_t j = 0; j < n; ++j) prev[j] = j;
  for (size_t i = 1; i <= a.size(); ++i) {
    row[0] = i;
    for (size_t j = 1; j < n; ++j) {
      row[j] = std::min({prev[j] + 1, row[j - 1] + 1, prev[j - 1] + (same(a[i - 1], b[j - 1]) ? 0 : 1)});
      if (i > 1 && j > 1 && same(a[i - 1], b[j - 2]) && same(a[i - 2], b[j - 1]))
        row[j] = std::min(row[j], prev2[j - 2] + 1);
    }
    prev2.swap(prev);
    prev.swap(row);
  }
  return prev[n - 1];
}

// The name a slip of got (2 letters or more) most likely meant: the nearest
// within a third of its length (at least one edit), or the only name got
// begins; "" when none is.
inline std::string_view nearest_name(std::string_view got, std::span<const std::string_view> names) {
  if (got.size() < 2) return {};  // one letter: any other is as near
  std::string_view best;
  size_t best_d = std::max<size_t>(1, got.size() / 3) + 1;
  for (std::string_view n : names) {
    const size_t d = edit_distance(got, n);
    if (d < best_d) best = n, best_d = d;
  }
  if (!best.empty()) return best;
  std::string_view only;
  for (std::string_view n : names)
    if (n.size() > got.size() && n.substr(0, got.size()) == got) {
      if (!only.empty()) return {};
      only = n;
    }
  return only;
}

// "; did you mean NAME?" when a name is near got, else "".
inline std::string did_you_mean(std::string_view got, std::span<const std::string_view> names) {
  const std::string_view n = nearest_name(got, names);
  return n.empty() ? std::string() : "; did you mean " + std::string(n) + "?";
}

// "QUOTED is not one of a, b, c" and the suggestion; quoted is got as the
// message shows it (quote_token).
inline std::string not_one_of(std::string_view got, const std::string& quoted,
                              std::span<const std::string_view> names, std::string_view also = "") {
  std::string r = quoted;
  r.append(" is not one of ");
  for (size_t k = 0; k < names.size(); ++k) r.append(k ? ", " : "").append(names[k]);
  r.append(also).append(did_you_mean(got, names));
  return r;
}

}  // namespace raycast
