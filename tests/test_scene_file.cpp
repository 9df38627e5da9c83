// Scene files (--scene FILE.json, formats/json.h): every key, the
// defaults, errors naming the JSON path, and a file of 100,000 spheres.
#include <fcntl.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>
#include <variant>

#include "render_support.h"
#include "formats/json.h"

namespace {

using namespace raycast;

api::scene parsed(const std::string& text) {
  auto r = parse_scene_file(text);
  if (auto* e = std::get_if<scene_file_error>(&r)) {
    ADD_FAILURE() << e->path << ": " << e->message;
    return {};
  }
  return std::get<api::scene>(r);
}

scene_file_error error_of(const std::variant<api::scene, scene_file_error>& r) {
  if (auto* e = std::get_if<scene_file_error>(&r)) return *e;
  ADD_FAILURE() << "no error";
  return {};
}

std::string error_path(const std::string& text) {
  auto r = parse_scene_file(text);
  if (auto* e = std::get_if<scene_file_error>(&r)) return e->path.empty() ? "(file)" : e->path;
  // Camera and sky rules are checked after overrides, by validate().
  if (auto e = validate(std::get<api::scene>(r))) return path(*e);
  return "(none)";
}

TEST(SceneFile, EveryKey) {
  const api::scene p = parsed(R"({
    "camera": {"width": 320, "height": 200, "aspect": "16:10", "lookfrom": [-2, 2, 1],
               "lookat": [0, 0, -1], "vup": [0, 1, 0.5], "vfov": 40, "focal_length": 2},
    "sky": {"bottom": [1, 0.9, 0.8], "top": [0.1, 0.2, 0.3]},
    "spheres": [{"center": [0, 0, -1], "radius": 0.5},
                {"center": [1, 2, 3], "radius": 4, "shade": "flat", "color": [0.25, 0.5, 1]},
                {"center": [0, -100.5, -1], "radius": 100, "shade": "normal"}]})");
  EXPECT_EQ(p.cam.width, 320);
  EXPECT_EQ(p.cam.height, 200);
  EXPECT_DOUBLE_EQ(p.cam.aspect, 1.6);
  EXPECT_EQ(p.cam.lookfrom, vec3(-2, 2, 1));
  EXPECT_EQ(p.cam.lookat, vec3(0, 0, -1));
  EXPECT_EQ(p.cam.vup, vec3(0, 1, 0.5));
  EXPECT_EQ(p.cam.vfov, 40.0);
  EXPECT_EQ(p.cam.focal_length, 2.0);
  EXPECT_EQ(p.sky.bottom, color(1, 0.9, 0.8));
  EXPECT_EQ(p.sky.top, color(0.1, 0.2, 0.3));
  ASSERT_EQ(p.spheres.size(), 3u);
  EXPECT_EQ(p.spheres[0].shade, shading::normal);
  EXPECT_EQ(p.spheres[1].shade, shading::flat);
  EXPECT_EQ(p.spheres[1].color, color(0.25, 0.5, 1));
  EXPECT_EQ(p.spheres[1].center, vec3(1, 2, 3));
  EXPECT_EQ(p.spheres[1].radius, 4.0);
  EXPECT_EQ(p.spheres[2].shade, shading::normal);
  EXPECT_FALSE(validate(p));
}

// The shade names are read in place where written plainly, and by
// unescaping otherwise: both give the same shading, and a name that only
// starts like one is refused.
TEST(SceneFile, ShadeNamesPlainOrEscaped) {
  const api::scene p = parsed(R"({"spheres": [
      {"center": [0, 0, -1], "radius": 0.5, "shade": "lit", "color": [1, 0, 0]},
      {"center": [0, 0, -1], "radius": 0.5, "shade": "\u006cit", "color": [1, 0, 0]},
      {"center": [0, 0, -1], "radius": 0.5, "shade": "fl\u0061t", "color": [1, 0, 0]},
      {"center": [0, 0, -1], "radius": 0.5, "shade": "flat" , "color": [1, 0, 0]},
      {"center": [0, 0, -1], "radius": 0.5, "shade": "norma\u006c"}]})");
  ASSERT_EQ(p.spheres.size(), 5u);
  EXPECT_EQ(p.spheres[0].shade, shading::lit);
  EXPECT_EQ(p.spheres[1].shade, shading::lit);
  EXPECT_EQ(p.spheres[2].shade, shading::flat);
  EXPECT_EQ(p.spheres[3].shade, shading::flat);
  EXPECT_EQ(p.spheres[4].shade, shading::normal);
  for (const char* bad : {"\"normalx\"", "\"Lit\"", "\"lit \"", "\"flat\\\"\"", "\"\"", "1"})
    EXPECT_EQ(error_path(std::string(R"({"spheres": [{"center": [0,0,-1], "radius": 1, "color": [1,0,0], "shade": )") +
                         bad + "}]}"),
              "spheres[0].shade")
        << bad;
}

