#include "tests/support/run_command.hpp"

#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>

namespace fleetmerge::testing {
namespace {

std::string ReadWholeFile(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// An empty file of our own for the command's standard error (mkstemp: no name clash between
// tests running in parallel).
std::filesystem::path MakeStderrFile() {
  std::string name = (std::filesystem::temp_directory_path() / "fleetmerge_stderr_XXXXXX").string();
  const int fd = mkstemp(name.data());
  if (fd < 0) return {};
  close(fd);
  return name;
}

}  // namespace

std::string ShellQuote(const std::string& text) {
  std::string quoted = "'";
  for (char c : text) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return quoted + "'";
}

CommandResult RunCommand(const std::string& command) {
  CommandResult result;
  const std::filesystem::path err_file = MakeStderrFile();
  if (err_file.empty()) return result;
  const std::string line = "{ " + command + "\n} 2>" + ShellQuote(err_file);
  if (FILE* pipe = popen(line.c_str(), "r"); pipe != nullptr) {
    std::array<char, 4096> buffer;
    std::size_t n = 0;
    while ((n = std::fread(buffer.data(), 1, buffer.size(), pipe)) > 0) {
      result.out.append(buffer.data(), n);
    }
    const int status = pclose(pipe);
    result.exit_code = status != -1 && WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  }
  result.err = ReadWholeFile(err_file);
  std::error_code ec;
  std::filesystem::remove(err_file, ec);
  return result;
}

}  // namespace fleetmerge::testing
