#include "chromium_page.hpp"

#include <png.h>

#include <fstream>
#include <stdexcept>
#include <thread>

namespace servoloop::testing {

using nlohmann::json;
namespace fs = std::filesystem;

namespace {

std::string base64Decode(const std::string& text) {
  static const std::string alphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  unsigned value = 0;
  int bits = -8;
  for (char c : text) {
    const auto index = alphabet.find(c);
    if (index == std::string::npos) continue;  // '=' and line breaks
    value = (value << 6) | static_cast<unsigned>(index);
    bits += 6;
    if (bits >= 0) {
      out.push_back(static_cast<char>((value >> bits) & 0xFF));
      bits -= 8;
    }
  }
  return out;
}

}  // namespace

RgbaImage decodePng(const std::string& png) {
  RgbaImage image;
  png_image reader{};
  reader.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_memory(&reader, png.data(), png.size())) return image;
  reader.format = PNG_FORMAT_RGBA;
  image.pixels.resize(PNG_IMAGE_SIZE(reader));
  if (!png_image_finish_read(&reader, nullptr, image.pixels.data(), 0, nullptr)) {
    png_image_free(&reader);
    return {};
  }
  image.width = reader.width;
  image.height = reader.height;
  return image;
}

std::size_t differingPixels(const RgbaImage& a, const RgbaImage& b, int threshold) {
  if (a.width != b.width || a.height != b.height) return a.width * a.height + b.width * b.height;
  std::size_t count = 0;
  for (std::size_t i = 0; i + 3 < a.pixels.size(); i += 4) {
    for (int c = 0; c < 3; ++c) {
      if (std::abs(int(a.pixels[i + c]) - int(b.pixels[i + c])) > threshold) {
        ++count;
        break;
      }
    }
  }
  return count;
}

std::string differingBox(const RgbaImage& a, const RgbaImage& b, int threshold) {
  if (a.width != b.width || a.height != b.height) return "sizes differ";
  unsigned x0 = a.width, y0 = a.height, x1 = 0, y1 = 0;
  for (unsigned y = 0; y < a.height; ++y) {
    for (unsigned x = 0; x < a.width; ++x) {
      const std::size_t i = (std::size_t(y) * a.width + x) * 4;
      for (int c = 0; c < 3; ++c) {
        if (std::abs(int(a.pixels[i + c]) - int(b.pixels[i + c])) > threshold) {
          x0 = std::min(x0, x), y0 = std::min(y0, y), x1 = std::max(x1, x), y1 = std::max(y1, y);
          break;
        }
      }
    }
  }
  if (x1 < x0) return "none";
  return std::to_string(x0) + "," + std::to_string(y0) + "-" + std::to_string(x1) + "," + std::to_string(y1);
}

bool ChromiumPage::available() { return fs::exists(kChromium); }

ChromiumPage::ChromiumPage(const fs::path& folder, const std::string& url, int width, int height) {
  const fs::path profile = folder / "chromium-profile";
  fs::create_directories(profile);
  ProcessOptions options;
  options.output_dir = folder;
  // WebGL with no GPU: Chromium's software renderer (SwiftShader through ANGLE).
  browser_ = std::make_unique<ChildProcess>(
      std::vector<std::string>{kChromium, "--headless=new", "--no-sandbox", "--no-first-run",
                               "--no-default-browser-check", "--disable-extensions", "--mute-audio",
                               "--use-angle=swiftshader", "--enable-unsafe-swiftshader",
                               "--remote-debugging-address=127.0.0.1", "--remote-debugging-port=0",
                               "--user-data-dir=" + profile.string(),
                               "--window-size=" + std::to_string(width) + "," + std::to_string(height),
                               "about:blank"},
      options);
  // Chromium writes the port it took and the browser's WebSocket path.
  const fs::path port_file = profile / "DevToolsActivePort";
  std::string port, path;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (std::chrono::steady_clock::now() < deadline) {
    std::ifstream in(port_file);
    if (in && std::getline(in, port) && std::getline(in, path) && !path.empty()) break;
    port.clear();
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  if (port.empty()) throw std::runtime_error("Chromium did not start: " + log());
  if (!devtools_.connect("ws://127.0.0.1:" + port + path)) {
    throw std::runtime_error("cannot reach Chromium's DevTools: " + devtools_.why());
  }
  const json target = command("Target.createTarget", {{"url", "about:blank"}}, false);
  const json attached =
      command("Target.attachToTarget", {{"targetId", target.at("targetId")}, {"flatten", true}}, false);
  session_ = attached.at("sessionId").get<std::string>();
  command("Emulation.setDeviceMetricsOverride",
          {{"width", width}, {"height", height}, {"deviceScaleFactor", 1}, {"mobile", false}});
  command("Page.navigate", {{"url", url}});
}

ChromiumPage::~ChromiumPage() {
  if (devtools_.isOpen()) {
    devtools_.send(json{{"id", next_id_++}, {"method", "Browser.close"}}.dump());
    browser_->wait(10.0);
  }
  devtools_.close();
}

json ChromiumPage::command(const std::string& method, const json& params, bool in_page) {
  const std::int64_t id = next_id_++;
  json message = {{"id", id}, {"method", method}, {"params", params}};
  if (in_page) message["sessionId"] = session_;
  if (!devtools_.send(message.dump())) throw std::runtime_error("DevTools connection lost sending " + method);
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (std::chrono::steady_clock::now() < deadline) {
    const auto text = devtools_.receive(std::chrono::milliseconds(500));
    if (!text) {
      if (!devtools_.isOpen()) throw std::runtime_error("Chromium closed its DevTools connection: " + log());
      continue;
    }
    const json reply = json::parse(*text, nullptr, false);
    if (!reply.is_object() || reply.value("id", std::int64_t{-1}) != id) continue;  // an event
    if (reply.contains("error")) throw std::runtime_error(method + ": " + reply["error"].dump());
    return reply.value("result", json::object());
  }
  throw std::runtime_error(method + ": no answer from Chromium in 60 s");
}

json ChromiumPage::evaluate(const std::string& expression) {
  const json result =
      command("Runtime.evaluate", {{"expression", expression}, {"returnByValue", true}, {"awaitPromise", true}});
  if (result.contains("exceptionDetails")) {
    exception_ = result["exceptionDetails"].dump();
    return nullptr;
  }
  exception_.clear();
  return result.at("result").value("value", json());
}

RgbaImage ChromiumPage::screenshot() {
  const json result = command("Page.captureScreenshot", {{"format", "png"}});
  return decodePng(base64Decode(result.at("data").get<std::string>()));
}

std::string ChromiumPage::log() const { return browser_ ? browser_->currentErr().substr(0, 4000) : std::string(); }

}  // namespace servoloop::testing
