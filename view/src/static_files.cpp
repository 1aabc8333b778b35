#include "static_files.hpp"

#include <algorithm>
#include <cctype>
#include <fstream>
#include <iterator>
#include <sstream>

namespace servoloop::view {

namespace fs = std::filesystem;

namespace {

// Whether `path` is `folder` or inside it (both canonical).
bool inside(const fs::path& path, const fs::path& folder) {
  auto p = path.begin();
  for (auto f = folder.begin(); f != folder.end(); ++f, ++p) {
    if (p == path.end() || *p != *f) return false;
  }
  return true;
}

std::string lower(std::string text) {
  std::transform(text.begin(), text.end(), text.begin(), [](unsigned char c) { return std::tolower(c); });
  return text;
}

}  // namespace

std::string mediaType(const fs::path& file) {
  const std::string extension = lower(file.extension().string());
  if (extension == ".html") return "text/html; charset=utf-8";
  if (extension == ".js") return "text/javascript; charset=utf-8";
  if (extension == ".css") return "text/css; charset=utf-8";
  if (extension == ".json") return "application/json";
  if (extension == ".png") return "image/png";
  if (extension == ".jpg" || extension == ".jpeg") return "image/jpeg";
  if (extension == ".svg") return "image/svg+xml";
  if (extension == ".dae") return "model/vnd.collada+xml";
  if (extension == ".obj" || extension == ".mtl") return "text/plain; charset=utf-8";
  if (extension == ".stl") return "model/stl";
  return "application/octet-stream";
}

void StaticFiles::addFolder(const std::string& url_prefix, const fs::path& folder) {
  std::error_code error;
  const fs::path canonical = fs::weakly_canonical(folder, error);
  std::lock_guard lock(mutex_);
  folders_.emplace_back(url_prefix, error ? folder : canonical);
}

fs::path StaticFiles::meshRoot(const fs::path& mesh) {
  for (fs::path folder = mesh.parent_path(); !folder.empty() && folder != folder.root_path();
       folder = folder.parent_path()) {
    std::error_code error;
    if (fs::exists(folder / "package.xml", error) || fs::exists(folder / "model.config", error)) return folder;
  }
  return mesh.parent_path();
}

std::string StaticFiles::meshUrl(const fs::path& mesh) {
  std::error_code error;
  const fs::path file = fs::weakly_canonical(mesh, error);
  if (error || !fs::is_regular_file(file, error)) return {};
  const fs::path root = meshRoot(file);
  std::lock_guard lock(mutex_);
  auto it = std::find(mesh_roots_.begin(), mesh_roots_.end(), root);
  std::size_t index = static_cast<std::size_t>(it - mesh_roots_.begin());
  if (it == mesh_roots_.end()) {
    mesh_roots_.push_back(root);
    folders_.emplace_back("/files/" + std::to_string(index) + "/", root);
  }
  std::string url = "/files/" + std::to_string(index) + "/";
  // Each part percent-encoded as a browser would need it.
  bool first = true;
  for (const fs::path& part : file.lexically_relative(root)) {
    if (!first) url += '/';
    first = false;
    for (unsigned char c : part.string()) {
      if (std::isalnum(c) || c == '-' || c == '_' || c == '.' || c == '~') {
        url += static_cast<char>(c);
      } else {
        static const char* hex = "0123456789ABCDEF";
        url += '%';
        url += hex[c >> 4];
        url += hex[c & 15];
      }
    }
  }
  return url;
}

HttpResponse StaticFiles::get(const std::string& path) const {
  fs::path folder;
  std::string relative;
  {
    std::lock_guard lock(mutex_);
    std::size_t best = 0;
    for (const auto& [prefix, served] : folders_) {
      if (path.rfind(prefix, 0) == 0 && prefix.size() > best) {
        best = prefix.size();
        folder = served;
        relative = path.substr(prefix.size());
      }
    }
  }
  if (folder.empty()) return {404, "text/plain; charset=utf-8", "not found: " + path + "\n"};
  if (relative.empty()) relative = "index.html";
  const fs::path lexical = (folder / relative).lexically_normal();
  std::error_code error;
  const fs::path file = fs::weakly_canonical(lexical, error);
  if (error || !inside(lexical, folder) || !inside(file, folder)) {
    return {403, "text/plain; charset=utf-8", "refused: " + path + " is outside the folders this view serves\n"};
  }
  if (!fs::is_regular_file(file, error)) return {404, "text/plain; charset=utf-8", "not found: " + path + "\n"};
  std::ifstream in(file, std::ios::binary);
  if (!in) return {404, "text/plain; charset=utf-8", "cannot read: " + path + "\n"};
  std::ostringstream body;
  body << in.rdbuf();
  return {200, mediaType(file), body.str()};
}

}  // namespace servoloop::view
