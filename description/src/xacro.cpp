#include "servoloop/description/xacro.hpp"

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <map>
#include <memory>
#include <optional>
#include <regex>
#include <set>
#include <sstream>
#include <vector>

#include <tinyxml2.h>
#include <yaml-cpp/depthguard.h>
#include <yaml-cpp/yaml.h>

#include "servoloop/core/errors.hpp"
#include "servoloop/core/logging.hpp"
#include "servoloop/core/text_file.hpp"
#include "servoloop/core/xml_error_text.hpp"
#include "servoloop/description/package_path.hpp"
#include "servoloop/params/parameter_store.hpp"
#include "xacro_expression.hpp"

namespace servoloop {
namespace fs = std::filesystem;
namespace {

using tinyxml2::XMLDocument;
using tinyxml2::XMLElement;
using tinyxml2::XMLNode;
using xacro::ExpressionError;
using xacro::LimitError;
using xacro::RecursionLevel;
using xacro::shortened;
using xacro::Value;

// Macro calls and includes nest at most this deep (a macro calling itself
// without end stops here), and an expansion makes at most this many nodes (a
// few macros calling each other twice over would otherwise fill the memory).
constexpr int kMaxNesting = 100;
constexpr std::size_t kMaxOutputNodes = 2'000'000;
// A property defined through another (p1 = ${p0 + 1}) evaluates that one
// first, recursively: a chain of them is at most this long (Python's xacro
// stops near here too, at its recursion limit). Properties evaluated where
// they are defined (lazy_eval="false") make no chain.
constexpr std::size_t kMaxPropertyChain = 100;
// $(...) inside $(...) (as in $(find $(arg package))) nests at most this deep.
constexpr int kMaxSubstitutionNesting = 20;

// A block: a macro's *name / **name parameter (already expanded in the caller)
// or a <xacro:property> with a body (expanded where it is inserted).
struct Block {
  const XMLElement* holder = nullptr;
  bool contents_only = false;
  bool expanded = false;
};

struct Property {
  std::optional<std::string> text;  // not evaluated yet (xacro evaluates on first use)
  std::optional<Value> value;
  std::optional<Block> block;
  bool evaluating = false;
};

struct File {
  std::string name;
  fs::path dir;
  std::set<std::string> prefixes;  // element prefixes bound to xacro's namespace
};

struct Macro {
  struct Param {
    std::string name;
    int stars = 0;  // 1: *block, 2: **block contents
    std::optional<std::string> default_text;
    bool forward = false;  // ^: the caller's property of the same name
  };
  std::string name;
  std::vector<Param> params;
  const XMLElement* body = nullptr;
  File file;
};

// xacro scopes are dynamic: a macro body sees its parameters, then the
// properties where it is called.
struct Scope {
  Scope* parent = nullptr;
  std::map<std::string, Property> properties;
  std::map<std::string, std::shared_ptr<const Macro>> macros;
  std::map<std::string, Scope*> namespaces;
};

std::string readFile(const fs::path& path, const std::string& what) { return readTextFile(path, what); }

bool isXacroNamespace(const std::string& uri) { return uri.find("ros.org/wiki/xacro") != std::string::npos; }

std::set<std::string> xacroPrefixes(const XMLElement* root) {
  std::set<std::string> prefixes{"xacro"};
  for (const auto* a = root->FirstAttribute(); a != nullptr; a = a->Next()) {
    const std::string name = a->Name();
    if (name.rfind("xmlns:", 0) == 0 && isXacroNamespace(a->Value())) prefixes.insert(name.substr(6));
  }
  return prefixes;
}

Value literalized(Value v) { return v.kind == Value::Kind::String ? xacro::literal(v.text) : v; }

// A YAML document's values. Maps and sequences nest at most kMaxValueDepth
// deep (checked before going down, so the recursion is never deeper).
Value fromYaml(const YAML::Node& node, int depth = 0) {
  const bool collection = node.Type() == YAML::NodeType::Map || node.Type() == YAML::NodeType::Sequence;
  if (collection && depth >= xacro::kMaxValueDepth) {
    throw ExpressionError("line " + std::to_string(node.Mark().line + 1) + ": maps and lists nest more than " +
                          std::to_string(xacro::kMaxValueDepth) + " levels deep, deeper than xacro's values go (" +
                          std::to_string(xacro::kMaxValueDepth) + " levels); no robot's YAML comes near that");
  }
  switch (node.Type()) {
    case YAML::NodeType::Map: {
      Value::DictItems items;
      for (const auto& kv : node) items.emplace_back(kv.first.Scalar(), fromYaml(kv.second, depth + 1));
      return Value::ofDict(std::move(items));
    }
    case YAML::NodeType::Sequence: {
      std::vector<Value> items;
      for (const auto& item : node) items.push_back(fromYaml(item, depth + 1));
      return Value::ofList(std::move(items));
    }
    case YAML::NodeType::Scalar: return node.Tag() == "!" ? Value::ofString(node.Scalar()) : xacro::literal(node.Scalar());
    default: return Value::none();
  }
}

// The offset of the first byte of `text` that cannot be in a YAML file (YAML is
// UTF-8 text: no bytes outside UTF-8, no control characters but tab and line
// breaks), or nullopt.
std::optional<std::size_t> notYamlText(const std::string& text) {
  std::optional<std::size_t> offset = invalidUtf8Offset(text);
  for (std::size_t i = 0; i < offset.value_or(text.size()); ++i) {
    const auto byte = static_cast<unsigned char>(text[i]);
    if ((byte < 0x20 && byte != '\t' && byte != '\n' && byte != '\r') || byte == 0x7F) return i;
  }
  return offset;
}

std::string trim(const std::string& s) {
  const auto first = s.find_first_not_of(" \t\r\n");
  if (first == std::string::npos) return "";
  return s.substr(first, s.find_last_not_of(" \t\r\n") - first + 1);
}

class Expander : public xacro::Names {
 public:
  explicit Expander(XacroArgs args) : args_(std::move(args)), given_(args_) {}

