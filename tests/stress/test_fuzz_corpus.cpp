// Replays the model-loader fuzzing corpus (tests/data/fuzz_corpus: hand-written seeds and inputs kept
// from scripts/fuzz.sh runs): every file must either load or throw pcr::InputError with a message;
// any other exception (or a crash, caught by Boost.Test as a fatal error) is a loader bug.
#define BOOST_TEST_MODULE fuzz_corpus
#include <boost/test/unit_test.hpp>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <typeinfo>
#include <vector>

#include "pcr/core/error.hpp"
#include "pcr/robots/urdf_loader.hpp"

using namespace pcr;

BOOST_AUTO_TEST_CASE(every_corpus_file_loads_or_throws_input_error) {
  const std::filesystem::path dir = std::filesystem::path(PCR_TEST_DATA_DIR) / "fuzz_corpus";
  std::vector<std::filesystem::path> files;
  for (const auto& entry : std::filesystem::directory_iterator(dir))
    if (entry.is_regular_file()) files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  BOOST_REQUIRE_MESSAGE(!files.empty(), "empty corpus " << dir);
  int loaded = 0, rejected = 0;
  for (const auto& path : files) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream text;
    text << in.rdbuf();
    try {
      parse_robot_model(text.str(), path.filename().string());
      ++loaded;
    } catch (const InputError& e) {
      ++rejected;
      BOOST_TEST(std::string(e.what()).size() > 0, path.filename() << ": InputError without a message");
    } catch (const std::exception& e) {
      BOOST_ERROR(path.filename() << ": " << typeid(e).name() << " instead of InputError: " << e.what());
    } catch (...) {
      BOOST_ERROR(path.filename() << ": a non-std exception instead of InputError");
    }
  }
  BOOST_TEST_MESSAGE(files.size() << " corpus files: " << loaded << " loaded, " << rejected << " rejected");
  // The seeds include a valid model (seed_valid_clamped_platform.urdf): loading must still work.
  BOOST_TEST(loaded > 0);
}
