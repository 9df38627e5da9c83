#include "aa_report.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <optional>
#include <ostream>

#include "aa_stats.h"

namespace raycast::bench {
namespace {

// One measured aa/ row at the config's size: ours (sampler set) or the book's.
struct aa_point {
  std::string scene, sampler;  // sampler empty: the book's row
  int64_t samples = 1;
  double ns_per_px = 0, ns_per_sample = 0, rmse = 0, max_abs = 0;
};

std::vector<aa_point> aa_points(const run_table& table, const aa_config& cfg) {
  std::vector<aa_point> out;
  for (const auto& [fn, m] : table.rows()) {
    const row_name& n = m.name;
    if (n.kind != "aa" || n.width != cfg.width || n.height != cfg.height) continue;
    if (n.backend != cfg.backend && !(n.backend == "book7" && n.sampler.empty())) continue;
    if (!m.counters.count("rms_err")) continue;
    aa_point p;
    p.scene = n.scene;
    p.sampler = n.sampler;
    p.samples = n.samples;
    p.ns_per_px = m.seconds * 1e9 / (double(n.width) * double(n.height));
    p.ns_per_sample = p.ns_per_px / double(n.samples);
    p.rmse = m.counters.at("rms_err");
    p.max_abs = m.counters.count("max_abs_err") ? m.counters.at("max_abs_err") : NAN;
    out.push_back(p);
  }
  std::sort(out.begin(), out.end(), [](const aa_point& a, const aa_point& b) {
    return std::tie(a.scene, a.sampler, a.samples) < std::tie(b.scene, b.sampler, b.samples);
  });
  return out;
}

// A sampler's points on a scene, by N.
std::vector<aa_point> curve_of(const std::vector<aa_point>& pts, const std::string& scene,
                               const std::string& sampler) {
  std::vector<aa_point> out;
  for (const aa_point& p : pts)
    if (p.scene == scene && p.sampler == sampler) out.push_back(p);
  return out;
}

std::vector<error_point> error_curve(const std::vector<aa_point>& c) {
  std::vector<error_point> out;
  for (const aa_point& p : c) out.push_back({double(p.samples), p.rmse});
  return out;
}

const aa_point* find_point(const std::vector<aa_point>& pts, const std::string& scene,
                           const std::string& sampler, int64_t samples) {
  for (const aa_point& p : pts)
    if (p.scene == scene && p.sampler == sampler && p.samples == samples) return &p;
  return nullptr;
}

std::string point_line(const std::string& label, const aa_point& p) {
  return strf("  %-12s %6lld %10.2f %10.3f %10s %10s\n", label.c_str(), static_cast<long long>(p.samples),
              p.ns_per_px, p.ns_per_sample, error_text(p.rmse).c_str(), error_text(p.max_abs).c_str());
}

// "16384 (128x128 strata)": the grid sample_table picks for a stratified count.
std::string strata_text(uint32_t n) {
  uint32_t nx = 1;
  for (uint32_t d = 1; uint64_t(d) * d <= n; ++d)
    if (n % d == 0) nx = d;
  return strf("%u (%ux%u strata)", n, nx, n / nx);
}

}  // namespace

void print_region_summary(std::ostream& os, const run_table& table, const aa_config& cfg);

void print_aa_summary(std::ostream& os, const run_table& table, const aa_config& cfg,
                      const std::vector<const aa_reference*>& refs, const std::string& cpu,
                      const std::string& date) {
  print_region_summary(os, table, cfg);
  const std::vector<aa_point> pts = aa_points(table, cfg);
  if (pts.empty()) return;
  const std::string book = "book7";
  os << "\nAntialiasing: error vs run time (aa/ rows): " << cpu << ", " << date << ", "
     << size_text(cfg.width, cfg.height) << ", 1 thread, rgb_f32, " << cfg.backend << "/exact, seed 0\n"
     << "  error of linear colour against the converged reference (the double reference,\n"
     << "  stratified, " << strata_text(cfg.reference_samples)
     << " a pixel): RMSE over every pixel and channel, and max\n"
     << "  abs error; ns/px: the median of a row's repetitions. N = 1 is the pixel point for every\n"
     << "  sampler (the same image; its rows differ in time only). book7: the book's ch. 7\n"
     << "  program (double, rand(), virtual hits), the same reference.\n";
  for (const aa_reference* r : refs)
    os << strf("  reference %-6s built in %.1f s on %d thread%s", r->spec.scene.c_str(), r->build_seconds,
               r->threads, r->threads == 1 ? "" : "s")
       << (r->from_cache ? " (read from " + r->file + ")"
                         : r->file.empty() ? " (not cached)" : " (now cached in " + r->file + ")")
       << "\n";
  for (const std::string& scene : cfg.scenes) {
    os << "\n" << scene << strf("%*s", int(19 - scene.size()), "N")
       << strf(" %10s %10s %10s %10s\n", "ns/px", "ns/sample", "RMSE", "max err");
    for (sampler_kind k : cfg.samplers) {
      const std::string name(to_string(k));
      const std::vector<aa_point> c = curve_of(pts, scene, name);
      for (size_t i = 0; i < c.size(); ++i) os << point_line(i == 0 ? name : "", c[i]);
    }
    for (const aa_point& p : curve_of(pts, scene, "")) os << point_line(book, p);
    os << "  log-log slope of RMSE against N (least squares, N >= 4):";
    for (sampler_kind k : cfg.samplers) {
      const auto slope = loglog_slope(error_curve(curve_of(pts, scene, std::string(to_string(k)))));
      os << " " << to_string(k) << " " << (slope ? strf("%.2f", *slope) : std::string("-"));
    }
    os << "\n";
    // The reference is itself a stratified estimate: its own RMSE is about
    // the stratified curve's at its sample count, the floor of what the rows
    // can show.
    const std::vector<aa_point> strat = curve_of(pts, scene, "stratified");
    const auto slope = loglog_slope(error_curve(strat));
    if (slope && *slope < 0)
      os << "  the reference's own RMSE, the stratified curve extrapolated to "
         << cfg.reference_samples << ": about "
         << error_text(strat.back().rmse *
                       std::pow(double(cfg.reference_samples) / double(strat.back().samples), *slope))
         << "\n  (an RMSE within a few times of it measures the reference as much as the row)\n";
  }

  // The book's RMSE at its samples: what each of our samplers needs to match it.
  for (const aa_point& b : pts) {
    if (!b.sampler.empty()) continue;
    os << "\nSamples to match the book's RMSE on " << b.scene << " (" << error_text(b.rmse) << " at "
       << b.samples << " random samples):\n  N* interpolated in log-log; the goal for the "
       << "default sampler, " << to_string(default_sampler) << ": N*/" << b.samples << " <= 0.25\n";
    for (sampler_kind k : cfg.samplers) {
      const auto m = samples_to_match(error_curve(curve_of(pts, b.scene, std::string(to_string(k)))), b.rmse);
      os << strf("  %-12s ", std::string(to_string(k)).c_str());
      if (!m) os << "N* -  (the curve does not reach it)\n";
      else
        os << strf("N* %8.1f   N*/%lld = %.3f%s\n", m->samples, static_cast<long long>(b.samples),
                   m->samples / double(b.samples), m->extrapolated ? "  (extrapolated past the last N)" : "");
    }
    // Per-sample speed: the book's ns/sample over ours, at our largest N (and 64).
    os << "Per-sample speed on " << b.scene << ", book7 s" << b.samples << " " << strf("%.2f", b.ns_per_sample)
       << " ns/sample against ours (goal: >= 50x):\n";
    std::vector<int64_t> at;
    for (int64_t n : {int64_t(64), cfg.samples.back()})
      if (std::count(cfg.samples.begin(), cfg.samples.end(), n) && !std::count(at.begin(), at.end(), n))
        at.push_back(n);
    for (sampler_kind k : cfg.samplers) {
      os << strf("  %-12s", std::string(to_string(k)).c_str());
      for (int64_t n : at)
        if (const aa_point* p = find_point(pts, b.scene, std::string(to_string(k)), n))
          os << strf("  s%-4lld %7.3f ns/sample %7.1fx", static_cast<long long>(n), p->ns_per_sample,
                     b.ns_per_sample / p->ns_per_sample);
      os << "\n";
    }
  }
}

void print_region_summary(std::ostream& os, const run_table& table, const aa_config& cfg) {
  const std::vector<region_row> rows = region_rows(cfg);
  const std::optional<double> full = table.seconds(rows.front().name + "|");
  if (!full) return;
  os << "\nRegions (--region) of world " << rows.front().width << "x" << rows.front().height
     << ", 16 samples, 1 thread: each quadrant rendered on its own (edges inside batches)\n";
  double sum = 0;
  bool all = true;
  for (const region_row& r : rows) {
    const std::optional<double> t = table.seconds(r.name + "|");
    if (!t) {
      all = false;
      continue;
    }
    const double px = double(r.x1 - r.x0) * double(r.y1 - r.y0);
    os << strf("  %-44s %9.2f ms  %6.2f ns per region pixel\n", r.name.c_str(), *t * 1e3, *t * 1e9 / px);
    if (&r != &rows.front()) sum += *t;
  }
  if (all) os << strf("  the four quadrants together: %.2f ms, %.3f x the whole frame's time\n", sum * 1e3, sum / *full);
}

std::string aa_plot_file(const std::string& plot) {
  const size_t dot = plot.rfind('.');
  const size_t slash = plot.rfind('/');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return plot + "-aa.svg";
  return plot.substr(0, dot) + "-aa" + plot.substr(dot);
}

bool write_aa_svg(const std::string& file, const run_table& table, const aa_config& cfg,
                  const std::string& cpu, const std::string& date) {
  const std::vector<aa_point> pts = aa_points(table, cfg);
  if (pts.empty()) return false;
  std::ofstream out(file);
  if (!out) return false;
  log_chart c;
  c.right = 170;
  double xlo = 1e300, xhi = 0, ylo = 1e300, yhi = 0;
  for (const aa_point& p : pts) {
    xlo = std::min(xlo, p.ns_per_px), xhi = std::max(xhi, p.ns_per_px);
    if (p.rmse > 0) ylo = std::min(ylo, p.rmse), yhi = std::max(yhi, p.rmse);
  }
  if (!(yhi > 0)) ylo = 1e-6, yhi = 1;
  c.fit_x(xlo, xhi);
  c.fit_y(std::pow(10.0, std::floor(std::log10(ylo))), yhi);
  c.x_title = "time per pixel (ns, log), 1 thread";
  c.y_title = "RMSE against the converged reference, linear colour (log)";
  write_svg_header(out, c, "raycast: antialiasing error vs run time — " + xml_escape(cpu) + ", " + date,
                   size_text(cfg.width, cfg.height) + ", " + cfg.backend +
                       "/exact, rgb_f32; points N = " + [&] {
                         std::string s;
                         for (int64_t n : cfg.samples) s += (s.empty() ? "" : ", ") + std::to_string(n);
                         return s;
                       }() + " samples a pixel; solid: world, dashed: sky");
  const char* colours[] = {"#d62728", "#2ca02c", "#1f4e9c"};  // random, stratified, sobol
  double legend_y = c.top + 10;
  for (size_t si = 0; si < cfg.scenes.size(); ++si)
    for (size_t ki = 0; ki < cfg.samplers.size(); ++ki) {
      const std::string sampler(to_string(cfg.samplers[ki]));
      const std::vector<aa_point> cv = curve_of(pts, cfg.scenes[si], sampler);
      if (cv.empty()) continue;
      const char* colour = colours[ki % 3];
      const char* dash = si == 0 ? "" : " stroke-dasharray=\"6 4\"";
      std::string line;
      for (const aa_point& p : cv) line += strf("%.1f,%.1f ", c.px(p.ns_per_px), c.py(p.rmse));
      out << "<polyline points=\"" << line << "\" fill=\"none\" stroke=\"" << colour
          << "\" stroke-width=\"1.8\"" << dash << "/>\n";
      for (const aa_point& p : cv)
        out << strf("<circle cx=\"%.1f\" cy=\"%.1f\" r=\"3.5\" fill=\"white\" stroke=\"%s\" stroke-width=\"1.5\"/>\n",
                    c.px(p.ns_per_px), c.py(p.rmse), colour);
      // N beside the last point of each curve.
      const aa_point& last = cv.back();
      out << strf("<text x=\"%.1f\" y=\"%.1f\" font-size=\"10\" fill=\"%s\">s%lld</text>\n",
                  c.px(last.ns_per_px) + 6, c.py(last.rmse) + 12, colour, static_cast<long long>(last.samples));
      const double lx = c.left + c.pw() + 14;
      out << strf("<line x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\" stroke=\"%s\" stroke-width=\"1.8\"%s/>\n",
                  lx, legend_y, lx + 26, legend_y, colour, dash);
      out << strf("<text x=\"%.1f\" y=\"%.1f\">", lx + 32, legend_y + 4)
          << xml_escape(sampler + " / " + cfg.scenes[si]) << "</text>\n";
      legend_y += 18;
    }
  for (const aa_point& p : pts) {
    if (!p.sampler.empty()) continue;  // the book's point: a black diamond
    const double x = c.px(p.ns_per_px), y = c.py(p.rmse);
    out << strf("<path d=\"M %.1f %.1f l 7 7 l -7 7 l -7 -7 z\" fill=\"black\"/>\n", x, y - 7);
    out << strf("<text x=\"%.1f\" y=\"%.1f\" text-anchor=\"end\">", x - 10, y + 4)
        << xml_escape("book7 s" + std::to_string(p.samples) + " (" + p.scene + ")") << "</text>\n";
  }
  out << "</svg>\n";
  return bool(out);
}

}  // namespace raycast::bench
