#include "xacro_expression.hpp"

#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <limits>
#include <optional>
#include <vector>

#include "xacro_builtins.hpp"
#include "xacro_methods.hpp"
#include "xacro_operators.hpp"

namespace servoloop::xacro {
namespace {

struct Token {
  enum class Kind { Number, String, Name, Op, End };
  Kind kind = Kind::End;
  std::string text;
  Value number;
  std::size_t begin = 0;  // where the token stands in the expression, for messages
  std::size_t end = 0;
};

// Python's backslash escapes in a string literal; an unknown one keeps its backslash.
char escaped(char c, bool& known) {
  known = true;
  switch (c) {
    case 'n': return '\n';
    case 't': return '\t';
    case 'r': return '\r';
    case '\\':
    case '\'':
    case '"': return c;
    default: known = false; return c;
  }
}

std::vector<Token> tokenize(const std::string& s) {
  std::vector<Token> tokens;
  std::size_t i = 0;
  while (i < s.size()) {
    const char c = s[i];
    if (std::isspace(static_cast<unsigned char>(c))) {
      ++i;
      continue;
    }
    Token t;
    t.begin = i;
    if (std::isdigit(static_cast<unsigned char>(c)) || (c == '.' && i + 1 < s.size() && std::isdigit(static_cast<unsigned char>(s[i + 1])))) {
      std::size_t j = i;
      bool is_float = false;
      while (j < s.size() && (std::isdigit(static_cast<unsigned char>(s[j])) || s[j] == '.' || s[j] == '_')) {
        is_float = is_float || s[j] == '.';
        ++j;
      }
      if (j < s.size() && (s[j] == 'e' || s[j] == 'E')) {
        std::size_t k = j + 1;
        if (k < s.size() && (s[k] == '+' || s[k] == '-')) ++k;
        if (k < s.size() && std::isdigit(static_cast<unsigned char>(s[k]))) {
          is_float = true;
          j = k;
          while (j < s.size() && std::isdigit(static_cast<unsigned char>(s[j]))) ++j;
        }
      }
      std::string digits;
      for (std::size_t k = i; k < j; ++k) {
        if (s[k] != '_') digits += s[k];
      }
      t.kind = Token::Kind::Number;
      t.text = s.substr(i, j - i);
      const char* b = digits.data();
      const char* e = b + digits.size();
      if (is_float) {
        double f = 0.0;
        if (auto r = std::from_chars(b, e, f); r.ec != std::errc() || r.ptr != e) fail("'" + t.text + "' is not a number");
        t.number = Value::ofFloat(f);
      } else {
        long long n = 0;
        if (auto r = std::from_chars(b, e, n); r.ec != std::errc() || r.ptr != e) fail("'" + t.text + "' is not a number");
        t.number = Value::ofInt(n);
      }
      i = j;
    } else if (std::isalpha(static_cast<unsigned char>(c)) || c == '_') {
      std::size_t j = i;
      while (j < s.size() && (std::isalnum(static_cast<unsigned char>(s[j])) || s[j] == '_')) ++j;
      t.kind = Token::Kind::Name;
      t.text = s.substr(i, j - i);
      i = j;
    } else if (c == '\'' || c == '"') {
      std::size_t j = i + 1;
      std::string text;
      while (j < s.size() && s[j] != c) {
        if (s[j] == '\\' && j + 1 < s.size()) {
          bool known = false;
          const char e = escaped(s[j + 1], known);
          if (!known) text += '\\';
          text += e;
          j += 2;
          continue;
        }
        text += s[j++];
      }
      if (j >= s.size()) fail("a string starting at " + s.substr(i, 10) + " is not closed");
      t.kind = Token::Kind::String;
      t.text = text;
      i = j + 1;
    } else {
      static const char* const kOps[] = {"**", "//", "==", "!=", "<=", ">=", "<", ">", "+", "-", "*", "/",
                                         "%",  "(",  ")",  "[",  "]",  ",",  ":", "{", "}", ".", "="};
      bool matched = false;
      for (const char* op : kOps) {
        const std::string o(op);
        if (s.compare(i, o.size(), o) == 0) {
          t.kind = Token::Kind::Op;
          t.text = o;
          i += o.size();
          matched = true;
          break;
        }
      }
      if (!matched) fail(std::string("unexpected character '") + c + "'");
    }
    t.end = i;
    tokens.push_back(std::move(t));
  }
  Token end;
  end.begin = end.end = s.size();
  tokens.push_back(end);
  return tokens;
}

// A value as messages show it: its repr, cut short past 60 characters.
std::string shown(const Value& v) {
  std::string text = repr(v);
  if (text.size() > 60) text = text.substr(0, 57) + "...";
  return text;
}

// A dict's keys for messages: "a, b, c" (the first 20).
std::string keyList(const Value& dict) {
  std::string keys;
  std::size_t n = 0;
  for (const auto& kv : *dict.dict) {
    if (n++ == 20) return keys + ", ... (" + std::to_string(dict.dict->size()) + " keys)";
    keys += (keys.empty() ? "" : ", ") + kv.first;
  }
  return keys.empty() ? "none: the dict is empty" : keys;
}

bool isModule(const std::string& name) { return name == "math" || name == "xacro" || name == "python"; }

// math's constants, which xacro also offers bare (pi rather than math.pi).
std::optional<Value> mathConstant(const std::string& name) {
  if (name == "pi") return Value::ofFloat(M_PI);
  if (name == "e") return Value::ofFloat(M_E);
  if (name == "tau") return Value::ofFloat(2.0 * M_PI);
  if (name == "inf") return Value::ofFloat(HUGE_VAL);
  if (name == "nan") return Value::ofFloat(std::nan(""));
  return std::nullopt;
}

class Parser {
 public:
  Parser(const std::string& expression, Names& names)
      : expression_(expression), tokens_(tokenize(expression)), names_(names) {}

