#include "report.h"

#include <algorithm>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <ostream>
#include <sstream>

namespace raycast::bench {

std::string strf(const char* format, ...) {
  char buf[512];
  va_list args;
  va_start(args, format);
  std::vsnprintf(buf, sizeof buf, format, args);
  va_end(args);
  return buf;
}

namespace {

using Run = benchmark::BenchmarkReporter::Run;

std::vector<std::string> split(const std::string& s, char sep) {
  std::vector<std::string> parts;
  std::stringstream in(s);
  for (std::string part; std::getline(in, part, sep);) parts.push_back(part);
  return parts;
}

bool parse_size(const std::string& s, int64_t& w, int64_t& h) {
  long long a = 0, b = 0;
  char tail = 0;
  if (std::sscanf(s.c_str(), "%lldx%lld%c", &a, &b, &tail) != 2 || a < 1 || b < 1) return false;
  w = a;
  h = b;
  return true;
}

double run_seconds(const Run& r) {
  return r.GetAdjustedRealTime() / benchmark::GetTimeUnitMultiplier(r.time_unit);
}

// "" for an iteration run, the statistic's name for an aggregate.
std::string aggregate_key(const Run& r) {
  return r.run_type == Run::RT_Aggregate ? r.aggregate_name : std::string();
}

// Time counters make sense for single runs and for the mean and median.
bool has_time(const Run& r) {
  if (r.error_occurred) return false;
  if (r.run_type != Run::RT_Aggregate) return true;
  return r.aggregate_unit == benchmark::kTime &&
         (r.aggregate_name == "mean" || r.aggregate_name == "median");
}

}  // namespace

std::optional<row_name> parse_row_name(const std::string& name) {
  const std::vector<std::string> p = split(name, '/');
  row_name n;
  if (p.size() == 6 && p[0] == "render" && p[4].size() > 1 && p[4][0] == 't') {
    n.kind = p[0];
    n.backend = p[1];
    n.precision = p[2];
    n.threads = std::atoi(p[4].c_str() + 1);
    n.out = p[5];
    if (!parse_size(p[3], n.width, n.height) || n.threads < 1) return std::nullopt;
    return n;
  }
  if (p.size() == 7 && p[0] == "render" && p[5].size() > 1 && p[5][0] == 't') {
    n.kind = "scene";
    n.backend = p[1];
    n.precision = p[2];
    n.scene = p[3];
    n.threads = std::atoi(p[5].c_str() + 1);
    n.out = p[6];
    if (!parse_size(p[4], n.width, n.height) || n.threads < 1) return std::nullopt;
    return n;
  }
  if (p.size() == 7 && p[0] == "shortcuts" && p[4] == "t1") {
    n.kind = p[0];
    n.backend = p[1];
    n.precision = p[2];
    n.out = p[5];
    n.shortcuts = p[6];
    if (!parse_size(p[3], n.width, n.height)) return std::nullopt;
    return n;
  }
  if ((p.size() == 5 || p.size() == 6) && p[0] == "aa" && p.back().size() > 1 && p.back()[0] == 's') {
    const size_t at = p.size() - 5;  // 1 when the row names a sampler
    n.kind = p[0];
    n.backend = p[1];
    if (at) n.sampler = p[2];
    n.scene = p[2 + at];
    n.samples = std::atoll(p.back().c_str() + 1);
    if (!parse_size(p[3 + at], n.width, n.height) || n.samples < 1) return std::nullopt;
    return n;
  }
  if (p.size() == 4 && p[0] == "bound" && p[1] == "memset") {
    n.kind = p[0];
    n.backend = p[1];
    n.out = p[3];
    if (!parse_size(p[2], n.width, n.height)) return std::nullopt;
    return n;
  }
  return std::nullopt;
}

std::string render_row_name(const std::string& backend, std::string_view precision, int64_t w,
                            int64_t h, int threads, std::string_view out) {
  return strf("render/%s/%.*s/%lldx%lld/t%d/%.*s", backend.c_str(), int(precision.size()),
              precision.data(), static_cast<long long>(w), static_cast<long long>(h), threads,
              int(out.size()), out.data());
}

std::string shortcuts_row_name(const std::string& backend, std::string_view precision, int64_t w,
                               int64_t h, std::string_view set) {
  return strf("shortcuts/%s/%.*s/%lldx%lld/t1/rgb8/%.*s", backend.c_str(), int(precision.size()),
              precision.data(), static_cast<long long>(w), static_cast<long long>(h),
              int(set.size()), set.data());
}

std::string scene_row_name(const std::string& backend, std::string_view precision,
                           const std::string& scene, int64_t w, int64_t h, int threads,
                           std::string_view out) {
  return strf("render/%s/%.*s/%s/%lldx%lld/t%d/%.*s", backend.c_str(), int(precision.size()),
              precision.data(), scene.c_str(), static_cast<long long>(w), static_cast<long long>(h),
              threads, int(out.size()), out.data());
}

std::string memset_row_name(int64_t w, int64_t h) {
  return strf("bound/memset/%lldx%lld/rgb8", static_cast<long long>(w), static_cast<long long>(h));
}

std::string aa_row_name(const std::string& backend, const std::string& sampler, const std::string& scene,
                        int64_t w, int64_t h, int64_t samples) {
  return strf("aa/%s%s%s/%s/%lldx%lld/s%lld", backend.c_str(), sampler.empty() ? "" : "/",
              sampler.c_str(), scene.c_str(), static_cast<long long>(w), static_cast<long long>(h),
              static_cast<long long>(samples));
}

std::optional<double> run_table::seconds(const std::string& name) const {
  const auto it = seconds_.find(name);
  if (it == seconds_.end()) return std::nullopt;
  return it->second;
}

std::optional<double> run_table::counter(const std::string& row, const std::string& name) const {
  const auto it = counters_.find(row + "|" + name);
  if (it == counters_.end()) return std::nullopt;
  return it->second;
}

void run_table::fill(std::vector<Run>& runs) {
  if (runs.empty()) return;
  const std::string fn = runs.front().run_name.function_name;
  // A row's time is the median of its repetitions: on a machine shared with
  // other work, a repetition that lost the CPU for a while moves the mean but
  // not the median.
  auto median_of = [](std::vector<double>& v) {
    std::sort(v.begin(), v.end());
    const size_t n = v.size();
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
  };
  std::vector<double> times;
  std::map<std::string, std::vector<double>> counter_values;
  for (const Run& r : runs) {
    if (!has_time(r)) continue;
    if (r.run_type == Run::RT_Aggregate) {
      seconds_[fn + "|" + r.aggregate_name] = run_seconds(r);
      // Only aggregates reported (--benchmark_report_aggregates_only): theirs.
      if (r.aggregate_name == "median")
        for (const auto& [k, c] : r.counters) counters_[fn + "|" + k] = c.value;
      continue;
    }
    times.push_back(run_seconds(r));
    for (const auto& [k, c] : r.counters) counter_values[k].push_back(c.value);
  }
  const size_t n = times.size();
  double median = 0;
  if (n > 0) seconds_[fn + "|"] = median = median_of(times);
  for (auto& [k, v] : counter_values) counters_[fn + "|" + k] = median_of(v);

  const std::optional<row_name> name = parse_row_name(fn);
  if (!name) return;
  const double px = double(name->width) * double(name->height);
  const std::string ref =
      name->kind == "scene"
          ? scene_row_name("reference", "exact", name->scene, name->width, name->height, name->threads,
                           name->out)
          : render_row_name("reference", "exact", name->width, name->height, name->threads, name->out);
  const std::string bound = memset_row_name(name->width, name->height);
  for (Run& r : runs) {
    const double sec = run_seconds(r);
    if (!has_time(r) || !(sec > 0)) continue;
    const std::string key = std::string(1, '|').append(aggregate_key(r));
    r.counters["ns_per_px"] = sec * 1e9 / px;
    r.counters["Mpix_per_s"] = px / sec * 1e-6;
    if (name->kind == "aa") {
      r.counters["ns_per_sample"] = sec * 1e9 / (px * double(name->samples));
      continue;
    }
    if (name->kind == "shortcuts") {
      const std::string none =
          shortcuts_row_name(name->backend, name->precision, name->width, name->height, "none");
      if (auto t = seconds(none + key)) r.counters["vs_none"] = *t / sec;
      continue;
    }
    if (name->kind != "render" && name->kind != "scene") continue;
    if (name->backend == "reference")
      r.counters["speedup"] = 1.0;
    else if (auto t = seconds(ref + key))
      r.counters["speedup"] = *t / sec;
    if (auto t = seconds(bound + key)) r.counters["vs_memset"] = sec / *t;
  }

  if (name->kind != "render" && name->kind != "scene" && name->kind != "aa") return;
  measured_row row;
  row.name = *name;
  for (const Run& r : runs) {
    const bool iteration = r.run_type == Run::RT_Iteration && !r.error_occurred;
    // Only aggregates reported (--benchmark_report_aggregates_only): theirs.
    const bool median_aggregate = r.run_type == Run::RT_Aggregate && r.aggregate_name == "median";
    if (!iteration && !(median_aggregate && n == 0)) continue;
    row.seconds = iteration ? median : run_seconds(r);
    row.from_iterations = iteration;
    for (const auto& [k, c] : r.counters) row.counters[k] = c.value;
  }
  if (row.seconds <= 0) return;
  auto it = rows_.find(fn);
  if (it == rows_.end() || row.from_iterations || !it->second.from_iterations) rows_[fn] = row;
}

bool counter_filler::ReportContext(const Context& context) {
  inner_->SetOutputStream(&GetOutputStream());
  inner_->SetErrorStream(&GetErrorStream());
  return inner_->ReportContext(context);
}

void counter_filler::ReportRuns(const std::vector<Run>& runs) {
  std::vector<Run> filled = runs;
  table_.fill(filled);
  inner_->ReportRuns(filled);
}

void counter_filler::Finalize() { inner_->Finalize(); }

std::vector<summary_row> summary_rows(const run_table& table, const summary_options& opt) {
  std::vector<summary_row> rows;
  for (const auto& [fn, m] : table.rows()) {
    const row_name& n = m.name;
    if (n.width != opt.width || n.height != opt.height || n.threads != opt.threads ||
        n.out != opt.out)
      continue;
    // Rows whose error was not measured have no place in an error-vs-time
    // summary.
    if (!m.counters.count("max_abs_err") && !m.counters.count("max_lsb")) continue;
    summary_row s;
    s.scene = n.scene;
    s.label = n.backend + "/" + n.precision + (n.scene.empty() ? "" : "/" + n.scene);
    s.ns_per_px = m.seconds * 1e9 / (double(n.width) * double(n.height));
    // Speedup against the reference of the same scene (the sky's for sky rows).
    const std::string ref_name =
        n.scene.empty() ? render_row_name("reference", "exact", opt.width, opt.height, opt.threads, opt.out)
                        : scene_row_name("reference", "exact", n.scene, opt.width, opt.height, opt.threads,
                                         opt.out);
    const auto ref = table.rows().find(ref_name);
    if (ref != table.rows().end()) s.speedup = ref->second.seconds / m.seconds;
    auto counter = [&](const char* k) {
      const auto it = m.counters.find(k);
      return it == m.counters.end() ? 0.0 : it->second;
    };
    // A row without float output (the book's program: 8-bit only) has no
    // max_abs_err: unknown, not 0.
    s.max_abs_err = m.counters.count("max_abs_err") ? counter("max_abs_err") : NAN;
    s.max_lsb = int(counter("max_lsb"));
    s.lsb_mismatch = counter("lsb_mismatch");
    rows.push_back(s);
  }
  // The sky first, then each scene; fastest first within each.
  std::sort(rows.begin(), rows.end(), [](const summary_row& a, const summary_row& b) {
    return a.scene != b.scene ? a.scene < b.scene : a.ns_per_px < b.ns_per_px;
  });
  // Pareto within a scene: times of different scenes do not compare.
  for (summary_row& r : rows) {
    r.pareto = !std::isnan(r.max_abs_err) && std::none_of(rows.begin(), rows.end(), [&](const summary_row& o) {
      return o.scene == r.scene && o.ns_per_px < r.ns_per_px && o.max_abs_err <= r.max_abs_err;
    });
  }
  return rows;
}

std::string size_text(int64_t w, int64_t h) {
  return strf("%lldx%lld", static_cast<long long>(w), static_cast<long long>(h));
}

std::string error_text(double e) {
  if (e == 0) return "0";
  if (!std::isfinite(e)) return "inf";
  return strf("%.1e", e);
}

void print_summary(std::ostream& os, const std::vector<summary_row>& rows,
                   const summary_options& opt, const std::vector<skipped_backend>& skipped) {
  os << "\nError vs run time: " << opt.cpu << ", " << opt.date << ", "
     << size_text(opt.width, opt.height) << ", " << opt.threads << " thread"
     << (opt.threads == 1 ? "" : "s") << " (of " << available_cores() << " cores), " << opt.out
     << " output\n"
     << "  ns/px: the median of a row's repetitions (--benchmark_repetitions=N; one by default)\n"
     << "  errors vs the double reference over the whole image: max_abs_err in linear colour\n"
     << "  (from the f32 rendering), max_lsb and lsb_mismatch from the 8-bit bytes;\n"
     << "  * = Pareto-optimal: no other row of the same scene is both faster and at most as\n"
     << "  wrong (max_abs_err; - where a row has no float output); the sky, then each sphere scene\n";
  if (rows.empty()) {
    os << "  (no rows measured at this size, thread count and output; see --benchmark_filter)\n";
  } else {
    os << strf("    %-36s %9s %9s %12s %8s %13s\n", "backend/precision[/scene]", "ns/px", "speedup",
               "max_abs_err", "max_lsb", "lsb_mismatch");
    for (size_t k = 0; k < rows.size(); ++k) {
      const summary_row& r = rows[k];
      if (k > 0 && rows[k - 1].scene != r.scene) os << "\n";
      const std::string speedup = r.speedup ? strf("%.1fx", *r.speedup) : "-";
      const std::string err = std::isnan(r.max_abs_err) ? "-" : error_text(r.max_abs_err);
      os << strf("  %c %-36s %9.3f %9s %12s %8d %12.4f%%\n", r.pareto ? '*' : ' ', r.label.c_str(),
                 r.ns_per_px, speedup.c_str(), err.c_str(), r.max_lsb, 100.0 * r.lsb_mismatch);
    }
  }
  os << "Skipped backends: ";
  if (skipped.empty()) os << "none (this CPU runs every backend)";
  for (size_t i = 0; i < skipped.size(); ++i)
    os << (i ? "; " : "") << skipped[i].name << " (" << skipped[i].reason << ")";
  os << "\n";
}

std::string xml_escape(const std::string& s) {
  std::string out;
  for (char c : s) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      default: out += c;
    }
  }
  return out;
}

