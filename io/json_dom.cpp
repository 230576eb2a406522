#include "io/json_dom.h"

#include <algorithm>
#include <set>
#include <vector>

#include "snapfit/error.h"

namespace snapfit {
namespace {

using json = nlohmann::json;

// Builds the DOM through SAX events so that every syntax error keeps its byte position
// (number overflow included) and duplicate keys are caught with their field path.
class DomBuilder : public nlohmann::json_sax<json> {
 public:
  json root;
  bool has_syntax_error = false;
  std::size_t error_byte = 0;  // characters read when the error was found
  std::string error_text;      // nlohmann's description, without its prefix
  std::string duplicate_path;  // set when a key repeats within one object

  bool null() override { return add(json(nullptr)) != nullptr; }
  bool boolean(bool v) override { return add(json(v)) != nullptr; }
  bool number_integer(number_integer_t v) override { return add(json(v)) != nullptr; }
  bool number_unsigned(number_unsigned_t v) override { return add(json(v)) != nullptr; }
  bool number_float(number_float_t v, const string_t&) override { return add(json(v)) != nullptr; }
  bool string(string_t& v) override { return add(json(v)) != nullptr; }
  bool binary(binary_t& v) override { return add(json::binary(v)) != nullptr; }

  bool start_object(std::size_t) override { return open(json::object(), false); }
  bool start_array(std::size_t) override { return open(json::array(), true); }
  bool end_object() override { return frames_.pop_back(), true; }
  bool end_array() override { return frames_.pop_back(), true; }

  bool key(string_t& k) override {
    Frame& f = frames_.back();
    if (!f.keys.insert(k).second) {
      duplicate_path = f.path.empty() ? k : f.path + "." + k;
      return false;
    }
    f.key = k;
    return true;
  }

  bool parse_error(std::size_t position, const std::string&, const json::exception& ex) override {
    has_syntax_error = true;
    error_byte = position;
    std::string what = ex.what();  // "[json.exception.parse_error.101] parse error at ...: text"
    if (const auto close = what.find("] "); close != std::string::npos) what.erase(0, close + 2);
    if (what.rfind("parse error", 0) == 0)
      if (const auto colon = what.find(": "); colon != std::string::npos) what.erase(0, colon + 2);
    error_text = what;
    return false;
  }

 private:
  struct Frame {
    json* node;
    bool is_array;
    std::set<std::string> keys;
    std::string key;
    std::size_t count = 0;
    std::string path;
  };
  std::vector<Frame> frames_;  // open containers, outermost first

  std::string child_path() const {
    if (frames_.empty()) return "";
    const Frame& f = frames_.back();
    if (f.is_array) return f.path + "[" + std::to_string(f.count) + "]";
    return f.path.empty() ? f.key : f.path + "." + f.key;
  }
  json* add(json value) {
    if (frames_.empty()) return &(root = std::move(value));
    Frame& f = frames_.back();
    if (f.is_array) {
      f.node->push_back(std::move(value));
      ++f.count;
      return &f.node->back();
    }
    return &((*f.node)[f.key] = std::move(value));
  }
  bool open(json container, bool is_array) {
    std::string path = child_path();
    json* node = add(std::move(container));
    frames_.push_back(Frame{node, is_array, {}, "", 0, std::move(path)});
    return true;
  }
};

// 1-based line and column of the character at which the parser stopped: the last of
// the `byte` characters it read (the end of the text counts as one character).
std::pair<std::size_t, std::size_t> line_and_column(const std::string& text, std::size_t byte) {
  const std::size_t last = byte == 0 ? 0 : byte - 1;
  std::size_t line = 1, line_start = 0;
  for (std::size_t i = 0; i < std::min(last, text.size()); ++i)
    if (text[i] == '\n') ++line, line_start = i + 1;
  return {line, last - line_start + 1};
}
}  // namespace

json parse_json_dom(const std::string& text, const std::string& origin) {
  DomBuilder dom;
  if (!json::sax_parse(text, &dom, json::input_format_t::json, true, false)) {
    if (!dom.duplicate_path.empty()) throw Error(origin + ": " + dom.duplicate_path + ": duplicate field");
    const auto [line, column] = line_and_column(text, dom.error_byte);
    throw Error(origin + ": invalid JSON at line " + std::to_string(line) + ", column " + std::to_string(column) +
                ": " + dom.error_text);
  }
  return std::move(dom.root);
}

}  // namespace snapfit