  Value parseAll() {
    Value v = conditional(true);
    if (peek().kind != Token::Kind::End) fail("unexpected '" + peek().text + "'");
    return v;
  }

 private:
  // Brackets, parentheses and operators nest at most this deep in one
  // expression: the parser recurses once per level (every path by which it
  // calls itself passes a Nesting: conditional, which every bracket,
  // parenthesis, argument and `else` starts, unary - and +, not, the right
  // side of **, and [subscripts]), and a deeper text would exhaust the stack.
  // A level counts towards kMaxRecursion too, with the levels of the
  // expressions and elements this one is evaluated inside.
  static constexpr int kMaxNesting = 100;
  class Nesting {
   public:
    explicit Nesting(Parser& parser)
        : parser_(parser.checkedNesting()), level_([&parser] { parser.refuseRecursion(); }) {
      ++parser_.nesting_;
    }
    ~Nesting() { --parser_.nesting_; }
    Nesting(const Nesting&) = delete;
    Nesting& operator=(const Nesting&) = delete;

   private:
    Parser& parser_;
    RecursionLevel level_;
  };

  Parser& checkedNesting() {
    if (nesting_ >= kMaxNesting) {
      fail("the expression nests more than " + std::to_string(kMaxNesting) +
           " levels of brackets, parentheses or operators (unary - + and not, the right side of **, "
           "x if c else y); no robot's expression comes near that: simplify it");
    }
    return *this;
  }

  [[noreturn]] void refuseRecursion() const {
    throw LimitError("${" + shortened(expression_) + "}: " + recursionLimitText("a level of this expression"));
  }

  const Token& peek() const { return tokens_[pos_]; }
  const Token& after() const { return tokens_[std::min(pos_ + 1, tokens_.size() - 1)]; }
  bool isOp(const char* op) const { return peek().kind == Token::Kind::Op && peek().text == op; }
  bool isWord(const char* word) const { return peek().kind == Token::Kind::Name && peek().text == word; }
  void expect(const char* op) {
    if (!isOp(op)) fail(std::string("expected '") + op + "'" + (peek().kind == Token::Kind::End ? " at the end" : " before '" + peek().text + "'"));
    ++pos_;
  }
  // The expression's text from token `first` up to (not including) the
  // current one, for messages; a long one is cut in the middle, so a chain of
  // a.b.c... costs the same per link however long it gets.
  std::string textFrom(std::size_t first) const {
    const std::size_t last = pos_ > first ? pos_ - 1 : first;
    const std::size_t begin = tokens_[first].begin;
    const std::size_t length = tokens_[last].end - begin;
    if (length <= 120) return expression_.substr(begin, length);
    return expression_.substr(begin, 57) + "..." + expression_.substr(tokens_[last].end - 60, 60);
  }