// The aspect is read by the command line's parser: a number, or a string
// holding W:H or a number.
TEST(SceneFile, AnAspectIsANumberOrAStringTheCommandLineTakes) {
  for (const char* aspect : {"1.6", "\"1.6\"", "\"16:10\"", "\"8:5\"", "\"1.6e0\""})
    EXPECT_DOUBLE_EQ(parsed(std::string(R"({"camera": {"aspect": )") + aspect + "}}").cam.aspect, 1.6)
        << aspect;
  for (const char* aspect : {"\"16:0\"", "\"wide\"", "\" 16:9\"", "\"-16:9\"", "true", "-1", "0"})
    EXPECT_EQ(error_path(std::string(R"({"camera": {"aspect": )") + aspect + "}}"), "camera.aspect") << aspect;
  // A number is JSON's, then the command line's: no leading zeros, no bare point.
  for (const char* n : {"01", "1.", "-01.5"})
    EXPECT_EQ(error_path(std::string(R"({"camera": {"vfov": )") + n + "}}"), "camera.vfov") << n;
}

// The table's defaults, as --help shows them, are the camera's and sky's.
TEST(SceneFile, TheInputTablesDefaultsAreTheScenes) {
  const api::scene lesson;
  settings s;
  for (const setting& row : input_table()) {
    if (!is_scene_row(row)) continue;
    // Defaults that are no value: a derived height, no lookat, no directional
    // light, no shadows, unbounded ambient occlusion.
    if (row.default_text.empty() || row.id == setting_id::height || row.id == setting_id::lookat ||
        row.id == setting_id::light || row.id == setting_id::shadows || row.id == setting_id::ao_distance)
      continue;
    given g;
    ASSERT_FALSE(parse_value(row, row.default_text, g.v, g.tokens)) << row.option;
    s[row.id] = g;
  }
  api::scene d;
  ASSERT_FALSE(resolve_scene(s, d));
  const api::camera& cp = d.cam;
  const api::sky& sk = d.sky;
  const api::light& li = d.light;
  EXPECT_FALSE(li.any());
  EXPECT_EQ(cp.width, lesson.cam.width);
  EXPECT_EQ(cp.aspect, lesson.cam.aspect);
  EXPECT_EQ(cp.viewport_height, lesson.cam.viewport_height);
  EXPECT_EQ(cp.focal_length, lesson.cam.focal_length);
  EXPECT_EQ(cp.lookfrom, lesson.cam.lookfrom);
  EXPECT_EQ(sk.bottom, lesson.sky.bottom);
  EXPECT_EQ(sk.top, lesson.sky.top);
  for (const setting& row : input_table()) {
    if (!row.file_key.empty()) {
      EXPECT_EQ(find_file_key(row.file_key), &row);
    }
  }
}

TEST(SceneFile, EmptyObjectIsTheLesson) {
  const api::scene p = parsed("{}");
  const api::scene lesson;
  EXPECT_EQ(p.cam.width, lesson.cam.width);
  EXPECT_FALSE(p.cam.lookat);
  EXPECT_TRUE(p.spheres.empty());
  EXPECT_EQ(p.sky.top, lesson.sky.top);
}

