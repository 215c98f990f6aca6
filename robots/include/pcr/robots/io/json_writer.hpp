#pragma once
// A small streaming JSON writer (RFC 8259) for results: objects, arrays, strings with full escaping,
// numbers with 17 significant digits (round-trip exact for double). JSON has no NaN or infinity: a
// non-finite number is written as null and counted (non_finite_count()), so callers can report it.
#include <cstdint>
#include <ostream>
#include <string>
#include <vector>

#include "pcr/core/types.hpp"

namespace pcr {

/// The JSON string literal of text, quotes included: ", \ and control characters are escaped
/// (\n, \t, ... or \u00XX); other bytes (UTF-8) pass through unchanged.
std::string json_quote(const std::string& text);

class JsonWriter {
 public:
  /// indent = spaces per nesting level; 0 writes everything on one line.
  explicit JsonWriter(std::ostream& out, int indent = 2);

  void begin_object();
  void end_object();
  void begin_array();
  void end_array();
  /// The key of the next member; only inside an object.
  void key(const std::string& name);
  void value(const std::string& text);
  void value(const char* text);
  void value(double number);  ///< null when not finite
  void value(int number);
  void value(std::int64_t number);   ///< exact (JSON readers into doubles round past 2^53)
  void value(std::uint64_t number);  ///< exact, as above
  void value(bool flag);
  void null();
  /// key(name), then value(v): one member of an object.
  template <typename T>
  void member(const std::string& name, const T& v) {
    key(name);
    value(v);
  }
  /// An array of numbers on one line, e.g. [1, 2, 3].
  void array(const VecX& numbers);
  void array(const Vec3& numbers) { array(VecX(numbers)); }

  /// Ends a top-level object: its last member "non_finite_values" (the nulls written so far, which
  /// stand for NaN or infinite numbers), the closing brace and a newline. Returns that count.
  int end_document();

  /// Objects and arrays open around the next value (0: it is the top-level value).
  int depth() const { return static_cast<int>(stack_.size()); }
  /// Numbers written as null because they were NaN or infinite.
  int non_finite_count() const { return non_finite_; }
  /// Whether every opened object/array was closed and one top-level value was written.
  bool complete() const { return stack_.empty() && wrote_top_; }

 private:
  void before_value();
  void newline();
  std::ostream& out_;
  int indent_;
  struct Level {
    bool object;
    int count;
    bool has_key;
  };
  std::vector<Level> stack_;
  bool wrote_top_ = false;
  bool inline_ = false;
  int non_finite_ = 0;
};

}  // namespace pcr