  // `live` is false on the side a short circuit skips: parsed, not evaluated.
  // In `x if c else y`, c is evaluated first and then only x or y (Python's
  // order): a live parse looks ahead (without evaluating) for the `if`.
  Value conditional(bool live) {
    const Nesting nesting(*this);
    const std::size_t start = pos_;
    if (!live) {
      orExpr(false);
      if (!isWord("if")) return Value{};
      ++pos_;
      orExpr(false);
      expectElse();
      return conditional(false);
    }
    orExpr(false);
    if (!isWord("if")) {
      pos_ = start;
      return orExpr(true);
    }
    ++pos_;
    const Value condition = orExpr(true);
    expectElse();
    const std::size_t otherwise = pos_;
    if (truthy(condition)) {
      pos_ = start;
      Value value = orExpr(true);
      pos_ = otherwise;
      conditional(false);
      return value;
    }
    return conditional(true);
  }

  void expectElse() {
    if (!isWord("else")) fail("'x if c' needs 'else y'");
    ++pos_;
  }

  Value orExpr(bool live) {
    Value v = andExpr(live);
    while (isWord("or")) {
      ++pos_;
      const bool decided = live && truthy(v);
      Value rhs = andExpr(live && !decided);
      if (live && !decided) v = rhs;
    }
    return v;
  }

  Value andExpr(bool live) {
    Value v = notExpr(live);
    while (isWord("and")) {
      ++pos_;
      const bool decided = live && !truthy(v);
      Value rhs = notExpr(live && !decided);
      if (live && !decided) v = rhs;
    }
    return v;
  }

  Value notExpr(bool live) {
    if (isWord("not")) {
      ++pos_;
      const Nesting nesting(*this);
      const Value v = notExpr(live);
      return live ? Value::ofBool(!truthy(v)) : Value{};
    }
    return comparison(live);
  }

  Value comparison(bool live) {
    Value left = arith(live);
    bool result = true;
    bool any = false;
    while (true) {
      std::string op;
      if (peek().kind == Token::Kind::Op &&
          (isOp("==") || isOp("!=") || isOp("<") || isOp("<=") || isOp(">") || isOp(">="))) {
        op = peek().text;
        ++pos_;
      } else if (isWord("in")) {
        op = "in";
        ++pos_;
      } else if (isWord("not") && after().kind == Token::Kind::Name && after().text == "in") {
        op = "not in";
        pos_ += 2;
      } else {
        break;
      }
      // As in Python, a chain stops at its first false link: what follows is
      // parsed but not evaluated (a ${a < b < f(x)} with a >= b never calls f).
      Value right = arith(live && result);
      if (live && result) result = compare(op, left, right);
      left = right;
      any = true;
    }
    return any ? (live ? Value::ofBool(result) : Value{}) : left;
  }

  Value arith(bool live) {
    Value v = term(live);
    while (isOp("+") || isOp("-")) {
      const std::string op = peek().text;
      ++pos_;
      Value rhs = term(live);
      if (live) v = binaryOp(op, v, rhs);
    }
    return v;
  }

  Value term(bool live) {
    Value v = unary(live);
    while (isOp("*") || isOp("/") || isOp("//") || isOp("%")) {
      const std::string op = peek().text;
      ++pos_;
      Value rhs = unary(live);
      if (live) v = binaryOp(op, v, rhs);
    }
    return v;
  }