  std::string run(const std::string& text, const std::string& source_name) {
    const XMLDocument& input = parse(text, source_name);
    const XMLElement* root = input.RootElement();
    File file{source_name, fs::path(source_name).parent_path(), xacroPrefixes(root)};
    if (file.dir.empty()) file.dir = fs::current_path();
    files_.push_back(file);
    Scope& global = newScope(nullptr);
    output_.InsertEndChild(output_.NewDeclaration());
    output_.InsertEndChild(output_.NewComment((" expanded by servoloop xacro from " + source_name + " ").c_str()));
    XMLElement* out_root = output_.NewElement(root->Name());
    output_.InsertEndChild(out_root);
    guarded(root, [&] {
      copyAttributes(root, out_root, global);
      expandChildren(root, out_root, global);
    });
    warnUnusedArguments(source_name);
    tinyxml2::XMLPrinter printer;
    output_.Print(&printer);
    return printer.CStr();
  }

  // An argument given on the command line that no file declares or reads is
  // most likely misspelt: xacro ignores it, servoloop says so.
  void warnUnusedArguments(const std::string& source_name) const {
    std::string declared;
    for (const auto& name : known_args_) declared += (declared.empty() ? "" : ", ") + name;
    for (const auto& [name, value] : given_) {
      if (known_args_.count(name) != 0) continue;
      logger().warn("{}: xacro argument {}:={} is ignored: no <xacro:arg name=\"{}\"> and no $(arg {}) in the files "
                    "(their arguments: {}); check its name",
                    source_name, name, value, name, name, declared.empty() ? "none" : declared);
    }
  }

  // xacro::Names
  std::optional<Value> lookup(const std::string& name) override { return lookupIn(*current_, name); }

  // The file is refused, with one error naming it (the caller adds the xacro
  // file and line), when it is not text, not YAML, holds more values than a
  // parameter file may once its aliases are expanded (params::kMaxYamlNodes:
  // a few lines of anchors and aliases can stand for billions), or nests
  // deeper than xacro's values.
  Value loadYaml(const std::string& file) override {
    fs::path path = file;
    if (path.is_relative()) path = files_.back().dir / path;
    const std::string call = "load_yaml('" + shortened(file) + "'): ";
    const std::string yaml_file = path.string();
    std::string text;
    try {
      text = readFile(path, "YAML file");
    } catch (const ConfigError& e) {
      throw ExpressionError(call + e.what());
    }
    if (const auto offset = notYamlText(text)) {
      char hex[8];
      std::snprintf(hex, sizeof hex, "0x%02X", static_cast<unsigned char>(text[*offset]));
      throw ExpressionError(call + yaml_file + ": byte " + std::to_string(*offset) + " (" + hex +
                            ") is not text, and a YAML file is UTF-8 text; is it the file you meant?");
    }
    YAML::Node document;
    try {
      document = YAML::Load(text);
    } catch (const YAML::DeepRecursion& e) {
      // yaml-cpp stops at a fixed depth with "bad file", which reads as a
      // syntax error; e.depth() is the level refused, one past the limit.
      throw ExpressionError(call + yaml_file + ": the YAML nests deeper than yaml-cpp's limit of " +
                            std::to_string(e.depth() - 1) + " levels" +
                            (e.mark.is_null() ? "" : " (at line " + std::to_string(e.mark.line + 1) + ")") +
                            "; no YAML file for load_yaml needs that: flatten it");
    } catch (const YAML::Exception& e) {
      const std::string at = e.mark.is_null() ? "" : ":" + std::to_string(e.mark.line + 1) + ":" +
                                                         std::to_string(e.mark.column + 1);
      throw ExpressionError(call + yaml_file + at + ": not valid YAML: " + e.msg +
                            "; fix the syntax there (indentation, a ':' after each key, closed brackets and quotes)");
    }
    try {
      params::checkYamlSize(document, yaml_file);
    } catch (const ConfigError& e) {
      throw ExpressionError(call + e.what());
    }
    try {
      return fromYaml(document);
    } catch (const ExpressionError& e) {
      throw ExpressionError(call + yaml_file + ": " + e.what());
    }
  }

