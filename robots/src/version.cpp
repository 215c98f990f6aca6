#include "pcr/robots/version.hpp"

namespace pcr {

const char* version() { return "0.1.0"; }

}  // namespace pcr
