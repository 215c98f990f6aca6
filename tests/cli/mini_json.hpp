#pragma once
// A tiny JSON reader for the tests (RFC 8259 grammar; \u escapes below U+0080 only), written here
// so that the writer's output is checked by an independent parser. Throws std::runtime_error.
#include <cstdlib>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace test_json {

struct Value {
  enum class Type { Null, Bool, Number, String, Array, Object } type = Type::Null;
  bool boolean = false;
  double number = 0.0;
  std::string text;
  std::vector<Value> items;
  std::map<std::string, Value> members;

  bool has(const std::string& key) const { return type == Type::Object && members.count(key) > 0; }
  const Value& operator[](const std::string& key) const {
    const auto it = members.find(key);
    if (type != Type::Object || it == members.end()) throw std::runtime_error("no member '" + key + "'");
    return it->second;
  }
  const Value& operator[](size_t i) const {
    if (type != Type::Array || i >= items.size()) throw std::runtime_error("no item " + std::to_string(i));
    return items[i];
  }
};

class Parser {
 public:
  explicit Parser(const std::string& text) : s_(text) {}
  Value parse() {
    Value v = value();
    skip();
    if (i_ != s_.size()) fail("text after the value");
    return v;
  }

 private:
  [[noreturn]] void fail(const std::string& what) {
    throw std::runtime_error("JSON: " + what + " at offset " + std::to_string(i_));
  }
  void skip() {
    while (i_ < s_.size() && (s_[i_] == ' ' || s_[i_] == '\n' || s_[i_] == '\r' || s_[i_] == '\t')) ++i_;
  }
  bool literal(const char* word) {
    const std::string w(word);
    if (s_.compare(i_, w.size(), w) != 0) return false;
    i_ += w.size();
    return true;
  }
  std::string string() {
    if (s_[i_] != '"') fail("expected a string");
    ++i_;
    std::string out;
    while (true) {
      if (i_ >= s_.size()) fail("unterminated string");
      const char c = s_[i_++];
      if (c == '"') return out;
      if (static_cast<unsigned char>(c) < 0x20) fail("raw control character in a string");
      if (c != '\\') {
        out += c;
        continue;
      }
      if (i_ >= s_.size()) fail("bad escape");
      const char e = s_[i_++];
      switch (e) {
        case '"': out += '"'; break;
        case '\\': out += '\\'; break;
        case '/': out += '/'; break;
        case 'b': out += '\b'; break;
        case 'f': out += '\f'; break;
        case 'n': out += '\n'; break;
        case 'r': out += '\r'; break;
        case 't': out += '\t'; break;
        case 'u': {
          if (i_ + 4 > s_.size()) fail("short \\u escape");
          const long code = std::strtol(s_.substr(i_, 4).c_str(), nullptr, 16);
          if (code >= 0x80) fail("\\u escape above U+007F not supported by this test parser");
          out += static_cast<char>(code);
          i_ += 4;
          break;
        }
        default: fail("bad escape");
      }
    }
  }
  Value value() {
    skip();
    if (i_ >= s_.size()) fail("unexpected end");
    Value v;
    const char c = s_[i_];
    if (c == '{') {
      v.type = Value::Type::Object;
      ++i_;
      skip();
      if (s_[i_] == '}') {
        ++i_;
        return v;
      }
      while (true) {
        skip();
        const std::string key = string();
        skip();
        if (s_[i_++] != ':') fail("expected ':'");
        if (v.members.count(key)) fail("duplicate key '" + key + "'");
        v.members[key] = value();
        skip();
        const char d = s_[i_++];
        if (d == '}') return v;
        if (d != ',') fail("expected ',' or '}'");
      }
    }
    if (c == '[') {
      v.type = Value::Type::Array;
      ++i_;
      skip();
      if (s_[i_] == ']') {
        ++i_;
        return v;
      }
      while (true) {
        v.items.push_back(value());
        skip();
        const char d = s_[i_++];
        if (d == ']') return v;
        if (d != ',') fail("expected ',' or ']'");
      }
    }
    if (c == '"') {
      v.type = Value::Type::String;
      v.text = string();
      return v;
    }
    if (literal("null")) return v;
    if (literal("true") || literal("false")) {
      v.type = Value::Type::Bool;
      v.boolean = s_[i_ - 1] == 'e' && s_[i_ - 2] == 'u';
      return v;
    }
    // number: -? int frac? exp?  (strtod accepts more, e.g. "nan", so check the first character)
    if (c != '-' && (c < '0' || c > '9')) fail("unexpected character");
    const char* begin = s_.c_str() + i_;
    char* end = nullptr;
    v.type = Value::Type::Number;
    v.number = std::strtod(begin, &end);
    if (end == begin) fail("bad number");
    i_ += static_cast<size_t>(end - begin);
    return v;
  }
  const std::string& s_;
  size_t i_ = 0;
};

inline Value parse(const std::string& text) {
  return Parser(text).parse();
}

}  // namespace test_json