TEST(SceneFile, ErrorsNameTheJsonPath) {
  const std::pair<const char*, const char*> cases[] = {
      {R"({"spheres": [{"center": [0,0,-1], "radius": 1}, {"center": [0,0,-1], "radius": 1},
                       {"center": [0,0,-1], "radius": 1}, {"center": [0,0,-1], "radius": 0}]})",
       "spheres[3].radius"},
      {R"({"spheres": [{"center": [0,0,-1], "radius": -2}]})", "spheres[0].radius"},
      {R"({"spheres": [{"center": [0,0,-1], "radius": "1"}]})", "spheres[0].radius"},
      {R"({"spheres": [{"center": [0,0], "radius": 1}]})", "spheres[0].center"},
      {R"({"spheres": [{"center": [0,"a",0], "radius": 1}]})", "spheres[0].center[1]"},
      {R"({"spheres": [{"radius": 1}]})", "spheres[0].center"},
      {R"({"spheres": [{"center": [0,0,-1]}]})", "spheres[0].radius"},
      {R"({"spheres": [{"center": [0,0,-1], "radius": 1, "shade": "flat"}]})", "spheres[0].color"},
      {R"({"spheres": [{"center": [0,0,-1], "radius": 1, "shade": "glossy"}]})", "spheres[0].shade"},
      {R"({"spheres": [{"center": [0,0,-1], "radius": 1, "colour": [1,0,0]}]})", "spheres[0].colour"},
      {R"({"spheres": {"center": [0,0,-1]}})", "spheres"},
      {R"({"spheres": [[0,0,-1]]})", "spheres[0]"},
      {R"({"camera": {"width": 400.5}})", "camera.width"},
      {R"({"camera": {"width": 0}})", "camera.width"},
      {R"({"camera": {"vfov": 180}})", "camera.vfov"},
      {R"({"camera": {"vfov": 40, "viewport_height": 2}})", "camera.viewport_height"},
      {R"({"camera": {"aspect": "16:0"}})", "camera.aspect"},
      {R"({"camera": {"lookat": [0,0,0]}})", "camera.lookat"},
      {R"({"camera": {"fov": 40}})", "camera.fov"},
      {R"({"sky": {"top": [1,1,1e31]}})", "sky.top"},
      {R"({"sky": {"middle": [1,1,1]}})", "sky.middle"},
      {R"({"lights": []})", "lights"},
      {R"([1, 2, 3])", "(file)"},
      {R"({"camera": {"width": 400,}})", "(file)"},
      {R"({"spheres": [{"center": [0,0,1e999], "radius": 1}]})", "spheres[0].center[2]"},
      {R"({"spheres": [{"center": [0,0,NaN], "radius": 1}]})", "(file)"},
  };
  for (const auto& [text, want] : cases) EXPECT_EQ(error_path(text), want) << text;
}

TEST(SceneFile, DuplicateKeysAreErrors) {
  EXPECT_EQ(error_path(R"({"camera": {"width": 400, "width": 200}})"), "camera.width");
  EXPECT_EQ(error_of(parse_scene_file(R"({"camera": {"width": 400, "width": 200}})")).message.rfind("duplicate key", 0),
            0u);
  EXPECT_EQ(error_path(R"({"spheres": [{"center": [0,0,-1], "radius": 1, "radius": 2}]})"), "spheres[0].radius");
  EXPECT_EQ(error_path(R"({"sky": {}, "sky": {}})"), "sky");
  // An escaped spelling is the same key.
  EXPECT_EQ(error_path(R"({"camera": {"width": 400, "w\u0069dth": 200}})"), "camera.width");
}

// Errors say where: line and column of the offending token, quoted shortly.
TEST(SceneFile, ErrorsSayWhereWithAShortQuote) {
  const scene_file_error e = error_of(parse_scene_file("{\"spheres\": [\n  {\"center\": [0, 0, -1], \"radius\": 1},\n"
                                                        "  {\"center\": [0, 0, -1], \"radius\": -0.5}]}"));
  EXPECT_EQ(e.path, "spheres[1].radius");
  EXPECT_NE(e.message.find("line 3, column 36: -0.5)"), std::string::npos) << e.message;
  const scene_file_error syntax = error_of(parse_scene_file("{\"camera\": {\"width\": 400,}}"));
  EXPECT_EQ(syntax.path, "");
  EXPECT_NE(syntax.message.find("a comma with no key after it (at line 1, column 25: ,}})"), std::string::npos)
      << syntax.message;
}

// Syntax errors are reported where the text breaks JSON's grammar, in plain
// terms, not where simdjson's iterator got to (a comma too many or too few in
// the spheres array was once reported at the file's last line as "more after
// the scene's object"). Texts of spheres one a line: "{"spheres": [" on line
// 1, sphere k on line k + 2, then the close padded with spaces to `bytes`, so
// that a text falls on either side of windowed_from.
enum class defect { doubled_comma, trailing_comma, missing_comma };

std::string sphere_line(int k) {
  return "  {\"center\": [" + std::to_string(k % 100) + ", " + std::to_string(k / 100) + ", -3], \"radius\": 0.25}";
}

