#pragma once
// tinyxml2's parse errors in words a user can act on. tinyxml2 reports
// "Error=XML_ERROR_PARSING_COMMENT ErrorID=10 (0xa) Line number=72"; this
// turns it into "a comment (<!-- ... -->) is not closed" (callers give the
// line, XMLDocument::ErrorLineNum(), in their own form).
#include <string>
#include <string_view>

namespace servoloop {

// error_name: XMLDocument::ErrorName(); detail: ErrorStr(), whose "name=..."
// part (the element concerned) is kept.
std::string xmlErrorWords(std::string_view error_name, std::string_view detail);

}  // namespace servoloop
