#include "io/json_reader.h"

#include <algorithm>
#include <charconv>
#include <climits>
#include <cmath>
#include <numeric>

#include "io/error.h"

namespace sixway::io {
namespace {

// Follows the parser through the document so that a repeated key can be named by its path; the
// parser itself would keep the last value silently.
class DuplicateKeyCheck {
 public:
  explicit DuplicateKeyCheck(std::string_view source) : source_(source) {}

  void onEvent(JsonEvent event, std::string_view key) {
    switch (event) {
      case JsonEvent::object_start:
        frames_.push_back({.array = false});
        break;
      case JsonEvent::array_start:
        frames_.push_back({.array = true});
        break;
      case JsonEvent::key: {
        Frame& frame = frames_.back();
        frame.key = key;
        if (!frame.keys.insert(frame.key).second)
          throw InputError(source_, path() + ": key appears twice in the same object");
        break;
      }
      case JsonEvent::object_end:
      case JsonEvent::array_end:
        frames_.pop_back();
        elementDone();
        break;
      case JsonEvent::value:
        elementDone();
        break;
    }
  }

 private:
  struct Frame {
    bool array;
    std::size_t index = 0;  // arrays: the element being read
    std::string key;        // objects: the key being read
    std::set<std::string> keys;
  };

  void elementDone() {
    if (!frames_.empty() && frames_.back().array) ++frames_.back().index;
  }

  std::string path() const {
    std::string path;
    for (const Frame& frame : frames_) {
      if (frame.array)
        path += "[" + std::to_string(frame.index) + "]";
      else
        path += (path.empty() ? "" : ".") + frame.key;
    }
    return path;
  }

  std::string source_;
  std::vector<Frame> frames_;
};

// Builds the document as nlohmann's DOM parser does and reports every event to a check first, with the depth
// nlohmann's parse callbacks would give it. nlohmann's callback parser is not used because it searches the
// enclosing array or object for discarded values at the end of every element that is itself an array or
// object, which makes parsing quadratic in the length of an array of objects.
class CheckedDomBuilder {
 public:
  using json = nlohmann::json;

  CheckedDomBuilder(json& root, const JsonEventCheck& check) : dom_(root), check_(check) {}

  bool null() { return scalar() && dom_.null(); }
  bool boolean(bool v) { return scalar() && dom_.boolean(v); }
  bool number_integer(json::number_integer_t v) { return scalar() && dom_.number_integer(v); }
  bool number_unsigned(json::number_unsigned_t v) { return scalar() && dom_.number_unsigned(v); }
  bool number_float(json::number_float_t v, const json::string_t& text) {
    return scalar() && dom_.number_float(v, text);
  }
  bool string(json::string_t& v) { return scalar() && dom_.string(v); }
  bool binary(json::binary_t& v) { return scalar() && dom_.binary(v); }

  bool start_object(std::size_t count) {
    check_(depth_++, JsonEvent::object_start, {});
    return dom_.start_object(count);
  }
  bool key(json::string_t& key) {
    check_(depth_, JsonEvent::key, key);
    return dom_.key(key);
  }
  bool end_object() {
    check_(--depth_, JsonEvent::object_end, {});
    return dom_.end_object();
  }
  bool start_array(std::size_t count) {
    check_(depth_++, JsonEvent::array_start, {});
    return dom_.start_array(count);
  }
  bool end_array() {
    check_(--depth_, JsonEvent::array_end, {});
    return dom_.end_array();
  }

  template <class Exception>
  bool parse_error(std::size_t position, const std::string& token, const Exception& error) {
    return dom_.parse_error(position, token, error);
  }

 private:
  bool scalar() {
    check_(depth_, JsonEvent::value, {});
    return true;
  }

  nlohmann::detail::json_sax_dom_parser<json> dom_;
  const JsonEventCheck& check_;
  int depth_ = 0;  // arrays and objects open around the next event
};

std::size_t editDistance(std::string_view a, std::string_view b) {
  std::vector<std::size_t> row(b.size() + 1);
  std::iota(row.begin(), row.end(), 0);
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t substitution = diagonal + (a[i - 1] == b[j - 1] ? 0 : 1);
      diagonal = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, substitution});
    }
  }
  return row[b.size()];
}