// "10" with a superscript exponent.
std::string decade_label(int e) {
  return strf("10<tspan dy=\"-7\" font-size=\"10\">%d</tspan>", e);
}


void write_svg_header(std::ostream& out, const log_chart& c, const std::string& title,
                      const std::string& subtitle) {
  out << strf(
      "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%.0f\" height=\"%.0f\" "
      "viewBox=\"0 0 %.0f %.0f\" font-family=\"sans-serif\" font-size=\"12\">\n",
      c.W, c.H, c.W, c.H);
  out << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
  out << strf("<text x=\"%.0f\" y=\"28\" text-anchor=\"middle\" font-size=\"16\">", c.W / 2)
      << title << "</text>\n";
  out << strf("<text x=\"%.0f\" y=\"50\" text-anchor=\"middle\" fill=\"#444\">", c.W / 2) << subtitle
      << "</text>\n";
  // Grid, ticks and axis titles.
  for (int e = c.x0; e <= c.x1; ++e) {
    const double x = c.px(std::pow(10.0, e));
    out << strf("<line x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\" stroke=\"#ddd\"/>\n", x, c.top,
                x, c.top + c.ph());
    out << strf("<text x=\"%.1f\" y=\"%.1f\" text-anchor=\"middle\">", x, c.top + c.ph() + 20)
        << decade_label(e) << "</text>\n";
  }
  for (int e = c.y0; e <= c.y1; ++e) {
    const double y = c.py(std::pow(10.0, e));
    out << strf("<line x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\" stroke=\"#ddd\"/>\n", c.left,
                y, c.left + c.pw(), y);
    out << strf("<text x=\"%.1f\" y=\"%.1f\" text-anchor=\"end\">", c.left - 8, y + 4)
        << (e == c.y0 && c.zero_at_bottom ? std::string("0") : decade_label(e)) << "</text>\n";
  }
  out << strf(
      "<rect x=\"%.1f\" y=\"%.1f\" width=\"%.1f\" height=\"%.1f\" fill=\"none\" "
      "stroke=\"#333\"/>\n",
      c.left, c.top, c.pw(), c.ph());
  out << strf("<text x=\"%.1f\" y=\"%.1f\" text-anchor=\"middle\">", c.left + c.pw() / 2, c.H - 22)
      << c.x_title << "</text>\n";
  out << strf("<text transform=\"translate(24 %.1f) rotate(-90)\" text-anchor=\"middle\">",
              c.top + c.ph() / 2)
      << c.y_title << "</text>\n";
}

