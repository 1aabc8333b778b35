#pragma once
// xacro, expanded in-process (no Python): what `rosrun xacro xacro FILE
// name:=value` prints. Non-real-time (reads files, allocates, throws).
//
// Supported: <xacro:property> (value, default, block bodies, scope="parent" /
// "global"), <xacro:arg> with defaults and name:=value arguments,
// <xacro:include> (relative paths and $(find pkg), with ns=), <xacro:macro>
// with defaults, `^` / `^|default` forwarding and *block / **block parameters,
// nested macros, <xacro:call macro=>, <xacro:insert_block>, <xacro:if> /
// <xacro:unless>, <xacro:element> / <xacro:attribute>; `${...}` expressions
// (see the expression header) and `$(arg)`, `$(find)`, `$(env)`, `$(optenv)`,
// `$(dirname)`, `$(eval)`; `$${` and `$$(` escapes. The xacro prefix is any that
// the root element binds to xacro's namespace URI, and always `xacro:`.
#include <filesystem>
#include <map>
#include <string>

namespace servoloop {

using XacroArgs = std::map<std::string, std::string>;

// True for a path ending in `.xacro` (robot.urdf.xacro, robot.xacro).
bool isXacroPath(const std::filesystem::path& path);

// Expands the xacro file at `path` with `args` (name → value, as name:=value)
// and returns the URDF text. Throws ConfigError naming the file and line, the
// macro or property at fault, and saying it is xacro.
std::string expandXacroFile(const std::filesystem::path& path, const XacroArgs& args = {});

// Expands xacro text; `source_name` names it in errors and is where relative
// includes and $(find) start.
std::string expandXacro(const std::string& text, const std::string& source_name, const XacroArgs& args = {});

// The robot description in the file at `path`: the file's text, or, for a
// .xacro file, its expansion with `args`. Throws ConfigError when the file is
// missing or unreadable.
std::string readRobotDescription(const std::filesystem::path& path, const XacroArgs& args = {});

// Evaluates a Python expression as roslaunch's $(eval ...) does, with the
// arithmetic, comparisons, `and`/`or`/`not`, conditionals and math of xacro's
// ${...}: `names` are its variables, each a string (roslaunch's arguments are
// text), and arg('name') stands for the variable name. Returns Python's str()
// of the result ("True", "3.5", "left"). Throws ConfigError saying what is
// wrong with the expression.
std::string evaluatePythonExpression(const std::string& expression, const std::map<std::string, std::string>& names);

// Parses "name:=value" (as rosrun xacro takes it); throws ConfigError naming
// the text otherwise.
std::pair<std::string, std::string> parseXacroArg(const std::string& text);

}  // namespace servoloop
