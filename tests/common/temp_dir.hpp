#pragma once
// A fresh, private (0700) folder under the system temporary folder, named
// <prefix>-XXXXXX by mkdtemp and removed with everything in it when the object
// dies. Tests that write files each take one, so two runs of the suite on one
// machine never share a path.
#include <filesystem>
#include <string>

namespace servoloop::testing {

class TempDir {
 public:
  explicit TempDir(const std::string& prefix = "servoloop-test");
  ~TempDir();
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;

  const std::filesystem::path& path() const { return path_; }
  // path() / name, as a string.
  std::string file(const std::string& name) const { return (path_ / name).string(); }

 private:
  std::filesystem::path path_;
};

// The whole content of a file ("" when it cannot be read).
std::string readFile(const std::filesystem::path& path);
// Writes `content` to `path`, replacing it (its folders are made as needed).
void writeFile(const std::filesystem::path& path, const std::string& content);

}  // namespace servoloop::testing
