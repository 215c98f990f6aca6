// libFuzzer target for the model loader: any input must either load or throw pcr::InputError.
// Another exception escapes and libFuzzer reports it as a crash ("deadly signal" after abort), as it
// does for memory errors (ASan) and undefined behaviour (UBSan, no recovery). Build and run:
// scripts/fuzz.sh (docs/benchmarks.md, "Fuzzing the model loader").
#include <cstddef>
#include <cstdint>
#include <string>

#include "pcr/core/error.hpp"
#include "pcr/robots/urdf_loader.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string xml(reinterpret_cast<const char*>(data), size);
  try {
    pcr::parse_robot_model(xml, "fuzz.urdf");
  } catch (const pcr::InputError&) {
    // The documented outcome for a bad model.
  }
  return 0;
}