std::string spheres_text(int n, int bad, defect d, size_t bytes) {
  std::string text = "{\"spheres\": [\n";
  for (int k = 0; k < n; ++k) {
    text += sphere_line(k);
    if (k == bad && d == defect::doubled_comma) text += ",";
    if (k < n - 1 ? !(k == bad && d == defect::missing_comma) : d == defect::trailing_comma) text += ",";
    text += "\n";
  }
  const std::string close = "]}\n";
  if (text.size() + close.size() < bytes) text += std::string(bytes - text.size() - close.size(), ' ');
  return text + close;
}

// As many spheres as such a text of `bytes` bytes holds.
int spheres_in(size_t bytes) {
  size_t size = std::string("{\"spheres\": [\n]}\n,").size();
  int n = 0;
  while ((size += sphere_line(n).size() + 2) <= bytes) ++n;
  return n;
}

// Each defect after sphere `bad` of n (the trailing comma after the last), in
// texts of `bytes` bytes, read from a string and from a file: the message,
// with the line and column of the comma too many, or of the sphere after the
// one missing.
void expect_syntax_errors_placed(int n, int bad, size_t bytes, const std::string& file) {
  for (const defect d : {defect::doubled_comma, defect::trailing_comma, defect::missing_comma}) {
    const int at = d == defect::trailing_comma ? n - 1 : bad;
    const std::string text = spheres_text(n, at, d, bytes);
    ASSERT_TRUE(bytes == 0 || text.size() == bytes) << text.size();
    const std::string place =
        d == defect::missing_comma
            ? std::to_string(at + 3) + ", column 3: " + sphere_line(at + 1).substr(2, 12)
            : std::to_string(at + 2) + ", column " + std::to_string(sphere_line(at).size() + 1) + ": " +
                  (d == defect::doubled_comma ? ",,)" : ",)");
    const std::string want = std::string("not valid JSON: ") +
                             (d == defect::missing_comma ? "a comma is missing before this value"
                                                         : "a comma with no value after it") +
                             " (at line " + place;
    SCOPED_TRACE(want);
    const scene_file_error e = error_of(parse_scene_file(text));
    EXPECT_EQ(e.path, "");
    EXPECT_EQ(e.message.rfind(want, 0), 0u) << e.message;
    if (text.size() >= windowed_from) {
      EXPECT_FALSE(read_scene_windows(text, 4096).has_value());
    }
    std::ofstream(file, std::ios::binary) << text;
    EXPECT_EQ(error_of(load_scene_file(file)).message, e.message);
  }
}

// A file of tens of megabytes hands its text back as the spheres fill
// memory: every sphere still arrives, and an error past the released text
// still says its line and column (counted before the text went).
// Over windowed_from bytes: parsed a window at a time, and parsed whole for
// its errors (read_scene_text).
TEST(SceneFile, ErrorsFarIntoABigFileSayTheirLine) {
  std::string text = "{\"spheres\": [\n";
  constexpr int n = 300000;
  for (int k = 0; k < n; ++k)
    text += "  {\"center\": [" + std::to_string(k % 1000) + ", " + std::to_string(k / 1000) + ", -3], \"radius\": 0.25},\n";
  const std::string good = text.substr(0, text.size() - 2) + "\n],\n\"camera\": {\"width\": 40}}";
  ASSERT_GE(good.size(), windowed_from);
  const api::scene p = parsed(good);
  ASSERT_EQ(p.spheres.size(), size_t(n));
  EXPECT_EQ(p.spheres.back().center, point3(999, (n - 1) / 1000, -3));
  EXPECT_EQ(p.cam.width, 40);
  // Line 1 is "{"spheres": [", sphere k is on line k + 2; the camera after them.
  std::string late_text = good.substr(0, good.size() - 4);
  late_text += "4.5}}";
  const scene_file_error late = error_of(parse_scene_file(late_text));
  EXPECT_EQ(late.path, "camera.width");
  EXPECT_NE(late.message.find("line " + std::to_string(n + 3) + ", column 21: 4.5)"), std::string::npos) << late.message;
  text += "  {\"center\": [0, 0, -3], \"radius\": -1}]}";
  const scene_file_error last = error_of(parse_scene_file(text));
  EXPECT_EQ(last.path, "spheres[" + std::to_string(n) + "].radius");
  EXPECT_NE(last.message.find("line " + std::to_string(n + 2) + ", column 36: -1)"), std::string::npos)
      << last.message;
}

