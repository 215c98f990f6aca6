#pragma once
// Running the built pcr tool from the CLI tests (test_cli, test_cli_tools, ...): each source file defines
// PCR_CLI_WORK_DIRECTORY, its own directory under the system's temporary one, named with the process id
// (created at the first use, removed at exit), so that the executables, and two runs of one of them (two
// build trees tested on one machine), can run at the same time.
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#ifndef PCR_CLI_WORK_DIRECTORY
#error "define PCR_CLI_WORK_DIRECTORY (a directory name) before including cli_runner.hpp"
#endif

namespace {

namespace fs = std::filesystem;

struct Run {
  int exit_code = -1;
  std::string out, err;
};

std::string read_text(const fs::path& path) {
  std::ifstream file(path);
  std::ostringstream text;
  text << file.rdbuf();
  return text.str();
}

/// The test's work directory, removed with its contents when the process ends.
struct WorkDirectory {
  fs::path path;
  WorkDirectory()
      : path(fs::temp_directory_path() /
             (std::string(PCR_CLI_WORK_DIRECTORY) + "_" + std::to_string(getpid()))) {
    fs::remove_all(path);
    fs::create_directories(path);
  }
  ~WorkDirectory() {
    std::error_code ignored;
    fs::remove_all(path, ignored);
  }
};

fs::path work_directory() {
  static const WorkDirectory dir;
  return dir.path;
}

/// Runs the built pcr tool with the given arguments (shell words), capturing stdout and stderr; `prefix`
/// is run by the same shell first (e.g. a ulimit for the tool).
Run run_pcr(const std::string& arguments, const std::string& prefix = "") {
  const fs::path out = work_directory() / "stdout.txt", err = work_directory() / "stderr.txt";
  const std::string command =
      prefix + "'" + PCR_TOOL + "' " + arguments + " > '" + out.string() + "' 2> '" + err.string() + "'";
  const int status = std::system(command.c_str());
  Run run;
  run.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  run.out = read_text(out);
  run.err = read_text(err);
  return run;
}

[[maybe_unused]] std::string model(const std::string& name) {
  return std::string("'") + PCR_MODEL_DIR + "/" + name + "'";
}

[[maybe_unused]] bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

/// Writes text to a file of the work directory; returns its path, quoted for the shell.
[[maybe_unused]] std::string write_file(const std::string& name, const std::string& text) {
  const fs::path path = work_directory() / name;
  std::ofstream(path) << text;
  return "'" + path.string() + "'";
}

[[maybe_unused]] std::string number(double x) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.17g", x);
  return buffer;
}

}  // namespace