 private:
  const XMLDocument& parse(const std::string& text, const std::string& name) {
    auto document = std::make_unique<XMLDocument>();
    if (document->Parse(text.c_str(), text.size()) != tinyxml2::XML_SUCCESS) {
      throw ConfigError(name + ":" + std::to_string(document->ErrorLineNum()) + ": xacro: not well-formed XML (" +
                        xmlErrorWords(document->ErrorName(), document->ErrorStr()) + ")");
    }
    if (document->RootElement() == nullptr) throw ConfigError(name + ": xacro: the file has no root element");
    names_[document.get()] = name;
    documents_.push_back(std::move(document));
    return *documents_.back();
  }

  Scope& newScope(Scope* parent) {
    scopes_.push_back(std::make_unique<Scope>());
    scopes_.back()->parent = parent;
    return *scopes_.back();
  }

  [[noreturn]] void fail(const XMLNode* where, const std::string& message) const {
    std::string location = files_.back().name;
    if (where != nullptr) {
      const auto it = names_.find(where->GetDocument());
      if (it != names_.end()) location = it->second + ":" + std::to_string(where->GetLineNum());
    }
    std::string text = location + ": xacro: " + message;
    for (auto it = calls_.rbegin(); it != calls_.rend(); ++it) text += "; in " + *it;
    throw ConfigError(text);
  }

  template <typename F>
  void guarded(const XMLElement* element, F&& f) {
    try {
      f();
    } catch (const ExpressionError& e) {
      fail(element, e.what());
    }
  }

  // ----- properties and names -----

  // The scope of namespace `head` as seen from `scope`, or nullptr.
  static Scope* namespaceIn(Scope& scope, const std::string& head) {
    for (Scope* s = &scope; s != nullptr; s = s->parent) {
      if (auto it = s->namespaces.find(head); it != s->namespaces.end()) return it->second;
    }
    return nullptr;
  }

  // A property by name, or `ns.name` in the namespace of <xacro:include ns="ns">.
  // (A dict's keys after the name, cfg.joints.max, are the expression's to read.)
  // A loop, not a recursion: a namespace may hold itself (a.a.a...). It goes
  // through no more namespaces than includes nest (each step reads the rest
  // of the name, so a long a.a.a... would otherwise cost its square).
  std::optional<Value> lookupIn(Scope& start, const std::string& full_name) {
    Scope* scope = &start;
    std::string name = full_name;
    for (int namespaces = 0; namespaces <= kMaxNesting; ++namespaces) {
      for (Scope* s = scope; s != nullptr; s = s->parent) {
        if (auto it = s->properties.find(name); it != s->properties.end()) return resolve(*s, name, it->second);
      }
      const auto dot = name.find('.');
      if (dot == std::string::npos) return std::nullopt;
      scope = namespaceIn(*scope, name.substr(0, dot));
      if (scope == nullptr) return std::nullopt;
      name.erase(0, dot + 1);
    }
    return std::nullopt;
  }

  // The properties being evaluated, each through the next (outermost first).
  class Resolving {
   public:
    Resolving(Expander& expander, Property& property, const std::string& name)
        : expander_(expander), property_(property) {
      property_.evaluating = true;
      expander_.resolving_.push_back(name);
    }
    ~Resolving() {
      property_.evaluating = false;
      expander_.resolving_.pop_back();
    }
    Resolving(const Resolving&) = delete;
    Resolving& operator=(const Resolving&) = delete;

   private:
    Expander& expander_;
    Property& property_;
  };

  // "property 'p200' is defined through a chain of more than 100 properties (p200 -> p199 -> ... -> p100)..."
  std::string chainText(const std::string& next) const {
    std::string chain;
    const std::size_t shown_first = 3;
    for (std::size_t i = 0; i < resolving_.size() && i < shown_first; ++i) chain += resolving_[i] + " -> ";
    if (resolving_.size() > shown_first + 1) chain += "... -> ";
    if (resolving_.size() > shown_first) chain += resolving_.back() + " -> ";
    chain += next;
    return "property '" + resolving_.front() + "' is defined through a chain of more than " +
           std::to_string(kMaxPropertyChain) + " properties (" + chain + "); xacro-file property chains deeper than " +
           std::to_string(kMaxPropertyChain) + " are refused: evaluate properties where they are defined "
           "(lazy_eval=\"false\"), or give some of them a value of their own";
  }

  Value resolve(Scope& owner, const std::string& name, Property& property) {
    if (property.block) {
      throw ExpressionError("property '" + name + "' is a block; insert it with <xacro:insert_block name=\"" + name +
                            "\"/>");
    }
    if (!property.value) {
      if (property.evaluating) throw ExpressionError("property '" + name + "' is defined in terms of itself");
      if (resolving_.size() >= kMaxPropertyChain) throw LimitError(chainText(name));
      const RecursionLevel level(
          [&] { throw LimitError("property '" + name + "': " + xacro::recursionLimitText("property '" + name + "'")); });
      const Resolving resolving(*this, property, name);
      try {
        property.value = literalized(evalText(*property.text, owner));
      } catch (const LimitError&) {
        throw;  // whole already; the chain it passed through would make it long
      } catch (const ExpressionError& e) {
        throw ExpressionError("property '" + name + "' (\"" + shortened(*property.text) + "\"): " + e.what());
      }
    }
    return *property.value;
  }