// The windowed reader of large texts (read_scene_windows) against the whole
// parse, for window sizes from one byte (every sphere larger than its first
// window) to the whole text: the same spheres, and the same keys down to the
// places their errors would quote ("at line L, column C"), before and after
// the array, on its last line or below it.
bool same_contents(const scene_file_contents& a, const scene_file_contents& b) {
  if (a.scene.spheres.size() != b.scene.spheres.size()) return false;
  for (size_t k = 0; k < a.scene.spheres.size(); ++k) {
    const sphere &x = a.scene.spheres[k], &y = b.scene.spheres[k];
    if (x.center != y.center || x.radius != y.radius || x.shade != y.shade || x.color != y.color) return false;
  }
  for (size_t id = 0; id < a.keys.at.size(); ++id) {
    const auto &x = a.keys.at[id], &y = b.keys.at[id];
    if (x.has_value() != y.has_value()) return false;
    if (x && (x->source != y->source || x->where != y->where || x->tokens != y->tokens)) return false;
  }
  return true;
}

constexpr size_t window_sizes[] = {1, 2, 3, 7, 16, 50, 64, 100, 333, 4096};

TEST(SceneFile, WindowsGiveTheWholeParsesResult) {
  std::string cloud = "{\"camera\": {\"width\": 64, \"height\": 36, \"vfov\": 50},\n \"spheres\": [\n";
  for (int k = 0; k < 40; ++k)
    cloud += std::string(k ? ",\n" : "") + "  {\"center\": [" + std::to_string(k * 0.1 - 2) + ", 0.5, -3], \"radius\": 0.05}";
  cloud += "\n]}";
  const std::string texts[] = {
      cloud,
      // One line; the camera after the array, its places after it on the same line.
      R"({"spheres":[{"center":[0,0,-1],"radius":0.5},{"radius":2,"center":[1,2,-3]}],"camera":{"width":80,"vfov":30}})",
      // The camera on the array's last line and below it.
      "{\"spheres\": [{\"center\": [0, 0, -1], \"radius\": 0.5},\r\n\t{\"center\": [0, 1, -1], \"radius\": 0.25}"
      "  ] , \"camera\": {\"width\": 80,\n \"aspect\": \"4:3\"}, \"sky\": {\"top\": [0.1, 0.2, 0.3]}}",
      // Colours, escapes, strings with brackets and braces in them.
      R"({"sky": {"bottom": [1, 1, 1]}, "spheres": [ {"shade": "flat", "color": [1, 0.5, 0], "cent\u0065r": [0, 0, -2],)"
      R"( "radius": 1e-1}, {"center": [0.5, 0, -2], "radius": 0.125, "shade": "lit", "color": [0, 0, 1]} ],)"
      R"( "camera": {"aspect": "16:9"}})",
      R"({"spheres": []})",
      "{\"spheres\":[ \n ], \"camera\": {\"width\": 8}}",
  };
  for (const std::string& text : texts) {
    SCOPED_TRACE(text.substr(0, 120));
    const auto whole = read_scene_text(text);
    ASSERT_TRUE(std::holds_alternative<scene_file_contents>(whole)) << std::get<scene_file_error>(whole).message;
    for (size_t w : window_sizes) {
      const std::optional<scene_file_contents> got = read_scene_windows(text, w);
      ASSERT_TRUE(got.has_value()) << "window " << w << " gave up";
      EXPECT_TRUE(same_contents(*got, std::get<scene_file_contents>(whole))) << "window " << w;
    }
  }
}

// Every error, in the array or out of it, makes the windows give up: the
// whole parse then reports it with its place.
TEST(SceneFile, WindowsGiveUpOnEveryError) {
  const std::string ball = R"({"center": [0, 0, -1], "radius": 0.5})";
  const std::string bad[] = {
      R"({"spheres": [)" + ball + "," + ball + R"(, {"center": [0, 0, -1], "radius": -1}, )" + ball + "]}",
      R"({"spheres": [)" + ball + " " + ball + "]}",          // no comma
      R"({"spheres": [)" + ball + ",," + ball + "]}",         // two
      R"({"spheres": [)" + ball + "," + ball + ",]}",         // a trailing comma
      R"({"spheres": [)" + ball + "," + ball,                 // never closed
      R"({"spheres": [)" + ball + "]",                        // nor the root
      R"({"spheres": [)" + ball + R"(], "spheres": [)" + ball + "]}",
      R"({"spheres": [)" + ball + R"(], "camera": {"width": "wide"}})",
      R"({"spheres": [)" + ball + R"(], "camera": {"width": 4}} [])",
      R"({"spheres": [{"center": [0, 0, -1], "radius": 0.5, "mass": 1}]})",
      R"({"spheres": [{"center": {"x": 0}, "radius": 0.5}]})",
      R"({"spheres": [)" + ball + R"(, [1, 2]]})",
      R"({"spheres": [)" + ball + R"(, {"center": [0, 0, -1], "radius": 0.5, "shade": "glossy"}]})",
      "{\"spheres\": [{\"center\": [0, 0, -1], \"radius\": 0.5, \"shade\": \"\xff\"}]}",
  };
  for (const std::string& text : bad) {
    SCOPED_TRACE(text);
    EXPECT_TRUE(std::holds_alternative<scene_file_error>(read_scene_text(text)));
    for (size_t w : window_sizes) EXPECT_FALSE(read_scene_windows(text, w).has_value()) << "window " << w;
  }
}