double log_chart::px(double v) const { return left + (std::log10(v) - x0) / (x1 - x0) * pw(); }

double log_chart::py(double v) const {
  const double y = std::isfinite(v) ? std::log10(std::max(v, y_floor)) : y1;
  return top + ph() - (y - y0) / (y1 - y0) * ph();
}

void log_chart::fit_x(double lo, double hi) {
  x0 = int(std::floor(std::log10(lo)));
  x1 = std::max(x0 + 1, int(std::ceil(std::log10(hi))));
}

void log_chart::fit_y(double lo, double hi) {
  y_floor = lo;
  y0 = int(std::floor(std::log10(lo) + 1e-9));  // 1e-9 is decade -9, whatever log10 rounds to
  y1 = std::max(y0 + 1, int(std::ceil(std::log10(hi))));
}

bool write_svg(const std::string& file, const std::vector<summary_row>& rows,
               const summary_options& opt) {
  std::ofstream out(file);
  if (!out) return false;
  constexpr double floor_err = 1e-9;
  log_chart c;
  double xlo = 1e300, xhi = 0, yhi = floor_err * 10;
  for (const summary_row& r : rows) {
    xlo = std::min(xlo, r.ns_per_px);
    xhi = std::max(xhi, r.ns_per_px);
    if (std::isfinite(r.max_abs_err)) yhi = std::max(yhi, r.max_abs_err);  // NaN: not plotted
  }
  if (rows.empty()) xlo = xhi = 1;
  c.fit_x(xlo, xhi);
  c.fit_y(floor_err, yhi);
  c.zero_at_bottom = true;
  c.x_title = "time per pixel (ns, log)";
  c.y_title = "max abs error, linear colour (log; 0 at the bottom)";
  const double W = c.W, H = c.H, top = c.top;
  auto px = [&](double ns) { return c.px(ns); };
  auto py = [&](double e) { return c.py(e); };
  write_svg_header(out, c, "raycast: error vs run time — " + xml_escape(opt.cpu) + ", " + opt.date,
                   size_text(opt.width, opt.height) + ", " + std::to_string(opt.threads) + " thread" +
                       (opt.threads == 1 ? "" : "s") + ", " + opt.out +
                       " output; error vs the double reference; filled = Pareto-optimal");
  // Each scene's Pareto front as a dashed staircase (the edge of what it
  // dominates); rows are sorted by scene, then time.
  std::map<std::string, std::pair<std::string, std::string>> fronts;  // scene -> points, last y
  for (const summary_row& r : rows) {
    if (!r.pareto) continue;
    auto& [front, front_y] = fronts[r.scene];
    if (!front.empty()) front += strf("%.1f,%s ", px(r.ns_per_px), front_y.c_str());
    front_y = strf("%.1f", py(r.max_abs_err));
    front += strf("%.1f,%s ", px(r.ns_per_px), front_y.c_str());
  }
  for (const auto& [scene, front] : fronts)
    out << "<polyline points=\"" << front.first
        << "\" fill=\"none\" stroke=\"#1f4e9c\" stroke-dasharray=\"4 4\" opacity=\"0.6\"/>\n";
  struct box {
    double x0, y0, x1, y1;
    bool hits(const box& o) const { return x0 < o.x1 && o.x0 < x1 && y0 < o.y1 && o.y0 < y1; }
  };
  std::vector<box> taken;
  for (const summary_row& r : rows) {
    if (std::isnan(r.max_abs_err)) continue;
    const double x = px(r.ns_per_px), y = py(r.max_abs_err);
    taken.push_back({x - 6, y - 6, x + 6, y + 6});
    out << strf(
        "<circle cx=\"%.1f\" cy=\"%.1f\" r=\"5\" fill=\"%s\" stroke=\"#1f4e9c\" "
        "stroke-width=\"1.5\"/>\n",
        x, y, r.pareto ? "#1f4e9c" : "white");
  }
  // Each label beside its point, at the first place that covers no point and
  // no earlier label: right, left, below, above, then further out.
  for (const summary_row& r : rows) {
    if (std::isnan(r.max_abs_err)) continue;
    const double x = px(r.ns_per_px), y = py(r.max_abs_err);
    const double w = 6.8 * double(r.label.size());
    const char* anchor = "start";
    double tx = x + 8, ty = y + 4;
    box b{};
    for (int k = 0; k < 24; ++k) {
      const int ring = k / 4;  // 0, then 13 px further out each time, alternating
      const double side = 13.0 * double((ring + 1) / 2) * (ring % 2 ? 1 : -1);
      const double away = 13.0 * double(ring);
      switch (k % 4) {
        case 0: anchor = "start", tx = x + 8, ty = y + 4 + side; break;
        case 1: anchor = "end", tx = x - 8, ty = y + 4 + side; break;
        case 2: anchor = "middle", tx = x, ty = y + 19 + away; break;
        default: anchor = "middle", tx = x, ty = y - 10 - away; break;
      }
      const double left_x = k % 4 == 0 ? tx : k % 4 == 1 ? tx - w : tx - w / 2;
      b = {left_x, ty - 10, left_x + w, ty + 3};
      const bool inside = b.x0 >= 0 && b.x1 <= W && b.y0 >= top - 20 && b.y1 <= H - 30;
      if (inside &&
          std::none_of(taken.begin(), taken.end(), [&](const box& o) { return o.hits(b); }))
        break;
    }
    taken.push_back(b);
    out << strf("<text x=\"%.1f\" y=\"%.1f\" text-anchor=\"%s\">%s</text>\n", tx, ty, anchor,
                xml_escape(r.label).c_str());
  }
  out << "</svg>\n";
  return bool(out);
}