  // A loop, as lookupIn.
  std::shared_ptr<const Macro> findMacro(Scope& start, const std::string& full_name) {
    Scope* scope = &start;
    std::string name = full_name;
    for (int namespaces = 0; namespaces <= kMaxNesting; ++namespaces) {
      for (Scope* s = scope; s != nullptr; s = s->parent) {
        if (auto it = s->macros.find(name); it != s->macros.end()) return it->second;
      }
      const auto dot = name.find('.');
      if (dot == std::string::npos) return nullptr;
      scope = namespaceIn(*scope, name.substr(0, dot));
      if (scope == nullptr) return nullptr;
      name.erase(0, dot + 1);
    }
    return nullptr;
  }

  // ----- text: ${expression}, $(substitution), $${ and $$( escapes -----

  Value evalText(const std::string& text, Scope& scope) {
    std::vector<Value> parts;
    std::string plain;
    auto flush = [&] {
      if (!plain.empty()) parts.push_back(Value::ofString(plain));
      plain.clear();
    };
    std::size_t i = 0;
    while (i < text.size()) {
      if (text[i] != '$') {
        plain += text[i++];
        continue;
      }
      std::size_t j = i;
      while (j < text.size() && text[j] == '$') ++j;
      if (j >= text.size() || (text[j] != '{' && text[j] != '(')) {
        plain.append(text, i, j - i);
        i = j;
        continue;
      }
      if (j - i >= 2) {  // $${ and $$( stand for ${ and $( themselves
        plain.append(j - i - 1, '$');
        plain += text[j];
        i = j + 1;
        continue;
      }
      if (text[j] == '{') {
        const auto close = text.find('}', j);
        if (close == std::string::npos) {
          throw ExpressionError("'${' without a closing '}' in \"" + shortened(text) + "\"");
        }
        std::string expression = text.substr(j + 1, close - j - 1);
        // As xacro does, $(...) inside ${...} is substituted first: ${$(arg mass) * 2}.
        if (expression.find("$(") != std::string::npos) expression = evalString(expression, scope);
        flush();
        Scope* saved = current_;
        current_ = &scope;
        try {
          parts.push_back(xacro::evaluate(expression, *this));
        } catch (const LimitError&) {
          current_ = saved;
          throw;
        } catch (const ExpressionError& e) {
          current_ = saved;
          throw ExpressionError("${" + shortened(expression) + "}: " + e.what());
        }
        current_ = saved;
        i = close + 1;
      } else {
        int depth = 0;
        std::size_t close = j;
        for (; close < text.size(); ++close) {
          if (text[close] == '(') ++depth;
          if (text[close] == ')' && --depth == 0) break;
        }
        if (close >= text.size()) {
          throw ExpressionError("'$(' without a closing ')' in \"" + shortened(text) + "\"");
        }
        flush();
        parts.push_back(Value::ofString(substitute(text.substr(j + 1, close - j - 1), scope)));
        i = close + 1;
      }
    }
    flush();
    if (parts.empty()) return Value::ofString("");
    if (parts.size() == 1) return parts[0];
    // A text is bounded as a value's is: "${p}${p}" doubles p, and thirty
    // such properties would stand for gigabytes.
    std::string joined;
    for (const auto& p : parts) {
      const std::string part = xacro::str(p);
      if (joined.size() + part.size() > xacro::kMaxValueText) {
        throw ExpressionError("\"" + shortened(text) + "\" would make a text over " +
                              std::to_string(xacro::kMaxValueText >> 20) +
                              " MiB; does a property double another again and again (p1 = \"${p0}${p0}\", ...)?");
      }
      joined += part;
    }
    return Value::ofString(joined);
  }

  std::string evalString(const std::string& text, Scope& scope) { return xacro::str(evalText(text, scope)); }

  // $(arg x), $(find pkg), $(env V), $(optenv V default), $(dirname), $(eval expr)
  std::string substitute(const std::string& body, Scope& scope) {
    if (substitutions_ >= kMaxSubstitutionNesting) {
      throw LimitError("$(" + shortened(body) + "): $(...) substitutions nest more than " +
                       std::to_string(kMaxSubstitutionNesting) + " deep inside one another; no robot description "
                       "comes near that: simplify it");
    }
    const RecursionLevel level(
        [&] { throw LimitError("$(" + shortened(body) + "): " + xacro::recursionLimitText("a $(...) substitution")); });
    ++substitutions_;
    struct Leave {
      int& count;
      ~Leave() { --count; }
    } leave{substitutions_};
    const std::string inner = body.find("$(") != std::string::npos ? evalString(body, scope) : body;
    const std::string trimmed = trim(inner);
    const auto space = trimmed.find_first_of(" \t");
    const std::string command = trimmed.substr(0, space);
    const std::string rest = space == std::string::npos ? "" : trim(trimmed.substr(space + 1));
    if (command == "arg") {
      known_args_.insert(rest);
      if (auto it = args_.find(rest); it != args_.end()) return it->second;
      throw ExpressionError("$(arg " + rest + ") is not set: pass " + rest + ":=value, or declare <xacro:arg name=\"" +
                            rest + "\" default=\"...\"/> before using it");
    }
    if (command == "find") {
      try {
        return findPackage(rest, files_.back().dir, files_.back().name).string();
      } catch (const ConfigError& e) {
        throw ExpressionError(std::string("$(find ") + rest + "): " + e.what());
      }
    }
    if (command == "env" || command == "optenv") {
      const auto split = rest.find_first_of(" \t");
      const std::string variable = rest.substr(0, split);
      if (const char* value = std::getenv(variable.c_str())) return value;
      if (command == "optenv") return split == std::string::npos ? "" : trim(rest.substr(split + 1));
      throw ExpressionError("$(env " + variable + "): the environment variable is not set; set it or use $(optenv " +
                            variable + " default)");
    }
    if (command == "dirname") return files_.back().dir.string();
    if (command == "eval") {
      ArgNames arg_names(args_, *this, known_args_);
      return xacro::str(xacro::evaluate(rest, arg_names));
    }
    throw ExpressionError("unknown substitution $(" + shortened(trimmed) +
                          "); xacro knows $(arg), $(find), $(env), $(optenv), $(dirname) and $(eval)");
  }