// Numbers and nesting far beyond any scene: refused quickly, with a quote of
// 32 bytes and "…", never the whole token.
TEST(SceneFile, HugeTokensAndDeepNestingGiveShortErrors) {
  const std::string digits(1000000, '7');
  const std::string cases[] = {
      R"({"spheres": [{"center": [0, 0, )" + digits + R"(], "radius": 1}]})",
      R"({"spheres": [{"center": [0, 0, -1], "radius": 1e999}]})",
      R"({"camera": {"width": )" + digits + "}}",
      R"({"camera": {"height": 18446744073709551616}})",
      R"({"camera": {"width": -9223372036854775809}})",
      R"({"camera": {"lookfrom": )" + std::string(100000, '[') + std::string(100000, ']') + "}}",
      R"({"spheres": )" + std::string(100000, '[') + std::string(100000, ']') + "}",
      "{\"" + std::string(100000, 'k') + "\": 1}",
      R"({"spheres": [{"center": [0, 0, -1], "radius": 1, "shade": ")" + std::string(100000, 'x') + R"("}]})",
  };
  const char* paths[] = {"spheres[0].center[2]", "spheres[0].radius", "camera.width", "camera.height",
                         "camera.width", "camera.lookfrom[0]", "spheres[0]", "", "spheres[0].shade"};
  for (size_t k = 0; k < std::size(cases); ++k) {
    const scene_file_error e = error_of(parse_scene_file(cases[k]));
    if (k == 7) {
      EXPECT_EQ(e.path.size(), 32 + std::string_view("\u2026").size()) << e.path;
    } else {
      EXPECT_EQ(e.path, paths[k]) << k;
    }
    EXPECT_LT(e.message.size(), 200u) << e.message;
  }
}

TEST(SceneFile, SpheresBeyondTheFloatRangeAreRefused) {
  EXPECT_EQ(error_path(R"({"spheres": [{"center": [0, 0, -2e38], "radius": 1e38}]})"), "spheres[0].radius");
  EXPECT_EQ(error_path(R"({"spheres": [{"center": [0, 0, -1], "radius": 1}, {"center": [0, 0, -2e38], "radius": 1}]})"),
            "spheres[1].center");
  // From the camera, not the origin of the world: far away but near the camera is fine.
  EXPECT_EQ(error_path(R"({"camera": {"lookfrom": [0, 0, 3e37]}, "spheres": [{"center": [0, 0, 2.5e37], "radius": 1e36}]})"),
            "(none)");
  EXPECT_EQ(error_path(R"({"spheres": [{"center": [1e30, 0, -1e30], "radius": 1e30}]})"), "(none)");
}

