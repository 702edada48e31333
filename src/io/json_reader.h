#pragma once
// Typed, validated reading of JSON settings files. Every error is one InputError line that names the
// file, the key's path ("obstacles[1].radius") and the reason.
//
// A JsonReader wraps one JSON object. Each key it is asked for, present or not, becomes known;
// finish() rejects any other key, so a typo is an error rather than a silently ignored setting.
// Checks are small functors that return the problem, or "" when the value is fine:
//   g.cellSize = r.required<float>("cell_size", positive());
//   s.albedo = r.optional<float>("albedo", s.albedo, inRange(0, 1));
#include <cstdint>
#include <functional>
#include <limits>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <glm/vec3.hpp>
#include <nlohmann/json.hpp>

namespace sixway::io {

// The deepest nesting of arrays and objects accepted. Sixway's own files nest fewer than 10 levels; a deeper
// document is refused while it is parsed, because printing or copying it recurses once per level and would
// overflow the stack.
inline constexpr int kMaxJsonNesting = 64;

using JsonEvent = nlohmann::json::parse_event_t;
// Called before each event of a parse with the depth nlohmann's parse callbacks report (0 for the outermost
// value, its keys and elements at 1) and, for a key, the key; it refuses the document by throwing.
using JsonEventCheck = std::function<void(int depth, JsonEvent event, std::string_view key)>;

// Parses JSON text in time linear in its length, calling `check` at every event. Syntax errors and numbers
// beyond double are nlohmann's exceptions, as from nlohmann::json::parse.
nlohmann::json parseJsonChecked(std::string_view text, const JsonEventCheck& check);

// Parses JSON text. Syntax errors (with line and column), keys repeated within one object and nesting deeper
// than kMaxJsonNesting are errors.
nlohmann::json parseJsonText(std::string_view text, std::string_view source);

// Conversion of one JSON value to T; nullopt when the value has the wrong type.
template <class T>
struct JsonDecode;

#define SIXWAY_JSON_DECODE(T, what)                        \
  template <>                                              \
  struct JsonDecode<T> {                                   \
    static constexpr const char* expected = what;          \
    static std::optional<T> from(const nlohmann::json& v); \
  };
SIXWAY_JSON_DECODE(float, "a number")
SIXWAY_JSON_DECODE(int, "an integer")
SIXWAY_JSON_DECODE(std::uint32_t, "an integer in [0, 4294967295]")
SIXWAY_JSON_DECODE(bool, "true or false")
SIXWAY_JSON_DECODE(std::string, "a string")
SIXWAY_JSON_DECODE(glm::vec3, "an array of 3 numbers")
SIXWAY_JSON_DECODE(glm::ivec3, "an array of 3 integers")
SIXWAY_JSON_DECODE(std::vector<std::string>, "an array of strings")
SIXWAY_JSON_DECODE(std::vector<glm::vec3>, "an array of arrays of 3 numbers")
#undef SIXWAY_JSON_DECODE

// Values as they appear in messages: "-0.5", "[1, 0, 2]".
std::string show(float v);
std::string show(double v);
std::string show(int v);
std::string show(std::uint32_t v);
std::string show(const glm::vec3& v);
std::string show(const glm::ivec3& v);

// --- checks -------------------------------------------------------------------------------------
// They apply to numbers and, component by component, to vectors.

namespace detail {

template <class T>
constexpr int componentCount() {
  if constexpr (requires(const T& v) { v.length(); }) {
    return T::length();
  } else {
    return 1;
  }
}

template <class T, class Pred>
bool everyComponent(const T& v, Pred pred) {
  if constexpr (componentCount<T>() == 1) {
    return pred(v);
  } else {
    for (int i = 0; i < componentCount<T>(); ++i)
      if (!pred(v[i])) return false;
    return true;
  }
}

template <class T>
std::string mustBe(const T& v, const std::string& rule) {
  const char* subject = componentCount<T>() == 1 ? "must be " : "every component must be ";
  return subject + rule + " (got " + show(v) + ")";
}

}  // namespace detail

struct NoCheck {
  template <class T>
  std::string operator()(const T&) const {
    return {};
  }
};

inline auto positive() {
  return [](const auto& v) -> std::string {
    return detail::everyComponent(v, [](auto c) { return c > 0; }) ? "" : detail::mustBe(v, "> 0");
  };
}

// Bounds are compared in the value's own type, so that inRange(-0.99, 0.99) accepts the float 0.99.
inline auto atLeast(double lo) {
  return [lo](const auto& v) -> std::string {
    auto ok = [lo](auto c) { return c >= static_cast<decltype(c)>(lo); };
    return detail::everyComponent(v, ok) ? "" : detail::mustBe(v, ">= " + show(lo));
  };
}

inline auto inRange(double lo, double hi) {
  return [lo, hi](const auto& v) -> std::string {
    auto ok = [lo, hi](auto c) {
      return c >= static_cast<decltype(c)>(lo) && c <= static_cast<decltype(c)>(hi);
    };
    return detail::everyComponent(v, ok) ? "" : detail::mustBe(v, "in [" + show(lo) + ", " + show(hi) + "]");
  };
}

// Both ends excluded.
inline auto inOpenRange(double lo, double hi) {
  return [lo, hi](const auto& v) -> std::string {
    auto ok = [lo, hi](auto c) {
      return c > static_cast<decltype(c)>(lo) && c < static_cast<decltype(c)>(hi);
    };
    return detail::everyComponent(v, ok) ? "" : detail::mustBe(v, "in (" + show(lo) + ", " + show(hi) + ")");
  };
}

inline auto multipleOf(int m) {
  return
      [m](int v) -> std::string { return v % m == 0 ? "" : detail::mustBe(v, "a multiple of " + show(m)); };
}

inline auto nonZero() {
  return [](const glm::vec3& v) -> std::string {
    const bool zero = v.x * v.x + v.y * v.y + v.z * v.z < 1e-12f;
    return zero ? "must not be the zero vector (got " + show(v) + ")" : "";
  };
}

// 0 (a feature turned off) or a value in [lo, hi].
inline auto zeroOrInRange(double lo, double hi) {
  return [lo, hi](float v) -> std::string {
    const bool ok = v == 0.0f || (v >= static_cast<float>(lo) && v <= static_cast<float>(hi));
    return ok ? "" : detail::mustBe(v, "0 or in [" + show(lo) + ", " + show(hi) + "]");
  };
}

template <class A, class B>
auto both(A a, B b) {
  return [a, b](const auto& v) -> std::string {
    std::string problem = a(v);
    return problem.empty() ? b(v) : problem;
  };
}

// --- the reader ---------------------------------------------------------------------------------

// The accepted spellings of an enum-like string setting.
template <class E>
using Choices = std::vector<std::pair<std::string_view, E>>;

class JsonReader {
 public:
  // `object` must outlive the reader (a value that is not an object is an error); `path` is its own
  // path, "" at the top.
  JsonReader(const nlohmann::json& object, std::string path, std::string_view source);

