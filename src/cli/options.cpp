#include "options.h"

#include "scene/builtin.h"
#include "scene/scene_file.h"

#include <CLI/CLI.hpp>

#include <algorithm>
#include <array>
#include <cerrno>
#include <charconv>
#include <chrono>
#include <cstdlib>
#include <cmath>
#include <string>
#include <vector>
#include <ostream>

namespace raycast::cli {

namespace {

std::string lower(std::string_view s) {
  std::string r(s);
  std::transform(r.begin(), r.end(), r.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return r;
}

using io::format_from_name;

std::string in_quotes(std::string_view s) { return "'" + std::string(s) + "'"; }

// The option that sets a scene field (the camera position has two spellings).
std::string_view option_for(scene_field f, std::string_view origin_option) {
  switch (f) {
    case scene_field::width: return "--width";
    case scene_field::height: return "--height";
    case scene_field::aspect: return "--aspect";
    case scene_field::viewport_height: return "--viewport-height";
    case scene_field::focal_length: return "--focal-length";
    case scene_field::origin: return origin_option;
    case scene_field::lookat: return "--lookat";
    case scene_field::vup: return "--vup";
    case scene_field::vfov: return "--vfov";
    case scene_field::sky_bottom: return "--sky-bottom";
    case scene_field::sky_top: return "--sky-top";
    case scene_field::sphere_center:
    case scene_field::sphere_radius:
    case scene_field::sphere_color: return "--scene";
  }
  return "--help";
}


}  // namespace

std::string printable(std::string_view s) {
  static constexpr char hex[] = "0123456789abcdef";
  std::string r;
  for (const unsigned char c : s) {
    if (c < 0x20 || c == 0x7f) {
      r += "\\x";
      r += hex[c >> 4];
      r += hex[c & 15];
    } else {
      r += char(c);
    }
  }
  return r;
}

std::optional<std::string> parse_int(std::string_view text, int64_t& value) {
  if (text.empty()) return "empty value";
  const char* end = text.data() + text.size();
  auto [p, ec] = std::from_chars(text.data(), end, value);
  if (ec == std::errc::result_out_of_range) return in_quotes(text) + " is out of range";
  if (ec != std::errc() || p != end) return in_quotes(text) + " is not an integer";
  return std::nullopt;
}

std::optional<std::string> parse_real(std::string_view text, double& value) {
  if (text.empty()) return "empty value";
  const char* begin = text.data();
  const char* end = begin + text.size();
  if (*begin == '+') ++begin;  // from_chars takes no plus sign
  auto [p, ec] = std::from_chars(begin, end, value);
  if (ec == std::errc::result_out_of_range) return in_quotes(text) + " is out of range for a double";
  if (ec != std::errc() || p != end || begin == end) return in_quotes(text) + " is not a number";
  if (!std::isfinite(value)) return in_quotes(text) + " is not a finite number";
  return std::nullopt;
}

std::optional<std::string> parse_triple(std::string_view text, vec3& value) {
  std::array<std::string_view, 3> parts;
  size_t n = 0, start = 0;
  for (size_t k = 0; k <= text.size(); ++k) {
    if (k == text.size() || text[k] == ',') {
      if (n == 3) return in_quotes(text) + " has more than 3 components (want x,y,z)";
      parts[n++] = text.substr(start, k - start);
      start = k + 1;
    }
  }
  if (n != 3) return in_quotes(text) + " has " + std::to_string(n) + " component(s), want 3 (x,y,z)";
  for (int k = 0; k < 3; ++k) {
    double d = 0;
    if (auto e = parse_real(parts[k], d)) return "component " + std::to_string(k + 1) + ": " + *e;
    value[k] = d;
  }
  return std::nullopt;
}

std::optional<std::string> parse_aspect(std::string_view text, double& value) {
  const size_t colon = text.find(':');
  if (colon == std::string_view::npos) {
    if (auto e = parse_real(text, value)) return e;
  } else {
    double w = 0, h = 0;
    if (auto e = parse_real(text.substr(0, colon), w)) return e;
    if (auto e = parse_real(text.substr(colon + 1), h)) return e;
    if (!(w > 0 && h > 0)) return in_quotes(text) + ": both sides of W:H must be positive";
    value = w / h;
  }
  if (!(value > 0) || !std::isfinite(value)) return in_quotes(text) + " must be positive and finite";
  return std::nullopt;
}

std::optional<std::string> parse_seed(std::string_view text, uint64_t& value) {
  const std::string t(text);
  if (t.empty() || t.size() > 20 || t.find_first_not_of("0123456789") != std::string::npos)
    return in_quotes(text) + " is not a whole number from 0 to 18446744073709551615";
  errno = 0;
  char* end = nullptr;
  const unsigned long long v = std::strtoull(t.c_str(), &end, 10);
  if (errno == ERANGE || end != t.c_str() + t.size())
    return in_quotes(text) + " is larger than 18446744073709551615";
  value = v;
  return std::nullopt;
}

std::optional<std::string> parse_region(std::string_view text, int64_t width, int64_t height, pixel_region& value) {
  int64_t v[4] = {};
  size_t n = 0, start = 0;
  for (size_t k = 0; k <= text.size(); ++k) {
    if (k == text.size() || text[k] == ',') {
      if (n == 4) return in_quotes(text) + " has more than 4 numbers (want x0,y0,x1,y1)";
      if (auto e = parse_int(text.substr(start, k - start), v[n]))
        return "number " + std::to_string(n + 1) + ": " + *e;
      ++n;
      start = k + 1;
    }
  }
  if (n != 4) return in_quotes(text) + " has " + std::to_string(n) + " number(s), want 4 (x0,y0,x1,y1)";
  if (!(0 <= v[0] && v[0] < v[2] && v[2] <= width))
    return "want 0 <= x0 < x1 <= " + std::to_string(width) + " (the image width), got " + std::string(text);
  if (!(0 <= v[1] && v[1] < v[3] && v[3] <= height))
    return "want 0 <= y0 < y1 <= " + std::to_string(height) + " (the image height), got " + std::string(text);
  value = {v[0], v[1], v[2], v[3]};
  return std::nullopt;
}

parse_result parse_args(int argc, const char* const* argv, std::ostream& out, std::ostream& err) {
  CLI::App app{
      "raycast: renders Ray Tracing in One Weekend's sky and spheres (chapters 4-6), on the\n"
      "fastest vector unit this CPU has.",
      "raycast"};
  app.option_defaults()->multi_option_policy(CLI::MultiOptionPolicy::Throw);

  std::string output, width_s, height_s, aspect_s, vh_s, focal_s, origin_s, bottom_s, top_s, format_s;
  std::string backend_s, precision_s, threads_s, lookfrom_s, lookat_s, vup_s, vfov_s, scene_s;
  std::string samples_s, sampler_s, seed_s, region_s;
  bool quiet = false, version = false, stats = false;

  app.add_option("-o,--output", output, "Output file; '-' writes binary PPM to standard output")
      ->type_name("FILE");
  app.add_option("-w,--width", width_s, "Image width in pixels [400]")->type_name("N");
  app.add_option("--height", height_s, "Image height in pixels [int(width / aspect), at least 1]")
      ->type_name("N");
  app.add_option("--aspect", aspect_s, "Aspect ratio, W:H or a number [16:9]")->type_name("RATIO");
  app.add_option("--viewport-height", vh_s, "Viewport height in world units [2.0]")->type_name("H");
  app.add_option("--focal-length", focal_s, "Distance from the origin to the viewport [1.0]")
      ->type_name("F");
  app.add_option("--origin", origin_s, "Camera position [0,0,0]")->type_name("X,Y,Z");
  app.add_option("--lookfrom", lookfrom_s, "Camera position (the same point as --origin)")
      ->type_name("X,Y,Z");
  app.add_option("--lookat", lookat_s, "Point the camera looks at [straight down -z]")
      ->type_name("X,Y,Z");
  app.add_option("--vup", vup_s, "Which way is up for the camera [0,1,0]")->type_name("X,Y,Z");
  app.add_option("--vfov", vfov_s,
                 "Vertical field of view in degrees, instead of --viewport-height")
      ->type_name("DEGREES");
  app.add_option("--sky-bottom", bottom_s, "Colour looking straight down [1,1,1]")->type_name("R,G,B");
  app.add_option("--sky-top", top_s, "Colour looking straight up [0.5,0.7,1.0]")->type_name("R,G,B");
  app.add_option("--scene", scene_s,
                 "Built-in scene (" + builtin_scene_list() + ") or a .json scene file, whose "
                 "settings the other options override [sky]")
      ->type_name("NAME|FILE");
  app.add_option("--format", format_s, "png|ppm|jpg|tif|exr, overrides the extension")
      ->type_name("FMT");
  app.add_option("--backend", backend_s,
                 "auto|reference|scalar|sse2|avx2|avx512|neon [auto: the best this CPU runs]")
      ->type_name("NAME");
  app.add_option("--precision", precision_s,
                 std::string("exact|fast [") + std::string(to_string(default_precision)) + "]")
      ->type_name("MODE");
  app.add_option("--threads", threads_s, "Render threads [all cores]")->type_name("N");
  app.add_option("--samples", samples_s,
                 "Samples per pixel, averaged (antialiasing); 1 is the pixel's own point [1]")
      ->type_name("N");
  app.add_option("--sampler", sampler_s,
                 std::string("Where a pixel's samples fall: random|stratified|sobol [") +
                     std::string(to_string(default_sampler)) + "]")
      ->type_name("NAME");
  app.add_option("--seed", seed_s, "Seed of the samples' random numbers, 0 to 2^64-1 [0]")->type_name("N");
  app.add_option("--region", region_s,
                 "Render and write only the pixels x0 <= x < x1, y0 <= y < y1 of the image (y0 = 0 is "
                 "the top row), the same bytes as those of the whole image [the whole image]")
      ->type_name("X0,Y0,X1,Y1");
  app.add_flag("-q,--quiet", quiet, "No progress on standard error");
  app.add_flag("--stats", stats,
               "After the run, print on standard error the seconds to load, prepare, render and write, "
               "rays per second, spheres and peak memory");
  app.add_flag("--version", version, "Print the version and the backend auto picks here");

  try {
    // CLI11 2.1 reads "--name=" (nothing after the '=') as "--name" and takes
    // the next argument as its value: "--width= -o a.png" would render at
    // width "-o". Pass it on as "--name" "", an empty value, refused as such.
    std::vector<std::string> split;
    for (int k = 0; k < argc; ++k) {
      const std::string_view a = argv[k];
      if (k > 0 && a.size() > 3 && a.substr(0, 2) == "--" && a.find('=') == a.size() - 1) {
        split.emplace_back(a.substr(0, a.size() - 1));
        split.emplace_back();
      } else {
        split.emplace_back(a);
      }
    }
    std::vector<const char*> split_argv;
    for (const std::string& a : split) split_argv.push_back(a.c_str());
    app.parse(int(split_argv.size()), split_argv.data());
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return {std::nullopt, app.exit(e, out, err)};
    err << "raycast: error: " << printable(e.what()) << " (see --help)\n";
    return {std::nullopt, 2};
  }

  if (version) {
    out << "raycast " << RAYCAST_VERSION << " (auto backend here: " << to_string(best_backend())
        << ")\n";
    return {std::nullopt, 0};
  }

  auto usage = [&](std::string_view option, const std::string& why) {
    err << "raycast: error: " << option << ": " << printable(why) << "\n";
    return parse_result{std::nullopt, 2};
  };
  auto given = [&](std::string_view name) { return app.count(std::string(name)) > 0; };

  job j;
  scene_params sp;
  camera_params& cp = sp.camera;
  // A built-in scene, or a scene file whose settings the options below override.
  std::string scene_file;
  if (given("--scene")) {
    if (auto spheres = builtin_spheres(scene_s)) {
      sp.spheres = std::move(*spheres);
    } else if (scene_s.size() > 5 && lower(scene_s.substr(scene_s.size() - 5)) == ".json") {
      const auto start = std::chrono::steady_clock::now();
      auto parsed = load_scene_file(scene_s);
      j.load_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      if (auto* e = std::get_if<scene_file_error>(&parsed))
        return usage("--scene", scene_s + ": " + (e->path.empty() ? "" : e->path + ": ") + e->message);
      sp = std::move(std::get<scene_params>(parsed));
      scene_file = scene_s;
    } else {
      return usage("--scene", in_quotes(scene_s) + " is not one of " + builtin_scene_list() +
                                  ", or a .json scene file");
    }
  }
  if (given("--width"))
    if (auto e = parse_int(width_s, cp.image_width)) return usage("--width", *e);
  if (given("--aspect"))
    if (auto e = parse_aspect(aspect_s, cp.aspect_ratio)) return usage("--aspect", *e);
  if (given("--height")) {
    int64_t h = 0;
    if (auto e = parse_int(height_s, h)) return usage("--height", *e);
    cp.image_height = h;
  }
  if (given("--viewport-height")) {
    if (auto e = parse_real(vh_s, cp.viewport_height)) return usage("--viewport-height", *e);
    cp.vfov_degrees.reset();  // overrides a scene file's vfov
  }
  if (given("--focal-length"))
    if (auto e = parse_real(focal_s, cp.focal_length)) return usage("--focal-length", *e);
  if (given("--origin") && given("--lookfrom"))
    return usage("--lookfrom", "names the same point as --origin; give one of them");
  if (given("--vfov") && given("--viewport-height"))
    return usage("--vfov", "replaces --viewport-height; give one of them");
  if (given("--origin"))
    if (auto e = parse_triple(origin_s, cp.origin)) return usage("--origin", *e);
  if (given("--lookfrom"))
    if (auto e = parse_triple(lookfrom_s, cp.origin)) return usage("--lookfrom", *e);
  if (given("--lookat")) {
    vec3 at;
    if (auto e = parse_triple(lookat_s, at)) return usage("--lookat", *e);
    cp.lookat = at;
  }
  if (given("--vup")) {
    if (auto e = parse_triple(vup_s, cp.vup)) return usage("--vup", *e);
    if (!given("--lookat") && !cp.lookat) cp.lookat = cp.origin + vec3(0.0, 0.0, -1.0);  // the lesson's view
  }
  if (given("--vfov")) {
    double f = 0;
    if (auto e = parse_real(vfov_s, f)) return usage("--vfov", *e);
    cp.vfov_degrees = f;
  }
  if (given("--sky-bottom"))
    if (auto e = parse_triple(bottom_s, sp.sky.bottom)) return usage("--sky-bottom", *e);
  if (given("--sky-top"))
    if (auto e = parse_triple(top_s, sp.sky.top)) return usage("--sky-top", *e);

  // The ranges are the scene's to check (scene/scene.h), once; here only the
  // field it blames becomes the option that set it.
  if (auto e = validate(sp)) {
    const std::string_view origin_option = given("--lookfrom") ? "--lookfrom" : "--origin";
    const std::string_view option = option_for(e->field, origin_option);
    // A setting the command line did not give came from the scene file.
    if (!scene_file.empty() && (option == "--scene" || !given(option)))
      return usage("--scene", scene_file + ": " + path(*e) + ": " + e->message);
    return usage(option, e->message);
  }

  if (!given("--output")) return usage("--output", "is required (a file name, or - for standard output)");
  if (output.empty()) return usage("--output", "empty file name");
  j.output = output;
  if (given("--format")) {
    auto f = format_from_name(format_s);
    if (!f) return usage("--format", in_quotes(format_s) + " is not one of png, ppm, jpg, tif, exr");
    j.format = *f;
  } else if (output == "-") {
    j.format = file_format::ppm;
  } else {
    if (auto why = io::format_from_path(output, j.format)) return usage("--output", *why);
  }
  if (output == "-" && j.format != file_format::ppm)
    return usage("--format", "standard output takes ppm only, got " + std::string(to_string(j.format)));

  if (given("--backend")) {
    auto b = parse_backend(backend_s);
    if (!b) return usage("--backend", in_quotes(backend_s) + " is not one of auto, reference, scalar, sse2, avx2, avx512, neon");
    if (auto why = backend_unavailable(*b)) return usage("--backend", *why);
    j.render.which = *b;
  }
  if (given("--precision")) {
    auto p = parse_precision(precision_s);
    if (!p) return usage("--precision", in_quotes(precision_s) + " is not one of exact, fast");
    j.render.prec = *p;
  }
  if (given("--threads")) {
    int64_t t = 0;
    if (auto e = parse_int(threads_s, t)) return usage("--threads", *e);
    if (t < 1 || t > 1024) return usage("--threads", "must be between 1 and 1024, got " + threads_s);
    j.render.threads = int(t);
  }
  if (given("--samples")) {
    int64_t n = 0;
    if (auto e = parse_int(samples_s, n)) return usage("--samples", *e);
    if (n < 1 || n > int64_t(max_samples))
      return usage("--samples", "must be between 1 and " + std::to_string(max_samples) + ", got " + samples_s);
    j.render.samples = uint32_t(n);
  }
  if (given("--sampler")) {
    auto k = parse_sampler(sampler_s);
    if (!k) return usage("--sampler", in_quotes(sampler_s) + " is not one of random, stratified, sobol");
    j.render.sampler = *k;
  }
  if (given("--seed"))
    if (auto e = parse_seed(seed_s, j.render.seed)) return usage("--seed", *e);
  j.quiet = quiet;
  j.stats = stats;
  j.sc = make_scene(std::move(sp));  // moves the spheres; the camera parameters (cp) stay
  if (given("--region")) {
    if (auto e = parse_region(region_s, j.sc.cam.image_width, j.sc.cam.image_height, j.region))
      return usage("--region", *e);
  } else {
    j.region = {0, 0, j.sc.cam.image_width, j.sc.cam.image_height};
  }
  if (const int64_t side = io::max_side(j.format); side > 0) {
    const std::string limit = std::string(io::display_name(j.format)) + " supports at most " +
                              std::to_string(side) + " pixels per side, got ";
    // The file holds the region: with --region, its sides are what count.
    if (given("--region")) {
      if (j.region.width() > side || j.region.height() > side)
        return usage("--region", limit + std::to_string(std::max(j.region.width(), j.region.height())));
    } else if (j.sc.cam.image_width > side) {
      return usage("--width", limit + std::to_string(j.sc.cam.image_width));
    } else if (j.sc.cam.image_height > side) {
      return usage(cp.image_height ? "--height" : "--aspect",
                   limit + (cp.image_height ? "" : "a height of ") + std::to_string(j.sc.cam.image_height));
    }
  }
  return {std::move(j), 0};
}

}  // namespace raycast::cli