  Value unary(bool live) {
    if (isOp("-") || isOp("+")) {
      const bool negate = isOp("-");
      ++pos_;
      const Nesting nesting(*this);
      Value v = unary(live);
      if (!live) return v;
      if (!v.isNumber()) fail(std::string("unary ") + (negate ? "-" : "+") + " of " + aTypeName(v) + " (" + shown(v) + ")");
      if (!negate) return isIntegral(v) ? Value::ofInt(toInt(v)) : v;
      if (isIntegral(v) && toInt(v) != std::numeric_limits<long long>::min()) return Value::ofInt(-toInt(v));
      return Value::ofFloat(-asDouble(v));
    }
    return power(live);
  }

  Value power(bool live) {
    Value base = postfix(live);
    if (isOp("**")) {
      ++pos_;
      // ** is right-associative: 2**3**2 is 2**(3**2), so a chain of them
      // nests (as the unary operators do), one level per operator.
      const Nesting nesting(*this);
      Value exponent = unary(live);
      if (live) return binaryOp("**", base, exponent);
    }
    return base;
  }

  // A primary followed by any number of .name, .method(...), (...) and [...].
  Value postfix(bool live) {
    const std::size_t start = pos_;
    Value v = primary(live);
    while (true) {
      if (isOp(".")) {
        const std::string owner = textFrom(start);
        if (after().kind != Token::Kind::Name) fail("expected a name after '" + owner + ".'");
        const std::string attribute = after().text;
        pos_ += 2;
        if (isOp("(")) {
          Arguments args = arguments(live);
          if (live) v = method(v, attribute, args, owner, textFrom(start));
        } else if (live) {
          v = attributeOf(v, attribute, owner, textFrom(start));
        }
      } else if (isOp("(")) {
        const std::string callee = textFrom(start);
        arguments(live);
        if (live) fail(textFrom(start) + ": " + callee + " is " + aTypeName(v) + " (" + shown(v) + "), not a function");
      } else if (isOp("[")) {
        const std::string owner = textFrom(start);
        v = subscript(v, live, owner, start);
      } else {
        return v;
      }
    }
  }

  // (a, b, key=c): positional arguments, then keyword ones, as in Python.
  Arguments arguments(bool live) {
    const std::size_t start = pos_;
    expect("(");
    Arguments args;
    bool keywords = false;
    while (!isOp(")")) {
      if (peek().kind == Token::Kind::Name && after().kind == Token::Kind::Op && after().text == "=") {
        const std::string key = peek().text;
        pos_ += 2;
        Value v = conditional(live);
        if (live) args.keyword.emplace_back(key, std::move(v));
        keywords = true;
      } else {
        if (keywords) fail("a positional argument follows a keyword argument in " + textFrom(start) + "...");
        Value v = conditional(live);
        if (live) args.positional.push_back(std::move(v));
      }
      if (!isOp(",")) break;
      ++pos_;
    }
    expect(")");
    return args;
  }

  Value method(const Value& receiver, const std::string& name, const Arguments& args, const std::string& owner,
               const std::string& call) {
    if (!hasMethod(receiver, name)) {
      const std::string methods = methodNames(receiver);
      fail(call + ": " + owner + " is " + aTypeName(receiver) + " (" + shown(receiver) + "), which has no method '" +
           name + "'" + (methods.empty() ? "" : " (servoloop's xacro knows " + methods + ")"));
    }
    return callMethod(receiver, name, args, call);
  }

  // owner.name without a call: a dict's key (xacro lets YAML dicts be read so).
  static Value attributeOf(const Value& v, const std::string& name, const std::string& owner, const std::string& text) {
    if (v.kind == Value::Kind::Dict) {
      if (const Value* item = v.find(name)) return *item;
      if (hasMethod(v, name)) fail(text + " is a method of a dict; call it: " + text + "()");
      fail(text + ": " + owner + " has no key '" + name + "' (its keys: " + keyList(v) + ")");
    }
    if (hasMethod(v, name)) fail(text + " is a method of " + aTypeName(v) + "; call it: " + text + "(...)");
    const std::string methods = methodNames(v);
    fail(text + ": " + owner + " is " + aTypeName(v) + " (" + shown(v) + "), which has no attribute '" + name + "'" +
         (methods.empty() ? "" : " (its methods: " + methods + ")"));
  }