  // $(eval ...) sees the arguments as names.
  class ArgNames : public xacro::Names {
   public:
    ArgNames(const XacroArgs& args, xacro::Names& files, std::set<std::string>& used)
        : args_(args), files_(files), used_(used) {}
    std::optional<Value> lookup(const std::string& name) override {
      if (auto it = args_.find(name); it != args_.end()) return used_.insert(name), xacro::literal(it->second);
      return std::nullopt;
    }
    Value loadYaml(const std::string& file) override { return files_.loadYaml(file); }

   private:
    const XacroArgs& args_;
    xacro::Names& files_;
    std::set<std::string>& used_;
  };

  // ----- the XML walk -----

  void countNode(const XMLNode* where) {
    if (++output_nodes_ > kMaxOutputNodes) {
      fail(where, "the expansion passed " + std::to_string(kMaxOutputNodes) +
                      " XML nodes; a macro probably calls itself or another macro without end");
    }
  }

  void copyAttributes(const XMLElement* in, XMLElement* out, Scope& scope) {
    for (const auto* a = in->FirstAttribute(); a != nullptr; a = a->Next()) {
      const std::string name = a->Name();
      if (name.rfind("xmlns:", 0) == 0 && files_.back().prefixes.count(name.substr(6)) > 0) continue;
      out->SetAttribute(a->Name(), evalString(a->Value(), scope).c_str());
    }
  }

  // Each call is a level of xacro's recursion: elements inside elements, and
  // the bodies of macros, includes, conditions and blocks.
  void expandChildren(const XMLNode* in, XMLNode* out, Scope& scope) {
    const RecursionLevel level([&] { fail(in, xacro::recursionLimitText(elementText(in))); });
    for (const XMLNode* node = in->FirstChild(); node != nullptr; node = node->NextSibling()) {
      countNode(node);
      if (const XMLElement* element = node->ToElement()) {
        expandElement(element, out, scope);
      } else if (const tinyxml2::XMLText* text = node->ToText()) {
        if (text->CData()) {
          out->InsertEndChild(text->ShallowClone(&output_));
        } else {
          std::string value;
          guarded(in->ToElement(), [&] { value = evalString(text->Value(), scope); });
          out->InsertEndChild(output_.NewText(value.c_str()));
        }
      } else if (node->ToComment() != nullptr) {
        out->InsertEndChild(output_.NewComment(node->Value()));
      }
    }
  }

  // <name> or <name name="..."> for messages.
  static std::string elementText(const XMLNode* node) {
    const XMLElement* element = node->ToElement();
    if (element == nullptr) return "the document";
    const char* name = element->Attribute("name");
    return "<" + std::string(element->Name()) + (name != nullptr ? " name=\"" + shortened(name) + "\"" : "") + ">";
  }

  const char* xacroName(const XMLElement* element) const {
    const char* name = element->Name();
    const char* colon = std::strchr(name, ':');
    if (colon == nullptr) return nullptr;
    return files_.back().prefixes.count(std::string(name, colon)) > 0 ? colon + 1 : nullptr;
  }

  void expandElement(const XMLElement* element, XMLNode* out, Scope& scope) {
    const char* local = xacroName(element);
    if (local == nullptr) {
      XMLElement* copy = output_.NewElement(element->Name());
      out->InsertEndChild(copy);
      guarded(element, [&] { copyAttributes(element, copy, scope); });
      expandChildren(element, copy, scope);
      return;
    }
    const std::string what = local;
    guarded(element, [&] {
      if (what == "property") {
        defineProperty(element, scope);
      } else if (what == "arg") {
        const std::string name = required(element, "name");
        known_args_.insert(name);
        if (args_.count(name) == 0 && element->Attribute("default") != nullptr) {
          args_[name] = evalString(element->Attribute("default"), scope);
        }
      } else if (what == "include") {
        include(element, out, scope);
      } else if (what == "macro") {
        defineMacro(element, scope);
      } else if (what == "if" || what == "unless") {
        if (condition(element, scope) == (what == "if")) expandChildren(element, out, scope);
      } else if (what == "insert_block") {
        insertBlock(element, out, scope);
      } else if (what == "element") {
        const tinyxml2::XMLAttribute* name_attribute = nullptr;
        for (const auto* a = element->FirstAttribute(); a != nullptr; a = a->Next()) {
          const std::string attribute = a->Name();
          const auto colon = attribute.find(':');
          if (colon != std::string::npos && attribute.substr(colon) == ":name" &&
              files_.back().prefixes.count(attribute.substr(0, colon)) > 0) {
            name_attribute = a;
          }
        }
        if (name_attribute == nullptr) fail(element, "<xacro:element> needs the attribute xacro:name");
        const std::string name = evalString(name_attribute->Value(), scope);
        if (name.empty()) fail(element, "<xacro:element xacro:name=...> gives an empty element name");
        XMLElement* created = output_.NewElement(name.c_str());
        out->InsertEndChild(created);
        for (const auto* a = element->FirstAttribute(); a != nullptr; a = a->Next()) {
          if (a != name_attribute) created->SetAttribute(a->Name(), evalString(a->Value(), scope).c_str());
        }
        expandChildren(element, created, scope);
      } else if (what == "attribute") {
        XMLElement* parent = out->ToElement();
        if (parent == nullptr) fail(element, "<xacro:attribute> must sit inside an element");
        parent->SetAttribute(evalString(required(element, "name"), scope).c_str(),
                             evalString(required(element, "value"), scope).c_str());
      } else if (what == "call") {
        callMacro(element, evalString(required(element, "macro"), scope), out, scope, "macro");
      } else {
        callMacro(element, what, out, scope, "");
      }
    });
  }