  template <class T, class Check = NoCheck>
  T required(std::string_view key, Check check = {}) {
    const nlohmann::json* value = find(key);
    if (!value) failMissing(key);
    return read<T>(key, *value, check);
  }

  template <class T, class Check = NoCheck>
  T optional(std::string_view key, T fallback, Check check = {}) {
    const nlohmann::json* value = find(key);
    return value ? read<T>(key, *value, check) : fallback;
  }

  // For keys whose absence means something other than a default value.
  template <class T, class Check = NoCheck>
  std::optional<T> maybe(std::string_view key, Check check = {}) {
    const nlohmann::json* value = find(key);
    if (!value) return std::nullopt;
    return read<T>(key, *value, check);
  }

  template <class E>
  E choice(std::string_view key, const Choices<E>& choices) {
    return pick(key, required<std::string>(key), choices);
  }

  template <class E>
  E choice(std::string_view key, const Choices<E>& choices, E fallback) {
    std::optional<std::string> name = maybe<std::string>(key);
    return name ? pick(key, *name, choices) : fallback;
  }

  // `name` looked up in `choices`; an error at `key` when it is not one of them.
  template <class E>
  E pick(std::string_view key, const std::string& name, const Choices<E>& choices) const {
    for (const auto& [spelling, value] : choices)
      if (spelling == name) return value;
    std::string list;
    for (const auto& choice : choices)
      list += (list.empty() ? "\"" : ", \"") + std::string(choice.first) + "\"";
    fail(key, "must be one of " + list + " (got \"" + name + "\")");
  }

