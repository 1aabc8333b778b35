#pragma once
// tinyxml2's parse errors in words a user can act on. tinyxml2 reports
// "Error=XML_ERROR_PARSING_COMMENT ErrorID=10 (0xa) Line number=72"; this
// turns it into "line 72: a comment (<!-- ... -->) is not closed".
#include <string>
#include <string_view>

namespace servoloop {

// error_name: XMLDocument::ErrorName(); line: ErrorLineNum(); detail:
// ErrorStr(), whose "name=..." part (the element concerned) is kept.
std::string xmlErrorText(std::string_view error_name, int line, std::string_view detail);

}  // namespace servoloop
