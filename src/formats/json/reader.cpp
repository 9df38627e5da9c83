#include "formats/json/reader.h"

#include <new>

#include "memory/arrays.h"

namespace raycast::json_detail {

// The number as written, for the input table's parsers.
std::string_view reader::number_token(od::value& v, const std::string& path, const char* must_be) {
  const char* start = at(v);
  od::json_type t;
  if (v.type().get(t) != simdjson::SUCCESS) fail_json("not a JSON value", start);
  if (t != od::json_type::number) fail(path, must_be, start);
  std::string_view token = v.raw_json_token();
  while (!token.empty() && std::string_view(" \t\r\n").find(token.back()) != std::string_view::npos)
    token.remove_suffix(1);
  if (!json_number(token)) fail(path, quote_token(token) + " is not a JSON number", start);
  return token;
}

void reader::read_setting(od::value& v, const setting& row, given& g) {
  const std::string path(row.file_key);
  const char* start = at(v);
  g.source = path;
  g.where = where(start);
  const auto parse = [&](std::string_view text, const std::string& blame) {
    if (auto e = parse_value(row, text, g.v, g.tokens)) fail(blame, *e, start);
  };
  switch (row.type) {
    case value_type::integer: parse(number_token(v, path, "must be an integer"), path); break;
    case value_type::real: parse(number_token(v, path, "must be a number"), path); break;
    case value_type::aspect: {
      // A number, or a string the command line would take: "16:9", "1.5".
      od::json_type t;
      if (v.type().get(t) != simdjson::SUCCESS) fail_json("not a JSON value", start);
      if (t == od::json_type::number) return parse(number_token(v, path, ""), path);
      if (t != od::json_type::string) fail(path, "must be a number or a string \"W:H\"", start);
      std::string_view text;
      if (error_code e = v.get_string().get(text)) fail_json(e, start);
      return parse(text, path);
    }
    case value_type::triple: {
      od::array arr = array(v, [&] { return path; }, "must be an array of 3 numbers");
      int n = 0;
      for (auto result : arr) {
        od::value el;
        if (error_code e = std::move(result).get(el)) fail_json(e, here());
        if (n == 3) fail(path, "must be an array of 3 numbers", starts_value(*at(el)) ? start : at(el));
        const std::string el_path = path + "[" + std::to_string(n) + "]";
        const std::string_view token = number_token(el, el_path, "must be a number");
        if (auto e = parse_real(token, g.v.triple[n])) fail(el_path, *e, at(el));
        g.tokens[size_t(n)] = token.substr(0, 64);
        ++n;
      }
      if (n != 3) fail(path, "must be an array of 3 numbers", start);
      break;
    }
    case value_type::name: {  // a string the command line would take: "orthographic"
      od::json_type t;
      if (v.type().get(t) != simdjson::SUCCESS) fail_json("not a JSON value", start);
      if (t != od::json_type::string) fail(path, "must be a string", start);
      std::string_view text;
      if (error_code e = v.get_string().get(text)) fail_json(e, start);
      g.tokens[0] = std::string(text.substr(0, 64));
      return parse(text, path);
    }
    case value_type::flag: {  // true or false: "shadows": true
      bool b = false;
      if (v.get_bool().get(b) != simdjson::SUCCESS) fail(path, "must be true or false", start);
      g.v.flag = b;
      g.tokens[0] = b ? "true" : "false";
      break;
    }
    default: fail(path, "is not a scene file key", start);
  }
}

// The keys of "camera", "sky", "light" or "ambient_occlusion": the input
// table's rows with that file key prefix.
void reader::read_settings(od::value& v, std::string_view object_name, settings& out) {
  static const auto known_of = [](std::string_view prefix) {
    std::vector<std::string_view> names;
    for (const setting& row : input_table())
      if (is_scene_row(row) && row.file_key.substr(0, row.file_key.find('.')) == prefix) names.push_back(row.file_key.substr(prefix.size() + 1));
    return names;
  };
  static const std::vector<std::string_view> camera_keys = known_of("camera"), sky_keys = known_of("sky"),
                                             light_keys = known_of("light"), ao_keys = known_of("ambient_occlusion");
  const std::vector<std::string_view>& known = object_name == "camera" ? camera_keys
                                               : object_name == "sky"  ? sky_keys
                                               : object_name == "light" ? light_keys
                                                                        : ao_keys;
  const auto object_path = [&] { return std::string(object_name); };
  fields(object(v, object_path), object_path, known, [&](int key, od::value& value) {
    const setting& row = *find_file_key(std::string(object_name) + "." + std::string(known[size_t(key)]));
    given g;
    read_setting(value, row, g);
    out[row.id] = std::move(g);
  });
}

void reader::read_spheres(od::value& v, std::vector<sphere>& out) {
  const char* start = at(v);
  od::array list = array(v, [] { return std::string("spheres"); }, "must be an array");
  // Exactly the spheres there are (a pass over the index, not the text). A
  // malformed array fails the count, which leaves the iterator lost (at the
  // end of the text): the error is reported from the text.
  size_t count = 0;
  if (error_code e = list.count_elements().get(count)) fail_json(e, start);
  out.reserve(count);
  advise_huge_pages(out.data(), out.capacity() * sizeof(sphere));
  size_t k = 0;
  for (auto result : list) {
    if (error_code e = result.error()) fail_json(e, here());
    od::value& item = result.value_unsafe();  // in place, as in fields()
    const char* sphere_at = at(item);
    out.push_back(read_sphere(item, k));
    if (++k % 4096 == 0) {
      release_text_before(sphere_at);
      scan_from_ = sphere_at;  // kept, and all before it read
    }
  }
}

sphere reader::read_sphere(od::value& item, size_t k) {
  const auto at_k = [&k] { return "spheres[" + std::to_string(k) + "]"; };
  const char* sphere_at = at(item);
  // Where each value is (nullptr: not given), for the errors about it.
  const char *center_at = nullptr, *radius_at = nullptr, *color_at = nullptr;
  sphere ball;
  static constexpr std::string_view sphere_keys[] = {"center", "radius", "shade", "color"};
  fields(object(item, at_k), at_k, sphere_keys, [&](int key, od::value& value) {
    switch (key) {
      case 0:
        center_at = at(value);
        ball.center = triple(value, [&] { return at_k() + ".center"; });
        break;
      case 1:
        radius_at = at(value);
        ball.radius = number(value, [&] { return at_k() + ".radius"; });
        break;
      case 2: {
        const char* shade_at = at(value);
        // The names as usually written, compared in place (a closing quote
        // cannot come early: it would be escaped); others are unescaped first.
        const std::string_view raw = value.raw_json_token();
        if (raw.rfind("\"normal\"", 0) == 0 || raw.rfind("\"flat\"", 0) == 0 || raw.rfind("\"lit\"", 0) == 0) {
          ball.shade = raw[1] == 'f' ? shading::flat : raw[1] == 'l' ? shading::lit : shading::normal;
          break;
        }
        std::string_view s;
        const error_code e = value.get_string().get(s);
        if (e != simdjson::SUCCESS && e != simdjson::INCORRECT_TYPE) fail_json(e, shade_at);
        if (e != simdjson::SUCCESS || (s != "normal" && s != "flat" && s != "lit"))
          fail(at_k() + ".shade", "must be \"normal\", \"flat\" or \"lit\"", shade_at);
        ball.shade = s == "flat" ? shading::flat : s == "lit" ? shading::lit : shading::normal;
        break;
      }
      case 3:
        color_at = at(value);
        ball.color = triple(value, [&] { return at_k() + ".color"; });
        break;
    }
  });
  if (!center_at) fail(at_k() + ".center", "is required", sphere_at);
  if (!radius_at) fail(at_k() + ".radius", "is required", sphere_at);
  if (ball.shade != shading::normal && !color_at)
    fail(at_k() + ".color", ball.shade == shading::flat ? "is required for flat shading" : "is required for lit shading",
         sphere_at);
  if (auto e = validate(ball, k)) {
    const char* blame = e->field == scene_field::sphere_center   ? center_at
                        : e->field == scene_field::sphere_radius ? radius_at
                                                                 : color_at;
    fail(path(*e), e->message, blame);
  }
  return ball;
}

const char* reader::read_window(std::vector<sphere>& out, size_t& k) {
  const char* after = nullptr;
  od::array list;
  if (doc_.get_array().get(list) != simdjson::SUCCESS) return after;
  try {
    for (auto result : list) {
      if (result.error() != simdjson::SUCCESS) break;
      od::value& item = result.value_unsafe();  // in place, as in fields()
      const sphere b = read_sphere(item, k);
      const char* next = here();
      if (!next) break;
      out.push_back(b);
      ++k;
      after = next;
    }
  } catch (const window_failed&) {
  }
  return after;
}

scene_file_contents reader::read() {
  scene_file_contents p;
  od::object root;
  if (error_code e = doc_.get_object().get(root)) {
    if (e == simdjson::INCORRECT_TYPE) fail("", "must be an object", here());
    fail_json(e, here());
  }
  static constexpr std::string_view root_keys[] = {"camera", "sky", "spheres", "light", "ambient_occlusion"};
  fields(root, [] { return std::string(); }, root_keys, [&](int key, od::value& value) {
    if (key == 2) read_spheres(value, p.scene.spheres);
    else read_settings(value, root_keys[key], p.keys);
  });
  // At the end, the document has no current location.
  const char* rest = nullptr;
  if (doc_.current_location().get(rest) == simdjson::SUCCESS) fail_json(simdjson::TRAILING_CONTENT, rest);
  // One file gives vfov or viewport_height, not both.
  if (auto e = check_groups(p.keys)) throw failure{{e->source, e->message}};
  return p;
}

std::variant<scene_file_contents, scene_file_error> parse_padded(const padded_text& t) {
  od::parser parser(max_scene_file_bytes);
  if (error_code e = parser.allocate(std::max<size_t>(t.size(), 1), max_depth))
    return scene_file_error{"", (e == simdjson::MEMALLOC ? "out of memory indexing " + bytes_text(t.size())
                                                         : "cannot index: " + json_error(e))};
  od::document doc;
  // Stage one (the index of the whole text) says nothing of where; a string
  // not closed or over a line's end (a quote missing, or one too many) is
  // placed by the scan.
  const error_code indexed = parser.iterate(t.data(), t.size(), t.capacity()).get(doc);
  if (indexed && indexed != simdjson::UNCLOSED_STRING && indexed != simdjson::UNESCAPED_CHARS)
    return scene_file_error{"", "not valid JSON: " + json_error(indexed)};
  try {
    reader r(t.data(), t.size(), t.mapped(), doc);
    if (indexed) r.fail_index(indexed);
    return r.read();
  } catch (const failure& x) {
    return x.e;
  } catch (const std::bad_alloc&) {
    return scene_file_error{"", "out of memory"};
  }
}

// A large text is parsed without an index of all of it: simdjson's index
// holds 4 bytes for each of its ~20 structural characters a sphere, which
// for a million spheres is 80 MB of fresh memory, slower to fault in on some
}  // namespace raycast::json_detail