  // [index], [key] or the slice [start:stop:step].
  Value subscript(const Value& v, bool live, const std::string& owner, std::size_t start) {
    const Nesting nesting(*this);
    expect("[");
    std::array<std::optional<Value>, 3> parts;
    bool is_slice = false;
    if (!isOp(":")) parts[0] = conditional(live);
    if (isOp(":")) {
      is_slice = true;
      ++pos_;
      if (!isOp(":") && !isOp("]")) parts[1] = conditional(live);
      if (isOp(":")) {
        ++pos_;
        if (!isOp("]")) parts[2] = conditional(live);
      }
    }
    expect("]");
    if (!live) return Value{};
    const std::string text = textFrom(start);
    return is_slice ? slice(v, parts, owner, text) : index(v, *parts[0], owner, text);
  }

  static Value index(const Value& v, const Value& key, const std::string& owner, const std::string& text) {
    if (v.kind == Value::Kind::Dict) {
      if (const Value* item = v.find(str(key))) return *item;
      fail(text + ": " + owner + " has no key " + shown(key) + " (its keys: " + keyList(v) + ")");
    }
    if (v.kind != Value::Kind::List && v.kind != Value::Kind::String) {
      fail(text + ": " + owner + " is " + aTypeName(v) + " (" + shown(v) + "), which cannot be indexed");
    }
    if (!isIntegral(key)) {
      fail(text + ": " + typeName(v) + " indices must be ints or slices, not " + aTypeName(key) + " (" + shown(key) +
           ")");
    }
    const bool is_list = v.kind == Value::Kind::List;
    const long long size = static_cast<long long>(is_list ? v.list->size() : v.text.size());
    const long long i = toInt(key) < 0 ? toInt(key) + size : toInt(key);
    if (i < 0 || i >= size) {
      const std::string what = is_list ? "a list of " + std::to_string(size) + " item" + (size == 1 ? "" : "s")
                                       : "a str of " + std::to_string(size) + " character" + (size == 1 ? "" : "s");
      fail(text + ": index " + std::to_string(toInt(key)) + " is out of range: " + owner + " is " + what + " (" +
           shown(v) + ")" +
           (size == 0 ? "" : "; valid indices are 0 to " + std::to_string(size - 1) + " and -" + std::to_string(size) +
                                 " to -1"));
    }
    return is_list ? (*v.list)[static_cast<std::size_t>(i)] : Value::ofString(v.text.substr(static_cast<std::size_t>(i), 1));
  }

  static Value slice(const Value& v, const std::array<std::optional<Value>, 3>& parts, const std::string& owner,
                     const std::string& text) {
    if (v.kind != Value::Kind::List && v.kind != Value::Kind::String) {
      fail(text + ": " + owner + " is " + aTypeName(v) + " (" + shown(v) + "), which cannot be sliced");
    }
    std::array<std::optional<long long>, 3> bounds;
    for (std::size_t k = 0; k < 3; ++k) {
      if (!parts[k] || parts[k]->kind == Value::Kind::None) continue;
      if (!isIntegral(*parts[k])) {
        fail(text + ": slice bounds must be ints or None, not " + aTypeName(*parts[k]) + " (" + shown(*parts[k]) + ")");
      }
      bounds[k] = toInt(*parts[k]);
    }
    long long step = bounds[2].value_or(1);
    if (step == 0) fail(text + ": the slice step cannot be zero");
    if (step == std::numeric_limits<long long>::min()) step = -std::numeric_limits<long long>::max();
    const bool is_list = v.kind == Value::Kind::List;
    const long long size = static_cast<long long>(is_list ? v.list->size() : v.text.size());
    const SliceBounds taken = sliceBounds(size, bounds[0], bounds[1], step);
    std::vector<Value> items;
    std::string chars;
    for (long long k = 0; k < taken.count; ++k) {
      const auto at = static_cast<std::size_t>(taken.start + k * taken.step);
      if (is_list) {
        items.push_back((*v.list)[at]);
      } else {
        chars += v.text[at];
      }
    }
    return is_list ? Value::ofList(std::move(items)) : Value::ofString(std::move(chars));
  }

