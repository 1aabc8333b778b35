#include "python_messages.hpp"

#include <cstdio>
#include <fstream>
#include <sstream>

namespace servoloop::ros1 {

namespace fs = std::filesystem;

namespace {

// What `python` prints for `code`, first line; empty when it fails.
std::string pythonSays(const fs::path& python, const std::string& code) {
  const std::string command = "'" + python.string() + "' -c '" + code + "' 2>/dev/null";
  FILE* pipe = ::popen(command.c_str(), "r");
  if (pipe == nullptr) return {};
  char buffer[4096];
  std::string out;
  while (std::fgets(buffer, sizeof buffer, pipe) != nullptr) out += buffer;
  const int status = ::pclose(pipe);
  if (status != 0) return {};
  if (const auto end = out.find('\n'); end != std::string::npos) out.resize(end);
  return out;
}

}  // namespace

PythonMessagesRegistration registerPythonMessages(const fs::path& program, const fs::path& python) {
  PythonMessagesRegistration result;
  std::error_code error;
  result.folder = fs::weakly_canonical(program.parent_path() / ".." / "share" / "servoloop" / "ros1" / "python", error);
  if (error || !fs::is_directory(result.folder / "controller_manager_msgs", error)) {
    result.why_not = "servoloop's generated Python messages are not in " + result.folder.string();
    return result;
  }
  const std::string site =
      pythonSays(python, "import site; print(site.getusersitepackages() if site.ENABLE_USER_SITE else \"\")");
  if (site.empty()) {
    result.why_not = python.string() + " reads no user site-packages (PYTHONNOUSERSITE, or a virtual environment)";
    return result;
  }
  result.pth = fs::path(site) / "servoloop_ros1_messages.pth";
  const std::string wanted = result.folder.string() + "\n";
  {
    std::ifstream in(result.pth);
    std::stringstream text;
    text << in.rdbuf();
    if (in && text.str() == wanted) {
      result.registered = true;
      return result;
    }
  }
  fs::create_directories(result.pth.parent_path(), error);
  // Written whole, then moved into place: a Python starting meanwhile reads
  // the old file or the new one.
  const fs::path staging = result.pth.string() + ".tmp";
  {
    std::ofstream out(staging, std::ios::trunc);
    out << wanted;
    if (!out) {
      result.why_not = "cannot write " + staging.string();
      return result;
    }
  }
  fs::rename(staging, result.pth, error);
  if (error) {
    result.why_not = "cannot write " + result.pth.string() + ": " + error.message();
    return result;
  }
  result.registered = true;
  result.written = true;
  return result;
}

}  // namespace servoloop::ros1
