#include "servoloop/core/xml_error_text.hpp"

#include <array>
#include <utility>

namespace servoloop {

std::string xmlErrorWords(std::string_view error_name, std::string_view detail) {
  // The element tinyxml2 names, when it names one ("...: XMLElement name=geometry").
  std::string element;
  if (const auto at = detail.rfind("name="); at != std::string_view::npos) {
    element = std::string(detail.substr(at + 5));
    while (!element.empty() && (element.back() == ' ' || element.back() == '\n')) element.pop_back();
  }
  const std::string tag = element.empty() ? "an element" : "element <" + element + ">";
  static constexpr std::array<std::pair<std::string_view, std::string_view>, 10> kWords{{
      {"XML_ERROR_PARSING_ELEMENT", "a tag is malformed or not closed (<name ...> or <name .../>)"},
      {"XML_ERROR_PARSING_ATTRIBUTE", "an attribute is malformed (write name=\"value\", with quotes)"},
      {"XML_ERROR_PARSING_TEXT", "text between tags cannot be read (a stray '<' or '&'? write &lt; or &amp;)"},
      {"XML_ERROR_PARSING_CDATA", "a <![CDATA[ section is not closed with ]]>"},
      {"XML_ERROR_PARSING_COMMENT", "a comment (<!-- ... -->) is not closed"},
      {"XML_ERROR_PARSING_DECLARATION", "a declaration (<?xml ... ?>) is malformed or not closed"},
      {"XML_ERROR_PARSING_UNKNOWN", "a <! ... > construct is not closed"},
      {"XML_ERROR_EMPTY_DOCUMENT", "there is no XML element in it (an empty file, or not XML)"},
      {"XML_ERROR_PARSING", "it cannot be read as XML"},
      {"XML_ELEMENT_DEPTH_EXCEEDED", "elements nest deeper than the XML reader allows (500 levels)"},
  }};
  if (error_name == "XML_ERROR_MISMATCHED_ELEMENT") {
    return tag + " is closed by an end tag of another name (or an end tag is missing)";
  }
  for (const auto& [name, text] : kWords) {
    if (name == error_name) return std::string(text);
  }
  return std::string(error_name) + (detail.empty() ? "" : " (" + std::string(detail) + ")");
}

}  // namespace servoloop
