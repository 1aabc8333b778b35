#include "xacro_test_support.hpp"

#include <charconv>
#include <cstdio>
#include <sstream>
#include <stdexcept>
#include <vector>

#include <tinyxml2.h>

namespace servoloop::testing {
namespace {

// "0.1 0.2" → "0.1 0.2" with each number at 12 significant digits; text that
// is not all numbers stays as it is.
std::string canonicalValue(const std::string& text) {
  std::istringstream in(text);
  std::string word;
  std::vector<std::string> words;
  bool numbers = true;
  while (in >> word) {
    double value = 0.0;
    const auto result = std::from_chars(word.data(), word.data() + word.size(), value);
    if (result.ec != std::errc() || result.ptr != word.data() + word.size()) {
      numbers = false;
      break;
    }
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%.12g", value == 0.0 ? 0.0 : value);
    words.emplace_back(buffer);
  }
  if (!numbers || words.empty()) {
    const auto first = text.find_first_not_of(" \t\r\n");
    return first == std::string::npos ? "" : text.substr(first, text.find_last_not_of(" \t\r\n") - first + 1);
  }
  std::string out;
  for (const auto& w : words) out += (out.empty() ? "" : " ") + w;
  return out;
}

void canonical(const tinyxml2::XMLElement* element, std::string& out) {
  out += "<";
  out += element->Name();
  for (const auto* a = element->FirstAttribute(); a != nullptr; a = a->Next()) {
    out += " " + std::string(a->Name()) + "=\"" + canonicalValue(a->Value()) + "\"";
  }
  out += ">";
  for (const auto* node = element->FirstChild(); node != nullptr; node = node->NextSibling()) {
    if (const auto* child = node->ToElement()) {
      canonical(child, out);
    } else if (const auto* text = node->ToText()) {
      out += canonicalValue(text->Value());
    }
  }
  out += "</" + std::string(element->Name()) + ">";
}

}  // namespace

std::string canonicalXml(const std::string& xml) {
  tinyxml2::XMLDocument document;
  if (document.Parse(xml.c_str(), xml.size()) != tinyxml2::XML_SUCCESS || document.RootElement() == nullptr) {
    throw std::runtime_error("not XML: " + xml.substr(0, 200));
  }
  std::string out;
  canonical(document.RootElement(), out);
  return out;
}

}  // namespace servoloop::testing
