#include "options.h"

#include "library/pipeline.h"
#include "library/source.h"
#include "render/backend.h"
#include "scene/camera.h"
#include "text/names.h"
#include "text/quote.h"

#include <CLI/CLI.hpp>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cstdio>
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

// Whether name holds one frame-number conversion (%d, %05d; %% is a
// percent sign), or why it holds a broken one.
bool frame_pattern(const std::string& name) {
  int conversions = 0;
  for (size_t k = 0; k < name.size(); ++k) {
    if (name[k] != '%') continue;
    if (k + 1 < name.size() && name[k + 1] == '%') {
      ++k;
      continue;
    }
    size_t e = k + 1;
    while (e < name.size() && std::isdigit(static_cast<unsigned char>(name[e]))) ++e;
    if (e >= name.size() || name[e] != 'd' || e - k > 4)
      throw usage_error{"--output", quote_token(name) + ": a frame's number is written %d or %05d (and % itself %%)"};
    ++conversions;
    k = e;
  }
  if (conversions > 1) throw usage_error{"--output", quote_token(name) + " has more than one %d"};
  return conversions == 1;
}

// The frames to render: --frames of a trajectory (all of them without it).
std::vector<size_t> frames_of(const settings& cli, scene_source& src) {
  std::vector<size_t> frames;
  if (!src.trajectory()) {
    if (cli.has(setting_id::frames))
      throw usage_error{"--frames", "applies to a trajectory (a particle file's frames); this scene is one picture"};
    return {0};
  }
  if (!cli.has(setting_id::frames)) {  // every frame, read as they come: here the first two, to know if one is all
    for (size_t k = 0; k < 2 && src.has_frame(k); ++k) frames.push_back(k);
    if (frames.empty()) throw usage_error{"--scene", "the file holds no frame"};
    return frames;
  }
  const size_t n = src.frame_count();
  if (auto e = select_frames(cli[setting_id::frames]->v, n, frames)) throw usage_error{"--frames", *e};
  if (frames.empty()) throw usage_error{"--frames", "selects none of the file's " + std::to_string(n) + " frames"};
  return frames;
}

// Where the frames go: one image, an image a frame (a pattern), or a movie.
void output_of(const settings& cli, const run_settings& run, job& j) {
  j.output = run.output;
  j.movie = io::movie_kind_of(run.output);
  j.pattern = frame_pattern(run.output);
  if (j.movie) {
    if (auto why = io::movie_unavailable()) throw usage_error{"--output", *why};
    if (j.pattern) throw usage_error{"--output", "a movie holds every frame: no %d in its name"};
  } else {
    j.format = output_format(run.output, run.options.format, front_end::command_line);
  }
  if (cli.has(fps)) j.fps = int(cli[fps]->v.integer);
  if (j.frames.size() > 1 && !j.pattern && !j.movie)
    throw usage_error{"--output", (j.every_frame ? std::string("the file's frames") : std::to_string(j.frames.size()) +
                                                                                      " frames") +
                                      " to one file: give a pattern such as f_%05d.png (the frame's index in the "
                                      "file), a movie (.mp4, .webm, .gif), or --frames K"};
  if (j.pattern && j.output == "-") throw usage_error{"--output", "standard output takes one image, not a pattern"};
}

// The run: --scene opened, the frames chosen, the first described (the
// options merged over its keys or framing), the output's format and names,
// and the region within the image.
job job_of(const settings& cli) {
  run_settings run;
  if (auto e = resolve_run(cli, run)) throw usage_error{e->source, e->message};
  if (!cli.has(output)) throw usage_error{"--output", "is required (a file name, or - for standard output)"};
  job j;
  j.source = std::make_shared<scene_source>(run.scene, cli, front_end::command_line);
  j.frames = frames_of(cli, *j.source);
  j.every_frame = j.source->trajectory() && !cli.has(setting_id::frames);
  output_of(cli, run, j);
  j.first = j.source->frame(j.frames[0]);
  const camera cam = make_camera(j.first.scene.cam);
  j.region = output_region(run.options, cam.image_width, cam.image_height, front_end::command_line);
  if (!j.movie)
    check_sides(j.format, j.region, {cli.has(region), j.first.scene.cam.height.has_value()}, front_end::command_line);
  j.options = std::move(run.options);
  j.options.format = j.movie ? "ppm" : std::string(io::to_string(j.format));
  j.quiet = run.quiet;
  j.stats = run.stats;
  j.skip_existing = cli.has(skip_existing);
  return j;
}

}  // namespace

std::string refusal_text(const refusal& r, int& exit_code) {
  const usage_error e = in_cli_words(r);
  exit_code = e.exit_code;
  return e.option + ": " + e.why;
}

std::string output_name(const job& j, size_t k) {
  if (!j.pattern) return j.output;
  std::string name;
  for (size_t i = 0; i < j.output.size(); ++i) {
    if (j.output[i] != '%') {
      name += j.output[i];
    } else if (j.output[i + 1] == '%') {
      name += '%';
      ++i;
    } else {
      size_t e = i + 1;
      while (j.output[e] != 'd') ++e;
      char buf[40];
      std::snprintf(buf, sizeof buf, ("%" + j.output.substr(i + 1, e - i - 1) + "zu").c_str(), k);
      name += buf;
      i = e;
    }
  }
  return name;
}

std::string printable(std::string_view s) { return control_escaped(s); }

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
