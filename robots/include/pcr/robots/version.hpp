#pragma once

namespace pcr {

/// Library version "major.minor.patch".
const char* version();

}  // namespace pcr
