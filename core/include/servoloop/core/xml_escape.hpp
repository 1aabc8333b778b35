#pragma once
// Text for an XML attribute value or element content that servoloop writes
// (the URDF of an SDF model, MuJoCo's MJCF): & < > " ' as entities.
#include <string>
#include <string_view>

namespace servoloop {

inline std::string xmlEscape(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (const char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&apos;"; break;
      default: out += c;
    }
  }
  return out;
}

}  // namespace servoloop
