#pragma once
// Bad input and misuse throw pcr::InputError (a std::invalid_argument) with a message that names the
// offending file / element / parameter and its value. Solver outcomes are never exceptions (see
// pcr/solve/solve_summary.hpp).
#include <sstream>
#include <stdexcept>
#include <string>

namespace pcr {

class InputError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

/// Builds a message from streamable parts: throw_input_error("rod '", name, "': radius = ", r, " <= 0").
template <typename... Parts>
[[noreturn]] void throw_input_error(const Parts&... parts) {
  std::ostringstream message;
  (message << ... << parts);
  throw InputError(message.str());
}

/// Throws InputError with the given parts unless condition holds.
template <typename... Parts>
void require(bool condition, const Parts&... parts) {
  if (!condition) throw_input_error(parts...);
}

}  // namespace pcr
