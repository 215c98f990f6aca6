#include "model_text_check.hpp"

#include <cstddef>
#include <cstdint>
#include <cstdio>

#include "pcr/core/error.hpp"

namespace pcr {
namespace {

std::string byte_name(unsigned char byte) {
  char text[8];
  std::snprintf(text, sizeof text, "0x%02X", static_cast<unsigned>(byte));
  return text;
}

std::string code_point_name(std::uint32_t code) {
  char text[16];
  std::snprintf(text, sizeof text, "U+%04X", static_cast<unsigned>(code));
  return text;
}

// XML 1.0 (5th ed.) production [2] Char.
bool is_xml_char(std::uint32_t code) {
  return code == 0x9 || code == 0xA || code == 0xD || (code >= 0x20 && code <= 0xD7FF) ||
         (code >= 0xE000 && code <= 0xFFFD) || (code >= 0x10000 && code <= 0x10FFFF);
}

// Sequence length announced by a lead byte (RFC 3629 table in section 4), 0 if it cannot start one.
int sequence_length(unsigned char lead) {
  if (lead < 0x80) return 1;
  if (lead >= 0xC2 && lead <= 0xDF) return 2;
  if (lead >= 0xE0 && lead <= 0xEF) return 3;
  if (lead >= 0xF0 && lead <= 0xF4) return 4;
  return 0;  // continuation byte 0x80-0xBF, overlong lead 0xC0/0xC1, or beyond U+10FFFF (0xF5-0xFF)
}

}  // namespace

void check_model_text(const std::string& text, const std::string& source) {
  long line = 1, column = 1;
  const auto fail = [&](const std::string& problem) {
    throw_input_error(source, ":", line, ":", column, ": ", problem,
                      " (a model file is XML 1.0 text in UTF-8)");
  };
  const std::size_t size = text.size();
  for (std::size_t i = 0; i < size;) {
    const unsigned char lead = static_cast<unsigned char>(text[i]);
    const int length = sequence_length(lead);
    if (length == 0) {
      fail("byte " + byte_name(lead) +
           (lead < 0xC0 ? " is a UTF-8 continuation byte without a lead byte" : " never occurs in UTF-8"));
    }
    std::uint32_t code = length == 1 ? lead : lead & (0xFFu >> (length + 1));
    for (int k = 1; k < length; ++k) {
      const std::string sequence =
          "the " + std::to_string(length) + "-byte UTF-8 sequence that starts with byte " + byte_name(lead);
      if (i + k >= size) fail(sequence + " is cut off by the end of the file");
      const unsigned char next = static_cast<unsigned char>(text[i + k]);
      if ((next & 0xC0) != 0x80) {
        fail(sequence + " is cut off: byte " + byte_name(next) + " is not a continuation byte");
      }
      code = (code << 6) | (next & 0x3Fu);
    }
    static const std::uint32_t smallest[5] = {0, 0, 0x80, 0x800, 0x10000};
    if (code < smallest[length]) fail("overlong UTF-8 encoding of " + code_point_name(code));
    if (code >= 0xD800 && code <= 0xDFFF)
      fail(code_point_name(code) + " is a UTF-16 surrogate, not a character");
    if (code > 0x10FFFF) fail(code_point_name(code) + " lies beyond U+10FFFF");
    if (code == 0) fail("NUL byte");  // the parsers would stop reading there
    if (!is_xml_char(code)) fail("character " + code_point_name(code) + " is not allowed in XML 1.0");
    if (code == '\n') {
      ++line;
      column = 1;
    } else {
      ++column;
    }
    i += static_cast<std::size_t>(length);
  }
}

}  // namespace pcr