// The candidate that `key` is most likely a typo of, if any is close enough.
template <class Keys>
std::optional<std::string> likelyTypo(std::string_view key, const Keys& candidates) {
  const std::size_t limit = key.size() <= 4 ? 1 : 2;
  std::optional<std::string> best;
  std::size_t bestDistance = limit + 1;
  for (const std::string& candidate : candidates) {
    const std::size_t d = editDistance(key, candidate);
    if (d < bestDistance) {
      best = candidate;
      bestDistance = d;
    }
  }
  return best;
}

std::string shortDump(const nlohmann::json& value) {
  std::string text = value.dump();
  return text.size() <= 60 ? text : text.substr(0, 57) + "...";
}

template <class T>
std::string showChars(T v) {
  char buffer[32];
  const auto end = std::to_chars(buffer, buffer + sizeof buffer, v).ptr;
  return std::string(buffer, end);
}

// Appending piece by piece: "[" + a + ", " + ... trips a false -Wrestrict in GCC 12 (bug 105651).
template <class V>
std::string showVector(const V& v) {
  std::string text = "[";
  for (int i = 0; i < 3; ++i) {
    if (i > 0) text += ", ";
    text += show(v[i]);
  }
  text += "]";
  return text;
}

template <class V, class Element>
std::optional<V> decodeVector(const nlohmann::json& v) {
  if (!v.is_array() || v.size() != 3) return std::nullopt;
  V out;
  for (int i = 0; i < 3; ++i) {
    std::optional<Element> c = JsonDecode<Element>::from(v[i]);
    if (!c) return std::nullopt;
    out[i] = *c;
  }
  return out;
}

template <class Element>
std::optional<std::vector<Element>> decodeList(const nlohmann::json& v) {
  if (!v.is_array()) return std::nullopt;
  std::vector<Element> out;
  for (const nlohmann::json& element : v) {
    std::optional<Element> decoded = JsonDecode<Element>::from(element);
    if (!decoded) return std::nullopt;
    out.push_back(*decoded);
  }
  return out;
}

}  // namespace

nlohmann::json parseJsonChecked(std::string_view text, const JsonEventCheck& check) {
  nlohmann::json root;
  CheckedDomBuilder builder(root, check);
  nlohmann::json::sax_parse(text.begin(), text.end(), &builder);
  return root;
}

nlohmann::json parseJsonText(std::string_view text, std::string_view source) {
  DuplicateKeyCheck duplicates(source);
  auto check = [&duplicates, source](int depth, JsonEvent event, std::string_view key) {
    if (depth >= kMaxJsonNesting)  // depth counts from 0: N nested levels reach N − 1
      throw InputError(source, "JSON nested deeper than " + std::to_string(kMaxJsonNesting) + " levels");
    duplicates.onEvent(event, key);
  };
  try {
    return parseJsonChecked(text, check);
  } catch (const nlohmann::json::exception& e) {
    // A syntax error (parse_error) or a number beyond double (out_of_range 406, e.g. 1e999). Drop the
    // "[json.exception.parse_error.101] " prefix; the rest names line and column, or the number.
    std::string what = e.what();
    if (const std::size_t end = what.find("] "); end != std::string::npos) what.erase(0, end + 2);
    throw InputError(source, "invalid JSON: " + what);
  }
}

std::optional<float> JsonDecode<float>::from(const nlohmann::json& v) {
  if (!v.is_number()) return std::nullopt;
  const double d = v.get<double>();
  const float f = static_cast<float>(d);
  // Beyond a float's range, or so small that it would read as 0: failType says which.
  return std::isfinite(f) && (f != 0 || d == 0) ? std::optional(f) : std::nullopt;
}

std::optional<int> JsonDecode<int>::from(const nlohmann::json& v) {
  if (!v.is_number_integer()) return std::nullopt;
  if (v.is_number_unsigned())
    return v.get<std::uint64_t>() <= INT_MAX ? std::optional(v.get<int>()) : std::nullopt;
  const std::int64_t i = v.get<std::int64_t>();
  return i >= INT_MIN && i <= INT_MAX ? std::optional(static_cast<int>(i)) : std::nullopt;
}

std::optional<std::uint32_t> JsonDecode<std::uint32_t>::from(const nlohmann::json& v) {
  if (!v.is_number_unsigned() || v.get<std::uint64_t>() > UINT32_MAX) return std::nullopt;
  return static_cast<std::uint32_t>(v.get<std::uint64_t>());
}

std::optional<bool> JsonDecode<bool>::from(const nlohmann::json& v) {
  return v.is_boolean() ? std::optional(v.get<bool>()) : std::nullopt;
}

