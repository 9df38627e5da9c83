#include "options.h"

#include "library/pipeline.h"
#include "library/source.h"
#include "render/backend.h"
#include "scene/camera.h"
#include "text/names.h"

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
    else if (auto e = parse_value(row, cl.text[size_t(row.id)], g.v, g.tokens)) throw usage_error{option, *e};
    if (!is_scene_row(row))
      if (auto e = check_range(row, g.v, g.tokens)) throw usage_error{option, *e};
    s[row.id] = std::move(g);
  }
  if (auto e = check_groups(s)) throw usage_error{e->source, e->message};
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

// A refusal of the pipeline in the command line's words: an option's own
// ("--width: ..."), or a scene file's ("--scene: FILE: camera.vfov: ...").
usage_error in_cli_words(const refusal& r) {
  const int code = r.kind == error_kind::io ? 1 : 2;
  if (r.source.starts_with("--")) return {r.source, r.why, code};
  std::string why = r.file.empty() ? "" : r.file + ": ";
  if (!r.source.empty()) why += r.source + ": ";
  return {"--scene", why + r.why, code};
}

// The run: the scene described (--scene's file read, the options merged over
// its keys), the output's format, and the region within the image.
job job_of(const settings& cli) {
  run_settings run;
  if (auto e = resolve_run(cli, run)) throw usage_error{e->source, e->message};
  if (!cli.has(output)) throw usage_error{"--output", "is required (a file name, or - for standard output)"};
  job j;
  described_scene d = describe(run.scene, cli, front_end::command_line);
  j.format = output_format(run.output, run.options.format, front_end::command_line);
  const camera cam = make_camera(d.scene.cam);
  j.region = output_region(run.options, cam.image_width, cam.image_height, front_end::command_line);
  check_sides(j.format, j.region, {cli.has(region), d.scene.cam.height.has_value()}, front_end::command_line);
  j.description = std::move(d.scene);
  j.options = std::move(run.options);
  j.options.format = std::string(io::to_string(j.format));
  j.output = std::move(run.output);
  j.quiet = run.quiet;
  j.stats = run.stats;
  j.load_seconds = d.load_seconds;
  return j;
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
    return {job_of(given_settings(app, cl)), 0};
  } catch (const refusal& r) {
    const usage_error e = in_cli_words(r);
    err << "raycast: error: " << printable(e.option) << ": " << printable(e.why) << "\n";
    return {std::nullopt, e.exit_code};
  } catch (const usage_error& e) {
    err << "raycast: error: " << printable(e.option) << ": " << printable(e.why) << "\n";
    return {std::nullopt, e.exit_code};
  }
}

}  // namespace raycast::cli