  std::string required(const XMLElement* element, const char* attribute) {
    const char* value = element->Attribute(attribute);
    if (value == nullptr) fail(element, std::string("<") + element->Name() + "> needs the attribute " + attribute);
    return value;
  }

  void defineProperty(const XMLElement* element, Scope& scope) {
    const std::string name = required(element, "name");
    if (name.empty()) fail(element, "<xacro:property> with an empty name");
    Scope* target = &scope;
    const char* where = element->Attribute("scope");
    const std::string where_text = where ? where : "";
    if (where_text == "parent") {
      target = scope.parent != nullptr ? scope.parent : &scope;
    } else if (where_text == "global") {
      while (target->parent != nullptr) target = target->parent;
    } else if (!where_text.empty()) {
      fail(element, "scope=\"" + where_text + "\" is neither \"parent\" nor \"global\"");
    }
    Property property;
    if (const char* value = element->Attribute("value")) {
      property.text = value;
      const char* lazy = element->Attribute("lazy_eval");
      if (target != &scope || (lazy != nullptr && std::string(lazy) == "false")) {
        property.value = literalized(evalText(value, scope));
      }
    } else if (const char* fallback = element->Attribute("default")) {
      if (lookupIn(scope, name)) return;
      property.text = fallback;
    } else {
      property.block = Block{element, true, false};
    }
    target->properties[name] = std::move(property);
  }

  bool condition(const XMLElement* element, Scope& scope) {
    const Value v = evalText(required(element, "value"), scope);
    switch (v.kind) {
      case Value::Kind::Bool: return v.boolean;
      case Value::Kind::Int: return v.integer != 0;
      case Value::Kind::Float: return static_cast<long long>(v.real) != 0;
      case Value::Kind::String: {
        const Value parsed = xacro::literal(trim(v.text));
        if (parsed.kind == Value::Kind::Bool) return parsed.boolean;
        if (parsed.kind == Value::Kind::Int) return parsed.integer != 0;
        break;
      }
      default: break;
    }
    fail(element, std::string("<") + element->Name() + " value=\"" + element->Attribute("value") + "\"> is \"" +
                      xacro::str(v) + "\", which is not a boolean (true, false, 1 or 0)");
  }

  void include(const XMLElement* element, XMLNode* out, Scope& scope) {
    const std::string filename = evalString(required(element, "filename"), scope);
    fs::path path = filename;
    if (path.is_relative()) path = files_.back().dir / path;
    path = path.lexically_normal();
    std::error_code ec;
    if (!fs::is_regular_file(path, ec)) {
      const char* optional = element->Attribute("optional");
      if (optional != nullptr && literalized(Value::ofString(optional)).boolean) return;
      fail(element, "<xacro:include filename=\"" + filename + "\">: " + path.string() +
                        " not found; fix the filename (relative names start at " + files_.back().dir.string() + ")");
    }
    if (static_cast<int>(files_.size()) > kMaxNesting) {
      fail(element, "includes nest more than " + std::to_string(kMaxNesting) + " deep; does a file include itself?");
    }
    const std::string text = readFile(path, "xacro include");
    const XMLDocument& document = parse(text, path.string());
    const XMLElement* root = document.RootElement();
    files_.push_back(File{path.string(), path.parent_path(), xacroPrefixes(root)});
    Scope* target = &scope;
    if (const char* ns = element->Attribute("ns")) {
      target = &newScope(&scope);
      scope.namespaces[evalString(ns, scope)] = target;
    }
    expandChildren(root, out, *target);
    files_.pop_back();
  }