std::optional<std::string> JsonDecode<std::string>::from(const nlohmann::json& v) {
  return v.is_string() ? std::optional(v.get<std::string>()) : std::nullopt;
}

std::optional<glm::vec3> JsonDecode<glm::vec3>::from(const nlohmann::json& v) {
  return decodeVector<glm::vec3, float>(v);
}

std::optional<glm::ivec3> JsonDecode<glm::ivec3>::from(const nlohmann::json& v) {
  return decodeVector<glm::ivec3, int>(v);
}

std::optional<std::vector<std::string>> JsonDecode<std::vector<std::string>>::from(const nlohmann::json& v) {
  return decodeList<std::string>(v);
}

std::optional<std::vector<glm::vec3>> JsonDecode<std::vector<glm::vec3>>::from(const nlohmann::json& v) {
  return decodeList<glm::vec3>(v);
}

// Whole numbers up to seven digits in full ("100000", not the shortest form "1e+05"); others in their
// shortest round-tripping form.
template <class T>
std::string showNumber(T v) {
  if (std::abs(v) < T(1e7) && v == std::trunc(v)) return std::to_string(static_cast<long>(v));
  return showChars(v);
}

std::string show(float v) {
  return showNumber(v);
}
std::string show(double v) {
  return showNumber(v);
}
std::string show(int v) {
  return std::to_string(v);
}
std::string show(std::uint32_t v) {
  return std::to_string(v);
}
std::string show(const glm::vec3& v) {
  return showVector(v);
}
std::string show(const glm::ivec3& v) {
  return showVector(v);
}

JsonReader::JsonReader(const nlohmann::json& object, std::string path, std::string_view source)
    : object_(object), path_(std::move(path)), source_(source) {
  if (!object_.is_object()) failHere("expected an object (got " + shortDump(object_) + ")");
}

const nlohmann::json* JsonReader::find(std::string_view key) {
  known_.emplace(key);
  const auto it = object_.find(std::string(key));
  return it == object_.end() ? nullptr : &*it;
}

void JsonReader::forbid(std::string_view key, std::string_view why) {
  if (find(key)) fail(key, "not allowed (" + std::string(why) + ")");
}

void JsonReader::finish() const {
  for (const auto& item : object_.items()) {
    if (known_.contains(item.key())) continue;
    const std::optional<std::string> meant = likelyTypo(item.key(), known_);
    fail(item.key(), "unknown key" + (meant ? " (did you mean \"" + *meant + "\"?)" : std::string()));
  }
}

std::string JsonReader::pathOf(std::string_view key) const {
  return path_.empty() ? std::string(key) : path_ + "." + std::string(key);
}

void JsonReader::fail(std::string_view key, std::string_view problem) const {
  throw InputError(source_, pathOf(key) + ": " + std::string(problem));
}

void JsonReader::failHere(std::string_view problem) const {
  throw InputError(source_, (path_.empty() ? "" : path_ + ": ") + std::string(problem));
}

void JsonReader::failMissing(std::string_view key) const {
  // A present key that nobody asked for yet and is spelt almost like the missing one is likely a typo.
  std::vector<std::string> unread;
  for (const auto& item : object_.items())
    if (!known_.contains(item.key())) unread.push_back(item.key());
  const std::optional<std::string> typo = likelyTypo(key, unread);
  fail(key, "required key missing" + (typo ? " (is \"" + *typo + "\" a typo?)" : std::string()));
}

void JsonReader::failType(std::string_view key, std::string_view expected, const nlohmann::json& got) const {
  // A number of the right type that a 32-bit float cannot hold, alone or in a vector: say so, rather than
  // "expected a number (got 1e+308)".
  if (std::string_view(expected).find("number") != std::string_view::npos) {
    const auto unrepresentable = [](const nlohmann::json& v) {
      return v.is_number_float() && !JsonDecode<float>::from(v);
    };
    const nlohmann::json* culprit = unrepresentable(got) ? &got : nullptr;
    if (got.is_array() && got.size() <= 16)
      for (const nlohmann::json& element : got)
        if (!culprit && unrepresentable(element)) culprit = &element;
    if (culprit) {
      const double d = culprit->get<double>();
      fail(key, std::abs(d) < 1
                    ? "is too small for a 32-bit float, which would make it 0 (got " + show(d) + ")"
                    : "is beyond the range of a 32-bit float, ±3.4e38 (got " + show(d) + ")");
    }
  }
  fail(key, "expected " + std::string(expected) + " (got " + shortDump(got) + ")");
}

}  // namespace sixway::io
