#pragma once
// Debian's Chromium, headless, driven over the Chrome DevTools Protocol (a
// WebSocket): one page opened on a URL, JavaScript evaluated in it, and
// screenshots decoded to RGBA pixels. For the view's browser tests.
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "child_process.hpp"
#include "ws_test_client.hpp"

namespace servoloop::testing {

struct RgbaImage {
  unsigned width = 0;
  unsigned height = 0;
  std::vector<std::uint8_t> pixels;  // width * height * 4
};

// Decodes a PNG (libpng); an empty image when it is not one.
RgbaImage decodePng(const std::string& png);
// Pixels whose colour differs by more than `threshold` (0..255, any channel).
std::size_t differingPixels(const RgbaImage& a, const RgbaImage& b, int threshold = 24);
// The smallest box holding every differing pixel, as "x0,y0-x1,y1" ("none").
std::string differingBox(const RgbaImage& a, const RgbaImage& b, int threshold = 24);

class ChromiumPage {
 public:
  static constexpr const char* kChromium = "/usr/bin/chromium";
  static bool available();

  // Starts Chromium headless with its own profile under `folder` (which
  // also holds its output) and opens `url` in a page of width x height.
  // Throws std::runtime_error when Chromium does not start or answer.
  ChromiumPage(const std::filesystem::path& folder, const std::string& url, int width, int height);
  ~ChromiumPage();  // closes the browser
  ChromiumPage(const ChromiumPage&) = delete;
  ChromiumPage& operator=(const ChromiumPage&) = delete;

  // The value of a JavaScript expression in the page (a promise is awaited);
  // null when it threw (exceptionText() says why).
  nlohmann::json evaluate(const std::string& expression);
  const std::string& exceptionText() const { return exception_; }
  // The page as a PNG, decoded.
  RgbaImage screenshot();
  // What Chromium printed (for failure messages).
  std::string log() const;

 private:
  nlohmann::json command(const std::string& method, const nlohmann::json& params, bool in_page = true);

  std::unique_ptr<ChildProcess> browser_;
  WsTestClient devtools_;
  std::string session_;
  std::int64_t next_id_ = 1;
  std::string exception_;
};

}  // namespace servoloop::testing