void print_stiff(std::ostream& os, const std::vector<path>& paths,
                 const std::vector<stiff_result>& results) {
  std::vector<size_t> cols;  // every path but the reference, which is the oracle
  for (size_t p = 0; p < paths.size(); ++p)
    if (paths[p].autovec || paths[p].core != backend::reference) cols.push_back(p);
  auto table = [&](const char* title, auto cell) {
    os << title << "\n" << strf("  %-40s %-9s", "case", "size");
    for (size_t p : cols) os << strf(" %9s", paths[p].backend.c_str());
    os << "\n" << strf("  %-40s %-9s", "", "");
    for (size_t p : cols) os << strf(" %9s", std::string(to_string(paths[p].prec)).c_str());
    os << "\n";
    for (const stiff_result& r : results) {
      os << strf("  %-40s %-9s", r.name.c_str(), size_text(r.width, r.height).c_str());
      if (!r.invalid.empty()) os << "  refused: " << r.invalid;
      for (size_t p : cols)
        if (r.invalid.empty()) os << strf(" %9s", cell(r.errors[p]).c_str());
      os << "\n";
    }
  };
  os << "\nStiff cases (not timed): error vs the double reference (raycast::reference_pixel)\n";
  table("max_abs_err, linear colour (f32 output):",
        [](const error_stats& e) { return error_text(e.max_abs_err); });
  table("max_lsb (rgb8 output):", [](const error_stats& e) { return strf("%d", e.max_lsb); });
  table("NaN count (f32 output; should be 0):",
        [](const error_stats& e) { return strf("%lld", static_cast<long long>(e.nan_count)); });
}