// Files: only regular ones are read, nothing blocks, nothing is read whole
// before its size is checked.
class SceneFileLoad : public ::testing::Test {
 protected:
  void SetUp() override {
    char templ[] = "/tmp/raycast-scene-XXXXXX";
    ASSERT_NE(mkdtemp(templ), nullptr);
    dir_ = templ;
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  std::string at(const std::string& name) const { return (dir_ / name).string(); }
  std::filesystem::path dir_;
};

TEST_F(SceneFileLoad, ReadsARegularFile) {
  std::ofstream(at("s.json")) << R"({"spheres": [{"center": [0, 0, -1], "radius": 0.5}]})";
  const auto r = load_scene_file(at("s.json"));
  ASSERT_TRUE(std::holds_alternative<api::scene>(r)) << std::get<scene_file_error>(r).message;
  EXPECT_EQ(std::get<api::scene>(r).spheres.size(), 1u);
  EXPECT_EQ(error_of(load_scene_file(at("missing.json"))).message, "No such file or directory");
}

TEST_F(SceneFileLoad, RefusesWhatIsNotARegularFileWithoutBlocking) {
  std::filesystem::create_directory(at("d.json"));
  ASSERT_EQ(mkfifo(at("f.json").c_str(), 0600), 0);
  const int sock = socket(AF_UNIX, SOCK_STREAM, 0);
  ASSERT_GE(sock, 0);
  sockaddr_un addr{};
  addr.sun_family = AF_UNIX;
  const std::string sock_path = at("s.json");
  ASSERT_LT(sock_path.size(), sizeof addr.sun_path);
  sock_path.copy(addr.sun_path, sock_path.size());
  ASSERT_EQ(bind(sock, reinterpret_cast<const sockaddr*>(&addr), sizeof addr), 0);
  const std::pair<std::string, std::string> cases[] = {
      {at("d.json"), "is a directory"},     {at("f.json"), "is a FIFO"},
      {sock_path, "is a socket"},           {"/dev/null", "is a character device"},
      {"/dev/zero", "is a character device"},
  };
  for (const auto& [name, want] : cases) {
    const auto start = std::chrono::steady_clock::now();
    const scene_file_error e = error_of(load_scene_file(name));
    EXPECT_EQ(e.path, "");
    EXPECT_EQ(e.message.rfind(want, 0), 0u) << name << ": " << e.message;
    EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(5)) << name;
  }
  close(sock);
}

TEST_F(SceneFileLoad, RefusesAFileLargerThanTheCapWithoutReadingIt) {
  {
    const int fd = open(at("big.json").c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
    ASSERT_GE(fd, 0);
    // Sparse: no disk, and a read of it would take seconds.
    ASSERT_EQ(ftruncate(fd, off_t(max_scene_file_bytes) + 1), 0);
    close(fd);
  }
  const auto start = std::chrono::steady_clock::now();
  const scene_file_error e = error_of(load_scene_file(at("big.json")));
  EXPECT_EQ(e.message, "is 4294967296 bytes; a scene file may be at most 4 GiB - 1 (4294967295 bytes)");
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(1));
}

// A file with more bytes than fstat said (one that grew, here one of /proc's,
// whose size reads 0) is refused at the first byte beyond: the buffer never
// outgrows the size that was checked.
TEST_F(SceneFileLoad, RefusesAFileThatGrowsWhileRead) {
  const scene_file_error e = error_of(load_scene_file("/proc/self/status"));
  EXPECT_EQ(e.message, "grew while being read (was 0 bytes)");
}

// Each class of syntax error, in the spheres and in the camera and sky: the
// place where the text breaks the grammar (a comma too many: that comma).
TEST(SceneFile, SyntaxErrorsSayWhatAndWhere) {
  const std::pair<const char*, const char*> cases[] = {
      {R"({"camera": {"width": 40 "vfov": 30}})",
       R"(a comma is missing before this key (at line 1, column 25: "vfov"))"},
      {R"({"camera": {"width" 40}})", "expected a colon after the key (at line 1, column 21: 40)"},
      {R"({"camera": {"width": 40,, "vfov": 30}})",
       R"(a comma with no key after it (at line 1, column 24: ,, "vfov": 30}}))"},
      {R"({"camera": {"width": 40}, "sky": {"top": [1, 1, 1}})",
       "expected ']' to close the array before this '}' (at line 1, column 50: }})"},
      {R"({"sky": {"top": [1, 1, 1,]}})", "a comma with no value after it (at line 1, column 25: ,]}})"},
      {R"({"sky": {"top": @}})", "expected a value (at line 1, column 17: @)"},
      {"{\"sky\": {\"top\": [1, 1, 1]},\n \"camera\": {\"width\": 40}",
       R"(an object is not closed (at line 1, column 1: {"sky")"},
      {R"({"spheres": [{"center": [0, 0, -1], "radius" 1}]})",
       "expected a colon after the key (at line 1, column 46: 1)"},
      {R"({"spheres": [{"center": [0, 0, -1], "radius": 1} x]})",
       "expected a comma or ']' after a value (at line 1, column 50: x)"},
      {R"({"spheres": [{"center": [0, 0, -1], "radius": 1})", "an array is not closed (at line 1, column 13: [{"},
      {R"({"spheres": [{"center": [0, 0, -1, "radius": 1}]})",
       "expected a comma or ']' after a value (at line 1, column 44: : 1}]})"},
      {R"({"spheres": [{"center": [0, 0, -1], "radius": 1}], "camera": {"width": 4})",
       "an object is not closed (at line 1, column 1: {"},
      {"{\"spheres\": [{\"center\": [0, 0, -1], \"shade: \"flat\",\n \"radius\": 1}]}",
       R"(expected a colon after the key (at line 1, column 46: flat"))"},
      {"{\"spheres\": [{\"center\": [0, 0, -1], \"radius: 1},\n {}]}",
       R"(a string is not closed on its line (at line 1, column 37: "radius: 1},))"},
  };
  for (const auto& [text, want] : cases) {
    const scene_file_error e = error_of(parse_scene_file(text));
    EXPECT_EQ(e.path, "") << text;
    EXPECT_EQ(e.message.rfind("not valid JSON: " + std::string(want), 0), 0u) << text << "\n" << e.message;
  }
}

