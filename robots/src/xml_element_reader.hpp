#pragma once
// Private to pcr_robots: reads the attributes of one TinyXML element with error messages that name the
// source file, the line, the element and the attribute with its value. Attributes that were never read
// are rejected by finish(), so a misspelt attribute is an error rather than silently ignored.
#include <set>
#include <string>

#include "pcr/core/types.hpp"

class TiXmlElement;

namespace pcr {

class XmlElementReader {
 public:
  /// label names the element in messages, e.g. "pcr_rod 'leg3' <section>".
  XmlElementReader(const TiXmlElement& element, std::string source, std::string label);

  const std::string& label() const { return label_; }
  bool has(const char* attribute) const;
  std::string text(const char* attribute);  ///< required
  std::string text_or(const char* attribute, const std::string& fallback);
  double number(const char* attribute);  ///< required, finite
  double number_or(const char* attribute, double fallback);
  double positive(const char* attribute);      ///< required, > 0
  double non_negative(const char* attribute);  ///< required, >= 0
  int integer_or(const char* attribute, int fallback);
  bool boolean_or(const char* attribute, bool fallback);  ///< "true"/"false"/"1"/"0"
  Vec3 vec3(const char* attribute);                       ///< three numbers separated by spaces
  Vec3 vec3_or(const char* attribute, const Vec3& fallback);

  /// Throws InputError "<source>:<line>: <label>: attribute 'a' = "v" <problem>".
  [[noreturn]] void fail(const char* attribute, const std::string& value, const std::string& problem) const;
  /// Throws InputError "<source>:<line>: <label>: <problem>".
  [[noreturn]] void fail(const std::string& problem) const;
  /// Rejects any attribute that was not read.
  void finish() const;

 private:
  const TiXmlElement& element_;
  std::string source_;
  std::string label_;
  std::set<std::string> read_;
};

/// "kind 'name'", the way messages name an element.
std::string quoted(const std::string& kind, const std::string& name);
/// The child element `name` of element; fails through reader if it is required and missing, or repeated.
const TiXmlElement* single_child(const XmlElementReader& reader, const TiXmlElement& element,
                                 const char* name, bool required);

}  // namespace pcr
