// Replays the model-loader fuzzing corpus (tests/data/fuzz_corpus: hand-written seeds and inputs kept
// from scripts/fuzz.sh runs): every file must either load or throw pcr::InputError with a message;
// any other exception (or a crash, caught by Boost.Test as a fatal error; a read past the end of the
// text under the sanitizer build) is a loader bug. Names: seed_valid_* are valid models; crash_* are
// inputs that crashed the loader once, and seed_inertial_* malformed <inertial> elements, which must be
// rejected with pcr's own message (file and line).
#define BOOST_TEST_MODULE fuzz_corpus
#include <boost/test/unit_test.hpp>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <typeinfo>
#include <vector>

#include "pcr/core/error.hpp"
#include "pcr/robots/urdf_loader.hpp"

using namespace pcr;

namespace {

std::vector<std::filesystem::path> corpus_files() {
  const std::filesystem::path dir = std::filesystem::path(PCR_TEST_DATA_DIR) / "fuzz_corpus";
  std::vector<std::filesystem::path> files;
  for (const auto& entry : std::filesystem::directory_iterator(dir))
    if (entry.is_regular_file()) files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  BOOST_REQUIRE_MESSAGE(!files.empty(), "empty corpus " << dir);
  return files;
}

std::string read_text(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

bool starts_with(const std::string& text, const std::string& prefix) {
  return text.compare(0, prefix.size(), prefix) == 0;
}

}  // namespace

BOOST_AUTO_TEST_CASE(every_corpus_file_loads_or_throws_input_error) {
  const std::vector<std::filesystem::path> files = corpus_files();
  int loaded = 0, rejected = 0;
  for (const auto& path : files) {
    try {
      parse_robot_model(read_text(path), path.filename().string());
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

BOOST_AUTO_TEST_CASE(kept_crashes_and_malformed_inertials_are_rejected_with_file_and_line) {
  int checked = 0, valid = 0;
  for (const auto& path : corpus_files()) {
    const std::string name = path.filename().string();
    if (starts_with(name, "seed_valid_")) {
      BOOST_CHECK_NO_THROW(parse_robot_model(read_text(path), name));
      ++valid;
      continue;
    }
    if (!starts_with(name, "crash_") && !starts_with(name, "seed_inertial_")) continue;
    ++checked;
    try {
      parse_robot_model(read_text(path), name);
      BOOST_ERROR(name << " loaded");
    } catch (const InputError& e) {
      // "<file>:<line>:" with a line number: pcr's own message, not urdfdom's log.
      const std::string message = e.what();
      BOOST_TEST((starts_with(message, name + ":") && message.size() > name.size() + 1 &&
                  std::isdigit(static_cast<unsigned char>(message[name.size() + 1]))),
                 name << ": " << message);
    }
  }
  // The corpus holds the two truncated-UTF-8 inputs, ten malformed inertials and two valid seeds.
  BOOST_TEST(checked >= 12);
  BOOST_TEST(valid >= 2);
}
