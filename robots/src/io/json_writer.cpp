#include "pcr/robots/io/json_writer.hpp"

#include <cmath>
#include <cstdio>

#include "pcr/core/error.hpp"

namespace pcr {

std::string json_quote(const std::string& text) {
  std::string out = "\"";
  for (const char ch : text) {
    const unsigned char c = static_cast<unsigned char>(ch);
    switch (c) {
      case '"': out += "\\\""; break;
      case '\\': out += "\\\\"; break;
      case '\b': out += "\\b"; break;
      case '\f': out += "\\f"; break;
      case '\n': out += "\\n"; break;
      case '\r': out += "\\r"; break;
      case '\t': out += "\\t"; break;
      default:
        if (c < 0x20) {  // RFC 8259 §7: control characters must be escaped
          char buffer[8];
          std::snprintf(buffer, sizeof buffer, "\\u%04x", c);
          out += buffer;
        } else {
          out += ch;
        }
    }
  }
  return out + "\"";
}

JsonWriter::JsonWriter(std::ostream& out, int indent) : out_(out), indent_(indent) {
  require(indent >= 0, "JsonWriter: indent = ", indent, " must be >= 0");
}

void JsonWriter::newline() {
  if (indent_ == 0 || inline_) return;
  out_ << '\n' << std::string(stack_.size() * static_cast<size_t>(indent_), ' ');
}

void JsonWriter::before_value() {
  if (stack_.empty()) {
    require(!wrote_top_, "JsonWriter: a second top-level value");
    wrote_top_ = true;
    return;
  }
  Level& level = stack_.back();
  if (level.object) {
    require(level.has_key, "JsonWriter: a value inside an object needs a key first");
    level.has_key = false;
    return;
  }
  if (level.count++ > 0) out_ << (inline_ ? ", " : ",");
  newline();
}

void JsonWriter::key(const std::string& name) {
  require(!stack_.empty() && stack_.back().object && !stack_.back().has_key, "JsonWriter: key '", name,
          "' outside an object or after another key");
  Level& level = stack_.back();
  if (level.count++ > 0) out_ << ',';
  newline();
  out_ << json_quote(name) << (indent_ > 0 ? ": " : ":");
  level.has_key = true;
}

void JsonWriter::begin_object() {
  before_value();
  out_ << '{';
  stack_.push_back({true, 0, false});
}

void JsonWriter::begin_array() {
  before_value();
  out_ << '[';
  stack_.push_back({false, 0, false});
}

int JsonWriter::end_document() {
  const int count = non_finite_;  // counted before this member is written
  key("non_finite_values");
  value(count);
  end_object();
  out_ << "\n";
  return count;
}

void JsonWriter::end_object() {
  require(!stack_.empty() && stack_.back().object && !stack_.back().has_key,
          "JsonWriter: end_object without a matching begin_object");
  const bool empty = stack_.back().count == 0;
  stack_.pop_back();
  if (!empty) newline();
  out_ << '}';
}

void JsonWriter::end_array() {
  require(!stack_.empty() && !stack_.back().object, "JsonWriter: end_array without a matching begin_array");
  const bool empty = stack_.back().count == 0;
  stack_.pop_back();
  if (!empty) newline();
  out_ << ']';
}

void JsonWriter::value(const std::string& text) {
  before_value();
  out_ << json_quote(text);
}

void JsonWriter::value(const char* text) {
  value(std::string(text));
}

void JsonWriter::value(double number) {
  if (!std::isfinite(number)) {
    ++non_finite_;
    null();
    return;
  }
  before_value();
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.17g", number);  // 17 digits: the double round-trips exactly
  out_ << buffer;
}

void JsonWriter::value(int number) {
  before_value();
  out_ << number;
}

void JsonWriter::value(std::int64_t number) {
  before_value();
  out_ << number;
}

void JsonWriter::value(std::uint64_t number) {
  before_value();
  out_ << number;
}

void JsonWriter::value(bool flag) {
  before_value();
  out_ << (flag ? "true" : "false");
}

void JsonWriter::null() {
  before_value();
  out_ << "null";
}

void JsonWriter::array(const VecX& numbers) {
  begin_array();
  inline_ = true;
  for (int i = 0; i < numbers.size(); ++i) value(numbers[i]);
  inline_ = false;
  stack_.pop_back();
  out_ << ']';
}

}  // namespace pcr