  void defineMacro(const XMLElement* element, Scope& scope) {
    auto macro = std::make_shared<Macro>();
    macro->name = required(element, "name");
    macro->body = element;
    macro->file = files_.back();
    const char* params = element->Attribute("params");
    std::string text = params != nullptr ? params : "";
    std::size_t i = 0;
    while (i < text.size()) {
      while (i < text.size() && std::isspace(static_cast<unsigned char>(text[i]))) ++i;
      if (i >= text.size()) break;
      std::string token;
      char quote = 0;
      while (i < text.size() && (quote != 0 || !std::isspace(static_cast<unsigned char>(text[i])))) {
        if (quote == 0 && (text[i] == '\'' || text[i] == '"')) {
          quote = text[i];
        } else if (text[i] == quote) {
          quote = 0;
        }
        token += text[i++];
      }
      Macro::Param param;
      while (param.stars < 2 && !token.empty() && token[0] == '*') {
        ++param.stars;
        token.erase(0, 1);
      }
      auto assign = token.find(":=");
      std::size_t skip = 2;
      if (assign == std::string::npos) {
        assign = token.find('=');
        skip = 1;
      }
      param.name = token.substr(0, assign);
      if (assign != std::string::npos) {
        std::string fallback = token.substr(assign + skip);
        if (fallback.size() >= 2 && fallback.front() == '"' && fallback.back() == '"') {
          fallback = fallback.substr(1, fallback.size() - 2);
        }
        if (!fallback.empty() && fallback[0] == '^') {
          param.forward = true;
          if (fallback.size() > 1 && fallback[1] == '|') param.default_text = fallback.substr(2);
        } else {
          param.default_text = fallback;
        }
      }
      if (param.name.empty()) fail(element, "macro '" + macro->name + "': a parameter without a name in params=\"" + text + "\"");
      macro->params.push_back(std::move(param));
    }
    scope.macros[macro->name] = std::move(macro);
  }

  void callMacro(const XMLElement* call, const std::string& name, XMLNode* out, Scope& scope, const std::string& via) {
    const std::shared_ptr<const Macro> macro = findMacro(scope, name);
    if (!macro) {
      const std::string shown = shortened(name);
      fail(call, "<" + shortened(call->Name()) + ">" + (via.empty() ? "" : " (macro=\"" + shown + "\")") +
                     ": no macro named '" + shown +
                     "' is defined here; define it with <xacro:macro name=\"" + shown +
                     "\" params=\"...\"> before this line, or include the file that does");
    }
    if (static_cast<int>(calls_.size()) >= kMaxNesting) {
      fail(call, "macro calls nest more than " + std::to_string(kMaxNesting) + " deep; does macro '" + name +
                     "' call itself without end?");
    }
    // The call's scope (and any made inside it) ends with the call: nothing
    // outside keeps a reference to it.
    const std::size_t scopes_before = scopes_.size();
    Scope& local = newScope(&scope);
    std::string known;
    for (const auto& p : macro->params) known += (known.empty() ? "" : ", ") + std::string(p.stars, '*') + p.name;
    for (const auto* a = call->FirstAttribute(); a != nullptr; a = a->Next()) {
      const std::string attribute = a->Name();
      if (!via.empty() && attribute == "macro") continue;
      bool found = false;
      for (const auto& p : macro->params) found = found || (p.stars == 0 && p.name == attribute);
      if (!found) {
        fail(call, "macro '" + name + "' has no parameter '" + attribute + "' (its parameters: " +
                       (known.empty() ? "none" : known) + ")");
      }
      Property property;
      property.value = literalized(evalText(a->Value(), scope));
      local.properties[attribute] = std::move(property);
    }
    // Block arguments are the call's child elements, expanded where the call is.
    // The holder lives until the call returns (only the call's own scope
    // refers to it); tinyxml2 keeps unattached nodes in a list it scans on
    // every insertion, so leaving holders behind would make expansion quadratic.
    XMLElement* blocks = nullptr;
    if (call->FirstChildElement() != nullptr) {
      blocks = output_.NewElement("blocks");
      expandChildren(call, blocks, scope);
    }
    const XMLElement* next_block = blocks != nullptr ? blocks->FirstChildElement() : nullptr;
    for (const auto& p : macro->params) {
      if (p.stars > 0) {
        if (next_block == nullptr) {
          fail(call, "macro '" + name + "' needs a child element for its block parameter '" +
                         std::string(p.stars, '*') + p.name + "'");
        }
        Property property;
        property.block = Block{next_block, p.stars == 2, true};
        local.properties[p.name] = std::move(property);
        next_block = next_block->NextSiblingElement();
        continue;
      }
      if (local.properties.count(p.name) > 0) continue;
      Property property;
      if (p.forward) {
        if (auto forwarded = lookupIn(scope, p.name)) {
          property.value = *forwarded;
        } else if (p.default_text) {
          property.value = literalized(evalText(*p.default_text, local));
        } else {
          fail(call, "macro '" + name + "': parameter " + p.name + ":=^ takes property '" + p.name +
                         "' from where the macro is called, and it is not defined there");
        }
      } else if (p.default_text) {
        property.value = literalized(evalText(*p.default_text, local));
      } else {
        fail(call, "macro '" + name + "' is called without its parameter '" + p.name + "'; add " + p.name + "=\"...\"");
      }
      local.properties[p.name] = std::move(property);
    }
    calls_.push_back("macro '" + name + "' called at " + names_.at(call->GetDocument()) + ":" +
                     std::to_string(call->GetLineNum()));
    files_.push_back(macro->file);
    expandChildren(macro->body, out, local);
    files_.pop_back();
    calls_.pop_back();
    if (blocks != nullptr) output_.DeleteNode(blocks);
    scopes_.resize(scopes_before);
  }

