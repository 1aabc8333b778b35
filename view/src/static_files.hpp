#pragma once
// The files the view serves: the page, Debian's three.js, and the folders
// holding the scene's meshes (each mesh's ROS package or Gazebo model
// folder, else the mesh's own folder, so that its textures and .mtl files
// load too). A request for anything outside those folders is refused, with
// ".." and symbolic links resolved before the check. Thread-safe.
#include <filesystem>
#include <mutex>
#include <string>
#include <utility>
#include <vector>

#include "http_ws_server.hpp"

namespace servoloop::view {

class StaticFiles {
 public:
  // Serves `folder` under `url_prefix` (which starts and ends with '/').
  void addFolder(const std::string& url_prefix, const std::filesystem::path& folder);
  // The URL of a mesh file, its folder served under /files/<n>/ (the same
  // n for meshes of one package). Empty when the file does not exist.
  std::string meshUrl(const std::filesystem::path& mesh);
  // A GET of `path`: 200 with the file, 403 outside every served folder,
  // 404 when missing.
  HttpResponse get(const std::string& path) const;

  // The folder a mesh's relative references resolve in: the nearest folder
  // above it with a package.xml or model.config, else its own folder.
  static std::filesystem::path meshRoot(const std::filesystem::path& mesh);

 private:
  mutable std::mutex mutex_;
  std::vector<std::pair<std::string, std::filesystem::path>> folders_;  // prefix, canonical folder
  std::vector<std::filesystem::path> mesh_roots_;
};

// The media type of a file, by its extension (application/octet-stream
// for one the page does not need to know).
std::string mediaType(const std::filesystem::path& file);

}  // namespace servoloop::view