void print_sphere_stiff(std::ostream& os, const std::vector<sphere_stiff_result>& results) {
  using raycast_test::sphere_metrics;
  // A count away from silhouettes, with the total in parentheses when it differs.
  auto count = [](int64_t away, int64_t all) {
    return away == all ? strf("%lld", static_cast<long long>(all))
                       : strf("%lld (%lld)", static_cast<long long>(away), static_cast<long long>(all));
  };
  auto cell = [](const sphere_stiff_result& r, auto text) {
    return text(r.ours) + " / " + text(r.naive) + " / " + (r.embree_error.empty() ? text(r.embree) : "-");
  };
  os << "\nStiff sphere cases (not timed): ours / naive (the book's ch. 6 hit_sphere in float) / Embree\n"
        "(rtcIntersect1) against the double reference; counts are pixels away from silhouettes, (all)\n"
        "where they differ; distance error relative, where both hit the same sphere away from\n"
        "silhouettes; LSB: 8-bit error of the pixels the reference shades from a sphere.\n\n";
  os << "| case | size | wrong object | false hits | false misses | max distance error | max LSB |\n"
        "|---|---|---|---|---|---|---|\n";
  for (const sphere_stiff_result& r : results) {
    os << "| " << r.name << " | " << size_text(r.width, r.height) << " | "
       << cell(r, [&](const sphere_metrics& m) { return count(m.wrong_object_away, m.wrong_object); }) << " | "
       << cell(r, [&](const sphere_metrics& m) { return count(m.false_hits_away, m.false_hits); }) << " | "
       << cell(r, [&](const sphere_metrics& m) { return count(m.false_misses_away, m.false_misses); }) << " | "
       << cell(r, [](const sphere_metrics& m) { return error_text(m.max_rel_distance_err); }) << " | "
       << cell(r, [&](const sphere_metrics& m) { return count(m.max_lsb_away, m.max_lsb); }) << " |\n";
  }
  for (const sphere_stiff_result& r : results)
    if (!r.embree_error.empty()) os << "Embree, " << r.name << ": " << r.embree_error << "\n";
}

