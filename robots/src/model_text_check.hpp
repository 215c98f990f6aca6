#pragma once
// Private to pcr_robots: the first check of a model file's text, before any XML parser reads it.
#include <string>

namespace pcr {

/// Requires the text to be well-formed UTF-8 (RFC 3629: no truncated or overlong sequence, no
/// surrogate, nothing beyond U+10FFFF) made only of XML 1.0 characters (no NUL, no control character
/// other than tab, line feed and carriage return). Throws InputError "<source>:<line>:<column>: ..."
/// (the column counts characters from 1). TinyXML 2.6, which pcr and urdfdom parse with, steps over a
/// multi-byte sequence by the length its lead byte announces: a file that ends inside one (e.g. in the
/// lone byte 0xE9) makes it read past the end of the text.
void check_model_text(const std::string& text, const std::string& source);

}  // namespace pcr
