#include "xml_element_reader.hpp"

#include <tinyxml.h>

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <sstream>

#include "pcr/core/error.hpp"

namespace pcr {
namespace {

// Parses one number covering the whole token; false for empty, partial or non-finite input.
bool parse_number(const std::string& token, double& value) {
  if (token.empty()) return false;
  char* end = nullptr;
  errno = 0;
  value = std::strtod(token.c_str(), &end);
  return errno == 0 && end == token.c_str() + token.size() && std::isfinite(value);
}

}  // namespace

XmlElementReader::XmlElementReader(const TiXmlElement& element, std::string source, std::string label)
    : element_(element), source_(std::move(source)), label_(std::move(label)) {}

bool XmlElementReader::has(const char* attribute) const {
  return element_.Attribute(attribute) != nullptr;
}

void XmlElementReader::fail(const char* attribute, const std::string& value,
                            const std::string& problem) const {
  throw_input_error(source_, ":", element_.Row(), ": ", label_, ": attribute '", attribute, "' = \"", value,
                    "\" ", problem);
}

void XmlElementReader::fail(const std::string& problem) const {
  throw_input_error(source_, ":", element_.Row(), ": ", label_, ": ", problem);
}

std::string XmlElementReader::text(const char* attribute) {
  const char* value = element_.Attribute(attribute);
  if (value == nullptr) fail(std::string("missing attribute '") + attribute + "'");
  read_.insert(attribute);
  return value;
}

std::string XmlElementReader::text_or(const char* attribute, const std::string& fallback) {
  return has(attribute) ? text(attribute) : fallback;
}

double XmlElementReader::number(const char* attribute) {
  const std::string value = text(attribute);
  std::istringstream stream(value);
  std::string token, extra;
  double x = 0.0;
  if (!(stream >> token) || (stream >> extra) || !parse_number(token, x))
    fail(attribute, value, "is not a finite number");
  return x;
}

double XmlElementReader::number_or(const char* attribute, double fallback) {
  return has(attribute) ? number(attribute) : fallback;
}

double XmlElementReader::positive(const char* attribute) {
  const double x = number(attribute);
  if (!(x > 0.0)) fail(attribute, text(attribute), "must be positive");
  return x;
}

double XmlElementReader::non_negative(const char* attribute) {
  const double x = number(attribute);
  if (!(x >= 0.0)) fail(attribute, text(attribute), "must be non-negative");
  return x;
}

int XmlElementReader::integer_or(const char* attribute, int fallback) {
  if (!has(attribute)) return fallback;
  const std::string value = text(attribute);
  char* end = nullptr;
  errno = 0;
  const long x = std::strtol(value.c_str(), &end, 10);
  if (value.empty() || errno != 0 || end != value.c_str() + value.size() || x < -1000000 || x > 1000000) {
    fail(attribute, value, "is not an integer");
  }
  return static_cast<int>(x);
}

bool XmlElementReader::boolean_or(const char* attribute, bool fallback) {
  if (!has(attribute)) return fallback;
  const std::string value = text(attribute);
  if (value == "true" || value == "1") return true;
  if (value == "false" || value == "0") return false;
  fail(attribute, value, "is not a boolean (true or false)");
}

Vec3 XmlElementReader::vec3(const char* attribute) {
  const std::string value = text(attribute);
  std::istringstream stream(value);
  Vec3 v;
  std::string token;
  for (int i = 0; i < 3; ++i) {
    if (!(stream >> token) || !parse_number(token, v[i]))
      fail(attribute, value, "is not three finite numbers");
  }
  if (stream >> token) fail(attribute, value, "has more than three numbers");
  return v;
}

Vec3 XmlElementReader::vec3_or(const char* attribute, const Vec3& fallback) {
  return has(attribute) ? vec3(attribute) : fallback;
}

std::string quoted(const std::string& kind, const std::string& name) {
  return kind + " '" + name + "'";
}

const TiXmlElement* single_child(const XmlElementReader& reader, const TiXmlElement& element,
                                 const char* name, bool required) {
  const TiXmlElement* child = element.FirstChildElement(name);
  if (child == nullptr && required) reader.fail(std::string("missing element <") + name + ">");
  if (child != nullptr && child->NextSiblingElement(name) != nullptr) {
    reader.fail(std::string("element <") + name + "> given more than once");
  }
  return child;
}

void XmlElementReader::finish() const {
  for (const TiXmlAttribute* a = element_.FirstAttribute(); a != nullptr; a = a->Next()) {
    if (read_.count(a->Name()) == 0) fail(a->Name(), a->Value(), "is not allowed here");
  }
}

}  // namespace pcr