std::string cpu_model() {
  std::ifstream in("/proc/cpuinfo");
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("model name", 0) != 0) continue;
    const size_t colon = line.find(':');
    if (colon == std::string::npos) break;
    const size_t start = line.find_first_not_of(" \t", colon + 1);
    return start == std::string::npos ? "unknown CPU" : line.substr(start);
  }
  return "unknown CPU";
}

std::string today() {
  const std::time_t now = std::time(nullptr);
  std::tm tm{};
  localtime_r(&now, &tm);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%d", &tm);
  return buf;
}

}  // namespace raycast::bench

namespace raycast::bench {

void print_shortcuts(std::ostream& os, const run_table& table, const std::vector<std::string>& sets) {
  std::map<std::pair<std::string, std::string>, std::map<std::string, double>> grid;
  int64_t w = 0, h = 0;
  for (const auto& [key, sec] : table.all_seconds()) {
    const std::string fn = key.substr(0, key.find('|'));
    if (key.back() != '|') continue;  // plain runs only, not aggregates
    const std::optional<row_name> n = parse_row_name(fn);
    if (!n || n->kind != "shortcuts") continue;
    w = n->width;
    h = n->height;
    grid[{n->backend, n->precision}][n->shortcuts] = sec * 1e9 / (double(w) * double(h));
  }
  if (grid.empty()) return;
  os << "\nWhat each shortcut saves (shortcuts/ rows): ns/px at " << w << "x" << h
     << ", 1 thread, rgb8; none = the general path, all = every shortcut (the default)\n";
  os << strf("  %-18s", "backend/precision");
  for (const std::string& v : sets) os << strf("%14s", v.c_str());
  os << "\n";
  for (const auto& [bp, cells] : grid) {
    os << strf("  %-18s", (bp.first + "/" + bp.second).c_str());
    for (const std::string& v : sets) {
      const auto it = cells.find(v);
      os << (it == cells.end() ? strf("%14s", "-") : strf("%14.3f", it->second));
    }
    os << "\n";
  }
}

}  // namespace raycast::bench
