#include "options.h"

#include "settings/inputs.h"
#include "scene/builtin.h"
#include "settings/names.h"
#include "formats/json.h"

#include <CLI/CLI.hpp>

#include <algorithm>
#include <chrono>
#include <string>
#include <vector>
#include <ostream>

namespace raycast::cli {

namespace {

using enum setting_id;

// A usage error: the option (or "--scene" for a scene file's key) and why.
struct usage_error {
  std::string option;
  std::string why;
  int exit_code = 2;  // 1: the input could not be read (an I/O failure)
};

// --help's line for a row: the names it takes, the help, the default.
std::string help_of(const setting& row) {
  std::string h;
  for (std::string_view n : row.names) h += (h.empty() ? "" : "|") + std::string(n);
  if (!row.help.empty()) h += (h.empty() ? "" : ": ") + std::string(row.help);
  if (!row.default_text.empty()) h += " [" + std::string(row.default_text) + "]";
  return h;
}

// Every row of the input table as a CLI11 option (or flag) collecting its text.
struct command_line {
  std::vector<std::string> text = std::vector<std::string>(setting_count);
  bool flags[setting_count] = {};
};

void add_options(CLI::App& app, command_line& cl) {
  for (const setting& row : input_table()) {
    const std::string names = (row.short_option.empty() ? "" : std::string(row.short_option) + ",") +
                              std::string(row.option);
    if (row.type == value_type::flag)
      app.add_flag(names, cl.flags[size_t(row.id)], help_of(row));
    else
      app.add_option(names, cl.text[size_t(row.id)], help_of(row))->type_name(std::string(row.type_name));
  }
}

// CLI11 2.1 reads "--name=" (nothing after the '=') as "--name" and takes
// the next argument as its value: "--width= -o a.png" would render at
// width "-o". Pass it on as "--name" "", an empty value, refused as such.
std::vector<std::string> split_empty_equals(int argc, const char* const* argv) {
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
  return split;
}

// The options given, parsed by the table's parsers. The run's ranges are
// checked here; the scene's after merging with a scene file (resolve()).
settings given_settings(const CLI::App& app, const command_line& cl) {
  settings s;
  for (const setting& row : input_table()) {
    const std::string option(row.option);
    if (app.count(option) == 0) continue;
    given g;
    g.source = option;
    if (row.type == value_type::flag) g.v.flag = cl.flags[size_t(row.id)];
    else if (auto e = parse_value(row, cl.text[size_t(row.id)], g)) throw usage_error{option, *e};
    if (size_t(row.id) >= scene_setting_count)
      if (auto e = check_range(row, g)) throw usage_error{option, *e};
    s[row.id] = std::move(g);
  }
  if (auto e = check_groups(input_table(), s)) throw usage_error{e->source, e->message};
  return s;
}

// CLI11's message with each word longer than a token excerpt cut short
// ("The following argument was not expected: --xxxx…").
std::string cut_long_words(std::string_view message) {
  std::string r;
  size_t start = 0;
  while (start <= message.size()) {
    size_t end = message.find(' ', start);
    if (end == std::string_view::npos) end = message.size();
    const std::string word = quote_token(message.substr(start, end - start));  // 'word', cut
    r += word.substr(1, word.size() - 2);
    if (end < message.size()) r += ' ';
    start = end + 1;
  }
  return r;
}

// The first argument the options did not take, in the user's words: an
// option we do not have (with the nearest we do), or a value no option took.
usage_error unexpected(const std::vector<std::string>& extras) {
  const std::string& a = extras.front();
  if (a.size() < 2 || a[0] != '-' || (a[1] >= '0' && a[1] <= '9') || a[1] == '.')
    return {quote_token(a), "not expected (no option takes it: each takes one value; see --help)"};
  const std::string name = a.substr(0, a.find('='));
  std::vector<std::string_view> options;
  for (const setting& row : input_table()) {
    options.push_back(row.option.substr(2));
    if (!row.short_option.empty()) options.push_back(row.short_option.substr(1));
  }
  const std::string_view bare = std::string_view(name).substr(name[1] == '-' ? 2 : 1);
  const std::string_view near = nearest_name(bare, options);
  const std::string shown = quote_token(name).substr(1);  // cut short, unquoted
  const std::string option = shown.substr(0, shown.size() - 1);
  if (near.empty()) return {option, "no such option (see --help)"};
  return {option, "no such option; did you mean " + std::string(near.size() == 1 ? "-" : "--") +
                                 std::string(near) + "?"};
}

// CLI11's one message not in a user's terms, an option given twice
// ("--output: At Most 1 required but received 2"), in ours.
std::string in_our_words(std::string message) {
  static constexpr std::string_view twice = ": At Most 1 required but received ";
  const size_t at = message.find(twice);
  if (at == std::string::npos) return message;
  return message.substr(0, at) + ": given " + message.substr(at + twice.size()) + " times; give it once";
}

// The scene: --scene's spheres and keys, the options merged over the keys,
// then the derived settings and the checks, each error blaming who gave it.
scene_params scene_of(const settings& cli, job& j) {
  scene_file_contents contents;
  std::string file;  // a scene file's name, for errors of its keys
  const particle_settings particles = particles_of(cli, cli.has(scene) ? cli[scene]->v.text : "");
  if (particles.refused) throw usage_error{std::string(particles.refused->option), particles.why};
  if (cli.has(scene)) {
    const auto start = std::chrono::steady_clock::now();
    auto read = read_scene(cli[scene]->v.text, particles.options);
    j.load_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (auto* e = std::get_if<scene_file_error>(&read)) {
      const std::string& name = cli[scene]->v.text;
      const std::string named = is_scene_file_name(name) ? name + ": " : "";
      throw usage_error{"--scene", named + (e->path.empty() ? "" : e->path + ": ") + e->message, e->io ? 1 : 2};
    }
    contents = std::move(std::get<scene_file_contents>(read));
    if (!builtin_spheres(cli[scene]->v.text)) file = cli[scene]->v.text;
  }
  settings merged = contents.keys;
  merge(merged, cli, input_table());
  const auto blame_source = [&](std::string_view source, const std::string& why) {
    if (source.starts_with("--")) return usage_error{std::string(source), why};
    return usage_error{"--scene", file + ": " + std::string(source) + ": " + why};
  };
  scene_params& params = contents.scene;
  if (auto e = resolve(merged, params.camera, params.sky, params.light)) throw blame_source(e->source, e->message);
  // What one value cannot say (lookat = lookfrom, vup along the view, a
  // derived height, spheres far from the camera) is the scene's to check
  // (scene/scene.h), once; here only the field it blames becomes the
  // setting that set it.
  if (auto e = validate(params)) {
    const blamed b = blame(*e, merged, !file.empty());
    if (b.from_file) throw usage_error{"--scene", file + ": " + path(*e) + ": " + e->message};
    throw usage_error{std::string(input_row(b.id).option), e->message};
  }
  return std::move(params);
}

// The output file and its format.
void output_of(const settings& cli, job& j) {
  if (!cli.has(output)) throw usage_error{"--output", "is required (a file name, or - for standard output)"};
  j.output = cli[output]->v.text;
  if (j.output.empty()) throw usage_error{"--output", "empty file name"};
  if (cli.has(format)) {
    j.format = io::format_names[cli[format]->v.name].format;
  } else if (auto why = io::format_from_path(j.output, j.format)) {
    throw usage_error{"--output", *why};
  }
  if (j.output == "-")
    if (auto why = io::stdout_format_error(j.format)) throw usage_error{"--format", *why};
}

std::string_view name_of(const settings& cli, setting_id id) { return input_row(id).names[cli[id]->v.name]; }

void render_options_of(const settings& cli, job& j) {
  if (cli.has(setting_id::backend)) {
    const auto b = *parse_backend(name_of(cli, setting_id::backend));
    if (auto why = backend_unavailable(b)) throw usage_error{"--backend", *why};
    j.render.which = b;
  }
  if (cli.has(setting_id::precision)) j.render.prec = *parse_precision(name_of(cli, setting_id::precision));
  if (cli.has(threads)) j.render.threads = int(cli[threads]->v.integer);
  if (cli.has(samples)) j.render.samples = uint32_t(cli[samples]->v.integer);
  if (cli.has(sampler)) j.render.sampler = *parse_sampler(name_of(cli, sampler));
  if (cli.has(seed)) j.render.seed = cli[seed]->v.seed;
  j.quiet = cli.has(quiet);
  j.stats = cli.has(stats);
}

// --region within the image, and the sides the format can hold.
void region_of(const settings& cli, const camera_params& cp, job& j) {
  const int64_t w = j.sc.cam.image_width, h = j.sc.cam.image_height;
  j.region = {0, 0, w, h};
  if (cli.has(region)) {
    const auto& r = cli[region]->v.region;
    if (auto why = check_region(r, w, h, cli[region]->tokens[0])) throw usage_error{"--region", *why};
    j.region = {r[0], r[1], r[2], r[3]};
  }
  const int64_t side = io::max_side(j.format);
  if (side <= 0) return;
  const std::string limit = std::string(io::display_name(j.format)) + " supports at most " + std::to_string(side) +
                            " pixels per side, got ";
  // The file holds the region: with --region, its sides are what count.
  if (cli.has(region)) {
    if (j.region.width() > side || j.region.height() > side)
      throw usage_error{"--region", limit + std::to_string(std::max(j.region.width(), j.region.height()))};
  } else if (w > side) {
    throw usage_error{"--width", limit + std::to_string(w)};
  } else if (h > side) {
    throw usage_error{cp.image_height ? "--height" : "--aspect",
                      limit + (cp.image_height ? "" : "a height of ") + std::to_string(h)};
  }
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

parse_result parse_args(int argc, const char* const* argv, std::ostream& out, std::ostream& err) {
  CLI::App app{
      "raycast: renders Ray Tracing in One Weekend's sky and spheres (chapters 4-7), on the\n"
      "fastest vector unit this CPU has.",
      "raycast"};
  app.option_defaults()->multi_option_policy(CLI::MultiOptionPolicy::Throw);
  app.allow_extras();  // reported here, first one first, with a suggestion
  command_line cl;
  add_options(app, cl);
  try {
    const std::vector<std::string> split = split_empty_equals(argc, argv);
    std::vector<const char*> split_argv;
    for (const std::string& a : split) split_argv.push_back(a.c_str());
    app.parse(int(split_argv.size()), split_argv.data());
    if (!app.remaining().empty()) throw unexpected(app.remaining());
  } catch (const usage_error& e) {
    err << "raycast: error: " << printable(e.option) << ": " << printable(e.why) << "\n";
    return {std::nullopt, 2};
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return {std::nullopt, app.exit(e, out, err)};
    err << "raycast: error: " << printable(cut_long_words(in_our_words(e.what()))) << " (see --help)\n";
    return {std::nullopt, 2};
  }
  if (cl.flags[size_t(version)]) {
    out << "raycast " << RAYCAST_VERSION << " (auto backend here: " << to_string(best_backend()) << ")\n";
    return {std::nullopt, 0};
  }
  try {
    const settings cli = given_settings(app, cl);
    job j;
    scene_params params = scene_of(cli, j);
    output_of(cli, j);
    render_options_of(cli, j);
    const camera_params cp = params.camera;
    j.sc = make_scene(std::move(params));  // moves the spheres
    region_of(cli, cp, j);
    return {std::move(j), 0};
  } catch (const usage_error& e) {
    err << "raycast: error: " << printable(e.option) << ": " << printable(e.why) << "\n";
    return {std::nullopt, e.exit_code};
  }
}

}  // namespace raycast::cli