  // A nested object, read by parse(JsonReader&). An absent object reads as {}, so its own defaults apply
  // and its required keys are reported by their full path.
  template <class Parse>
  auto object(std::string_view key, Parse parse) {
    const nlohmann::json empty = nlohmann::json::object();
    const nlohmann::json* value = find(key);
    return readObject(key, value ? *value : empty, parse);
  }

  template <class Parse>
  auto optionalObject(std::string_view key, Parse parse) -> std::optional<decltype(parse(*this))> {
    const nlohmann::json* value = find(key);
    if (!value) return std::nullopt;
    return readObject(key, *value, parse);
  }

  // An array of objects, each read by parse(JsonReader&); absent reads as empty.
  template <class Parse>
  auto objects(std::string_view key, Parse parse, std::size_t minCount = 0,
               std::size_t maxCount = std::numeric_limits<std::size_t>::max()) {
    std::vector<decltype(parse(*this))> result;
    const nlohmann::json* value = find(key);
    if (!value) return result;
    if (!value->is_array()) failType(key, "an array of objects", *value);
    if (value->size() < minCount)
      fail(key, "needs at least " + std::to_string(minCount) + " elements (got " +
                    std::to_string(value->size()) + ")");
    if (value->size() > maxCount)
      fail(key, "at most " + std::to_string(maxCount) + " elements are supported (got " +
                    std::to_string(value->size()) + ")");
    for (std::size_t i = 0; i < value->size(); ++i)
      result.push_back(readObject(std::string(key) + "[" + std::to_string(i) + "]", (*value)[i], parse));
    return result;
  }

  template <class Parse>
  auto requiredObjects(std::string_view key, Parse parse, std::size_t minCount = 1) {
    if (!find(key)) failMissing(key);
    return objects(key, parse, minCount);
  }

  bool has(std::string_view key) { return find(key) != nullptr; }
  // For keys that take a number or a name ("voxels": 64 or "native").
  bool isString(std::string_view key) {
    const nlohmann::json* value = find(key);
    return value && value->is_string();
  }

  // An error if `key` is present: for keys that other settings make meaningless.
  void forbid(std::string_view key, std::string_view why);

  // An error naming the first key that was never asked for.
  void finish() const;

  [[noreturn]] void fail(std::string_view key, std::string_view problem) const;
  // An error about this object as a whole.
  [[noreturn]] void failHere(std::string_view problem) const;

 private:
  const nlohmann::json* find(std::string_view key);
  std::string pathOf(std::string_view key) const;
  [[noreturn]] void failMissing(std::string_view key) const;
  [[noreturn]] void failType(std::string_view key, std::string_view expected,
                             const nlohmann::json& got) const;

  template <class T, class Check>
  T read(std::string_view key, const nlohmann::json& value, const Check& check) const {
    std::optional<T> decoded = JsonDecode<T>::from(value);
    if (!decoded) failType(key, JsonDecode<T>::expected, value);
    if (std::string problem = check(*decoded); !problem.empty()) fail(key, problem);
    return *decoded;
  }

  template <class Parse>
  auto readObject(std::string_view key, const nlohmann::json& value, Parse parse) const {
    JsonReader child(value, pathOf(key), source_);
    auto result = parse(child);
    child.finish();
    return result;
  }

  const nlohmann::json& object_;
  std::string path_;
  std::string source_;
  std::set<std::string, std::less<>> known_;
};

}  // namespace sixway::io
