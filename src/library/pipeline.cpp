#include "library/pipeline.h"

#include <algorithm>
#include <utility>

#include "scene/scene.h"

namespace raycast {
namespace {

using enum setting_id;
using kind = error_kind;

}  // namespace

std::string spell(const setting& row, front_end fe) {
  if (fe == front_end::command_line) return std::string(row.option);
  return std::string(row.file_key.empty() ? row.keyword : row.file_key);
}

api::error library_error(const refusal& r) {
  return api::error(r.kind, r.source.empty() ? "scene" : r.source, (r.file.empty() ? "" : r.file + ": ") + r.why);
}

refusal refused(const setting_error& e, std::string file) {
  return refusal{kind::invalid_argument, e.source, std::move(file), e.message};
}

io::file_format output_format(const std::string& path, const std::string& format_name, front_end fe) {
  const std::string out = spell(input_row(output), fe), fmt = spell(input_row(format), fe);
  if (path.empty()) throw refusal{kind::invalid_argument, out, "", "empty file name"};
  io::file_format f{};
  if (!format_name.empty()) {
    const setting& row = input_row(format);
    size_t k = 0;
    if (auto e = parse_name(format_name, row.names, k, row.any_case)) throw refusal{kind::invalid_argument, fmt, "", *e};
    f = *io::format_from_name(row.names[k]);
  } else if (auto why = io::format_from_path(path, f)) {
    throw refusal{kind::invalid_argument, out, "", *why};
  }
  if (path == "-")
    if (auto why = io::stdout_format_error(f)) throw refusal{kind::invalid_argument, fmt, "", *why};
  return f;
}

api::region output_region(const api::options& o, int64_t width, int64_t height, front_end fe) {
  if (!o.region) return {0, 0, width, height};
  const api::region& g = *o.region;
  const std::string got = std::to_string(g.x0) + "," + std::to_string(g.y0) + "," + std::to_string(g.x1) + "," +
                          std::to_string(g.y1);
  if (auto why = check_region({g.x0, g.y0, g.x1, g.y1}, width, height, got))
    throw refusal{kind::invalid_argument, spell(input_row(region), fe), "", *why};
  return g;
}

void check_sides(io::file_format f, const api::region& r, const side_blame& blame, front_end fe) {
  const int64_t side = io::max_side(f), longest = std::max(r.width(), r.height());
  if (side <= 0 || longest <= side) return;
  const std::string why = std::string(io::display_name(f)) + " supports at most " + std::to_string(side) +
                          " pixels per side, got ";
  const auto refuse = [&](std::string source, std::string got) {
    throw refusal{kind::invalid_argument, std::move(source), "", why + got};
  };
  if (fe == front_end::library) refuse("format", std::to_string(longest));
  // The command line blames the option that made the side too long.
  if (blame.region) refuse("--region", std::to_string(longest));
  if (r.width() > side) refuse("--width", std::to_string(r.width()));
  if (blame.height) refuse("--height", std::to_string(r.height()));
  refuse("--aspect", "a height of " + std::to_string(r.height()));
}

render_options renderer_options(const api::options& o) {
  if (auto e = check_options(o)) throw library_error(refused(*e));
  const raycast::backend b = *parse_backend(o.backend);
  if (auto why = backend_unavailable(b)) throw api::error(kind::unsupported_backend, "backend", *why);
  render_options r;
  r.which = b;
  r.prec = *parse_precision(o.precision);
  r.threads = o.threads;
  r.samples = uint32_t(o.samples);
  r.sampler = *parse_sampler(o.sampler);
  r.seed = o.seed;
  return r;
}

}  // namespace raycast