  void insertBlock(const XMLElement* element, XMLNode* out, Scope& scope) {
    const std::string name = evalString(required(element, "name"), scope);
    for (Scope* s = &scope; s != nullptr; s = s->parent) {
      const auto it = s->properties.find(name);
      if (it == s->properties.end()) continue;
      if (!it->second.block) fail(element, "'" + name + "' is a property with a value, not a block");
      const Block block = *it->second.block;
      if (!block.expanded) {
        expandChildren(block.holder, out, scope);
      } else if (block.contents_only) {
        for (const XMLNode* n = block.holder->FirstChild(); n != nullptr; n = n->NextSibling()) {
          insertCopy(n, out, element, name);
        }
      } else {
        insertCopy(block.holder, out, element, name);
      }
      return;
    }
    fail(element, "<xacro:insert_block name=\"" + name + "\">: no block named '" + name +
                      "' (a *" + name + " macro parameter or a <xacro:property name=\"" + name + "\"> with a body)");
  }

  // A copy of `node` (an expanded block) at the end of `out`. Its nodes count
  // towards kMaxOutputNodes, and the output nests no deeper than kMaxRecursion
  // elements for it: a block passed from macro to macro, wrapped each time,
  // grows without any expansion of its own, and tinyxml2 copies, prints and
  // frees a tree recursively. The walk here is a loop.
  void insertCopy(const XMLNode* node, XMLNode* out, const XMLElement* where, const std::string& block) {
    int out_depth = 0;
    for (const XMLNode* n = out; n != nullptr; n = n->Parent()) ++out_depth;
    std::vector<std::pair<const XMLNode*, int>> pending{{node, 1}};
    while (!pending.empty()) {
      const auto [n, depth] = pending.back();
      pending.pop_back();
      countNode(where);
      if (out_depth + depth > xacro::kMaxRecursion) {
        fail(where, "<xacro:insert_block name=\"" + shortened(block) + "\"> would nest the output more than " +
                        std::to_string(xacro::kMaxRecursion) +
                        " elements deep; does a macro pass its block on to itself, wrapped, again and again?");
      }
      for (const XMLNode* child = n->FirstChild(); child != nullptr; child = child->NextSibling()) {
        pending.emplace_back(child, depth + 1);
      }
    }
    out->InsertEndChild(node->DeepClone(&output_));
  }

  XacroArgs args_;
  const XacroArgs given_;             // the name:=value arguments of the command line
  std::set<std::string> known_args_;  // declared by <xacro:arg> or read by $(arg)
  std::vector<std::unique_ptr<XMLDocument>> documents_;
  std::map<const XMLDocument*, std::string> names_;
  std::vector<std::unique_ptr<Scope>> scopes_;
  std::vector<File> files_;
  std::vector<std::string> calls_;
  std::vector<std::string> resolving_;  // see Resolving
  int substitutions_ = 0;               // $(...) being substituted, one inside another
  Scope* current_ = nullptr;
  XMLDocument output_;
  std::size_t output_nodes_ = 0;
};

}  // namespace

bool isXacroPath(const fs::path& path) { return path.extension() == ".xacro"; }

std::string expandXacro(const std::string& text, const std::string& source_name, const XacroArgs& args) {
  Expander expander(args);
  return expander.run(text, source_name);
}

std::string expandXacroFile(const fs::path& path, const XacroArgs& args) {
  return expandXacro(readFile(path, "xacro file"), path.string(), args);
}

std::string readRobotDescription(const fs::path& path, const XacroArgs& args) {
  if (isXacroPath(path)) return expandXacroFile(path, args);
  return readFile(path, "URDF file");
}

std::string evaluatePythonExpression(const std::string& expression, const std::map<std::string, std::string>& names) {
  class StringNames : public xacro::Names {
   public:
    explicit StringNames(const std::map<std::string, std::string>& names) : names_(names) {}
    std::optional<Value> lookup(const std::string& name) override {
      if (auto it = names_.find(name); it != names_.end()) return Value::ofString(it->second);
      return std::nullopt;
    }
    Value loadYaml(const std::string& /*file*/) override {
      throw xacro::ExpressionError("load_yaml is xacro's, not roslaunch's");
    }

   private:
    const std::map<std::string, std::string>& names_;
  };
  // arg('x') and arg("x") are the variable x.
  static const std::regex kArgCall(R"re(\barg\(\s*['"]([^'"]*)['"]\s*\))re");
  const std::string text = std::regex_replace(expression, kArgCall, "$1");
  StringNames lookup(names);
  try {
    return xacro::str(xacro::evaluate(text, lookup));
  } catch (const xacro::ExpressionError& error) {
    throw ConfigError("$(eval " + expression + "): " + error.what());
  }
}

std::pair<std::string, std::string> parseXacroArg(const std::string& text) {
  const auto assign = text.find(":=");
  if (assign == std::string::npos || assign == 0) {
    throw ConfigError("xacro argument '" + text + "' is not name:=value (e.g. prefix:=left_)");
  }
  return {text.substr(0, assign), text.substr(assign + 2)};
}

}  // namespace servoloop