  Value primary(bool live) {
    if (peek().kind == Token::Kind::Name) return nameOrCall(live);
    return atom(live);
  }

  Value atom(bool live) {
    const Token t = peek();
    ++pos_;
    switch (t.kind) {
      case Token::Kind::Number: return t.number;
      case Token::Kind::String: return Value::ofString(t.text);
      case Token::Kind::End: fail("the expression ends too early");
      case Token::Kind::Name:
      case Token::Kind::Op: break;
    }
    if (t.text == "(") {
      Value v = conditional(live);
      expect(")");
      return v;
    }
    if (t.text == "[") {
      std::vector<Value> items;
      while (!isOp("]")) {
        items.push_back(conditional(live));
        if (!isOp(",")) break;
        ++pos_;
      }
      expect("]");
      return Value::ofList(std::move(items));
    }
    if (t.text == "{") {
      Value::DictItems items;
      while (!isOp("}")) {
        const Value key = conditional(live);
        expect(":");
        Value item = conditional(live);
        items.emplace_back(str(key), std::move(item));
        if (!isOp(",")) break;
        ++pos_;
      }
      expect("}");
      return Value::ofDict(std::move(items));
    }
    fail("unexpected '" + t.text + "'");
  }

  // A name: a constant, a function call, a property, a property of an
  // include's namespace (ns.name), or something of the math, xacro or python
  // module (math.pi, math.sqrt(x), xacro.load_yaml(f)).
  Value nameOrCall(bool live) {
    const std::size_t start = pos_;
    const std::string name = peek().text;
    ++pos_;
    if (name == "True") return Value::ofBool(true);
    if (name == "False") return Value::ofBool(false);
    if (name == "None") return Value::none();
    if (isOp("(")) {
      Arguments args = arguments(live);
      return live ? callFunction(name, args, names_) : Value{};
    }
    if (!live) return Value{};
    if (auto v = names_.lookup(name)) return *v;
    std::string path = name;
    // Namespaces nest no deeper than includes do: past that many segments
    // a.b.c... is not looked up as one name (each look-up reads the whole
    // path, so a long chain would cost its square).
    for (int segments = 0; segments < kMaxNesting && isOp(".") && after().kind == Token::Kind::Name; ++segments) {
      const std::string attribute = after().text;
      path += "." + attribute;
      pos_ += 2;
      if (auto v = names_.lookup(path)) return *v;
      if (isModule(name) && path == name + "." + attribute) {
        if (isOp("(")) {
          Arguments args = arguments(true);
          return callFunction(path, args, names_);
        }
        if (name == "math") {
          if (auto constant = mathConstant(attribute)) return *constant;
        }
        fail("'" + path + "' is not a constant of xacro's " + name + " module; call a function with " + path + "(...)");
      }
    }
    pos_ = start + 1;
    if (auto constant = mathConstant(name)) return *constant;
    fail("name '" + name + "' is not defined");
  }

  std::string expression_;
  std::vector<Token> tokens_;
  std::size_t pos_ = 0;
  int nesting_ = 0;
  Names& names_;
};

}  // namespace

int& RecursionLevel::depth() {
  thread_local int levels = 0;
  return levels;
}

std::string recursionLimitText(const std::string& here) {
  return "xacro nests more than " + std::to_string(kMaxRecursion) + " levels deep at " + here +
         " (elements inside elements, macro calls, includes, $(...) inside $(...), properties defined through other "
         "properties and brackets in expressions count together); no robot description comes near that: flatten "
         "it, or look for something that refers to itself in a roundabout way";
}

std::string shortened(const std::string& text) {
  if (text.size() <= 120) return text;
  return text.substr(0, 57) + "..." + text.substr(text.size() - 60);
}

Value evaluate(const std::string& expression, Names& names) { return Parser(expression, names).parseAll(); }

}  // namespace servoloop::xacro