// A few spheres, parsed whole.
TEST_F(SceneFileLoad, SyntaxErrorsInASmallFileSayWhereTheyAre) {
  expect_syntax_errors_placed(5, 1, 0, at("small.json"));
}

// Either side of windowed_from (1 MiB): one byte short, parsed whole; from
// it on, read a window at a time, which gives up at the error and leaves it
// to the whole parse. The error far past the first window.
TEST_F(SceneFileLoad, SyntaxErrorsInLargeFilesSayWhereTheyAre) {
  const int n = spheres_in(windowed_from - 1);
  expect_syntax_errors_placed(n, n - 10, windowed_from - 1, at("below.json"));
  expect_syntax_errors_placed(n, n - 10, windowed_from, at("at.json"));
  expect_syntax_errors_placed(2 * n, n - 10, 0, at("above.json"));
}

// A text of 16 MiB or more hands its start back as the spheres are read
// (release_text_before): a syntax error past that is still placed, in a
// sphere and in the camera after the array.
TEST(SceneFile, SyntaxErrorsPastTheTextHandedBackSayWhereTheyAre) {
  constexpr int n = 420000;
  std::string text = spheres_text(n, -1, defect::missing_comma, 0);
  text.resize(text.size() - 3);  // "]}\n"
  text += "],\n\"camera\": {\"width\": 40 \"vfov\": 30}}";
  ASSERT_GE(text.size(), size_t(16) << 20);
  const scene_file_error camera = error_of(parse_scene_file(text));
  EXPECT_EQ(camera.message, "not valid JSON: a comma is missing before this key (at line " + std::to_string(n + 3) +
                                ", column 24: \"vfov\")");
  // The colon of a sphere's radius left out, 1 MB before the end.
  const size_t colon = text.find("\"radius\":", text.size() - 1000000) + 8;
  text.erase(colon, 1);
  const size_t line_start = text.rfind('\n', colon) + 1;
  const std::string place = std::to_string(std::count(text.begin(), text.begin() + long(colon), '\n') + 1) +
                            ", column " + std::to_string(colon + 2 - line_start);
  EXPECT_EQ(error_of(parse_scene_file(text)).message,
            "not valid JSON: expected a colon after the key (at line " + place + ": 0.25)");
}

// 100,000 spheres : parsed, and rendered by a
// SIMD backend exactly as by the scalar renderer at a small size.
TEST(SceneFile, AHundredThousandSpheres) {
  std::string text = R"({"camera": {"width": 24, "height": 12}, "spheres": [)";
  for (int k = 0; k < 100000; ++k) {
    const double x = double(k % 400) * 0.01 - 2.0, y = double(k / 400) * 0.01 - 1.25;
    text += k ? R"(,{"center": [)" : R"({"center": [)";
    text += std::to_string(x) + "," + std::to_string(y) + R"(,-3], "radius": 0.004)";
    text += k % 2 ? R"(, "shade": "flat", "color": [1, 0.5, 0]})" : "}";
  }
  text += "]}";
  const api::scene p = parsed(text);
  ASSERT_EQ(p.spheres.size(), 100000u);
  ASSERT_FALSE(validate(p));
  const scene s = make_scene(p);
  const raycast_test::image want = raycast_test::render_with_scalar(s, precision::exact, pixel_format::rgb8);
  const raycast_test::image got =
      raycast_test::render_with(renderer(s, {backend::automatic, precision::exact, 1}), pixel_format::rgb8);
  EXPECT_EQ(got.bytes, want.bytes);
}

}  // namespace
