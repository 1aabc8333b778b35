#include "xacro_expression.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <vector>

namespace servoloop::xacro {
namespace {

struct Token {
  enum class Kind { Number, String, Name, Op, End };
  Kind kind = Kind::End;
  std::string text;
  Value number;
};

// Python's numeric tower for the operators: bool and int stay int, anything
// with a float becomes float.
bool integral(const Value& v) { return v.kind == Value::Kind::Int || v.kind == Value::Kind::Bool; }
long long asInt(const Value& v) { return v.kind == Value::Kind::Bool ? (v.boolean ? 1 : 0) : v.integer; }

[[noreturn]] void fail(const std::string& message) { throw ExpressionError(message); }

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
      while (j < s.size() && (std::isalnum(static_cast<unsigned char>(s[j])) || s[j] == '_' ||
                              (s[j] == '.' && j + 1 < s.size() &&
                               (std::isalpha(static_cast<unsigned char>(s[j + 1])) || s[j + 1] == '_')))) {
        ++j;
      }
      t.kind = Token::Kind::Name;
      t.text = s.substr(i, j - i);
      i = j;
    } else if (c == '\'' || c == '"') {
      std::size_t j = i + 1;
      std::string text;
      while (j < s.size() && s[j] != c) {
        if (s[j] == '\\' && j + 1 < s.size()) ++j;
        text += s[j++];
      }
      if (j >= s.size()) fail("a string starting at " + s.substr(i, 10) + " is not closed");
      t.kind = Token::Kind::String;
      t.text = text;
      i = j + 1;
    } else {
      static const char* const kOps[] = {"**", "//", "==", "!=", "<=", ">=", "<", ">", "+", "-", "*",
                                         "/",  "%",  "(",  ")",  "[",  "]",  ",", ":", "{", "}"};
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
    tokens.push_back(std::move(t));
  }
  tokens.push_back(Token{});
  return tokens;
}

Value numeric(const char* op, const Value& a, const Value& b) {
  const std::string o(op);
  if (o == "+" && a.kind == Value::Kind::String && b.kind == Value::Kind::String) return Value::ofString(a.text + b.text);
  if (o == "+" && a.kind == Value::Kind::List && b.kind == Value::Kind::List) {
    std::vector<Value> items(*a.list);
    items.insert(items.end(), b.list->begin(), b.list->end());
    return Value::ofList(std::move(items));
  }
  if (o == "*" && a.kind == Value::Kind::String && integral(b)) {
    // A repeated string as long as a description could sensibly hold.
    constexpr long long kMaxRepeatedBytes = 1 << 20;
    const long long times = std::max(asInt(b), 0LL);
    if (times > 0 && static_cast<long long>(a.text.size()) > kMaxRepeatedBytes / times) {
      fail("'" + a.text.substr(0, 20) + "' * " + std::to_string(times) + " would make a string over " +
           std::to_string(kMaxRepeatedBytes) + " bytes");
    }
    std::string out;
    for (long long k = 0; k < times; ++k) out += a.text;
    return Value::ofString(out);
  }
  if (!a.isNumber() || !b.isNumber()) {
    fail("unsupported operand types for " + o + ": " + typeName(a) + " (" + repr(a) + ") and " + typeName(b) + " (" +
         repr(b) + ")");
  }
  if (integral(a) && integral(b) && o != "/") {
    // Python's integers have no bound; a result beyond 64 bits is taken as a
    // float here (below), as no robot description needs one exactly.
    const long long x = asInt(a);
    const long long y = asInt(b);
    long long r = 0;
    if (o == "+" && !__builtin_add_overflow(x, y, &r)) return Value::ofInt(r);
    if (o == "-" && !__builtin_sub_overflow(x, y, &r)) return Value::ofInt(r);
    if (o == "*" && !__builtin_mul_overflow(x, y, &r)) return Value::ofInt(r);
    if ((o == "//" || o == "%") && y == 0) fail("integer division or modulo by zero");
    if ((o == "//" || o == "%") && !(y == -1 && x == std::numeric_limits<long long>::min())) {
      long long q = x / y;
      if ((x % y != 0) && ((x < 0) != (y < 0))) --q;
      return o == "//" ? Value::ofInt(q) : Value::ofInt(x - q * y);
    }
    if (o == "**" && y >= 0) {
      // By squaring, so a large exponent costs its bits, not its value.
      long long result = 1;
      long long base = x;
      bool overflow = false;
      for (long long e = y; e > 0 && !overflow; e >>= 1) {
        if ((e & 1) != 0) overflow = __builtin_mul_overflow(result, base, &result);
        if (e > 1 && !overflow) overflow = __builtin_mul_overflow(base, base, &base);
      }
      if (!overflow) return Value::ofInt(result);
    }
  }
  const double x = asDouble(a);
  const double y = asDouble(b);
  if (o == "+") return Value::ofFloat(x + y);
  if (o == "-") return Value::ofFloat(x - y);
  if (o == "*") return Value::ofFloat(x * y);
  if (o == "/") {
    if (y == 0.0) fail("division by zero");
    return Value::ofFloat(x / y);
  }
  if (o == "//" || o == "%") {
    if (y == 0.0) fail("float division or modulo by zero");
    const double q = std::floor(x / y);
    return o == "//" ? Value::ofFloat(q) : Value::ofFloat(x - q * y);
  }
  if (o == "**") return Value::ofFloat(std::pow(x, y));
  fail("unknown operator " + o);
}

bool equal(const Value& a, const Value& b) {
  if (a.isNumber() && b.isNumber()) return asDouble(a) == asDouble(b);
  if (a.kind != b.kind) return false;
  switch (a.kind) {
    case Value::Kind::None: return true;
    case Value::Kind::String: return a.text == b.text;
    case Value::Kind::List:
      return a.list->size() == b.list->size() && std::equal(a.list->begin(), a.list->end(), b.list->begin(), equal);
    case Value::Kind::Dict: return str(a) == str(b);
    default: return false;
  }
}

bool compare(const std::string& op, const Value& a, const Value& b) {
  if (op == "==") return equal(a, b);
  if (op == "!=") return !equal(a, b);
  if (op == "in" || op == "not in") {
    bool found = false;
    if (b.kind == Value::Kind::String && a.kind == Value::Kind::String) {
      found = b.text.find(a.text) != std::string::npos;
    } else if (b.kind == Value::Kind::List) {
      found = std::any_of(b.list->begin(), b.list->end(), [&](const Value& x) { return equal(a, x); });
    } else if (b.kind == Value::Kind::Dict && a.kind == Value::Kind::String) {
      found = b.dict->count(a.text) > 0;
    } else {
      fail("'in' needs a str, list or dict on its right, not " + typeName(b));
    }
    return op == "in" ? found : !found;
  }
  int order = 0;
  if (a.isNumber() && b.isNumber()) {
    order = asDouble(a) < asDouble(b) ? -1 : (asDouble(a) > asDouble(b) ? 1 : 0);
  } else if (a.kind == Value::Kind::String && b.kind == Value::Kind::String) {
    order = a.text.compare(b.text);
  } else {
    fail("'" + op + "' cannot compare " + typeName(a) + " (" + repr(a) + ") with " + typeName(b) + " (" + repr(b) + ")");
  }
  if (op == "<") return order < 0;
  if (op == "<=") return order <= 0;
  if (op == ">") return order > 0;
  return order >= 0;
}

double number(const std::string& fn, const Value& v) {
  if (!v.isNumber()) fail(fn + "() needs a number, got " + typeName(v) + " (" + repr(v) + ")");
  return asDouble(v);
}

Value callBuiltin(const std::string& fn, const std::vector<Value>& args, Names& names) {
  auto need = [&](std::size_t lo, std::size_t hi) {
    if (args.size() < lo || args.size() > hi) {
      fail(fn + "() takes " + (lo == hi ? std::to_string(lo) : std::to_string(lo) + " to " + std::to_string(hi)) +
           " argument(s), " + std::to_string(args.size()) + " given");
    }
  };
  static const std::map<std::string, double (*)(double)> kUnary = {
      {"sin", [](double x) { return std::sin(x); }},     {"cos", [](double x) { return std::cos(x); }},
      {"tan", [](double x) { return std::tan(x); }},     {"asin", [](double x) { return std::asin(x); }},
      {"acos", [](double x) { return std::acos(x); }},   {"atan", [](double x) { return std::atan(x); }},
      {"sinh", [](double x) { return std::sinh(x); }},   {"cosh", [](double x) { return std::cosh(x); }},
      {"tanh", [](double x) { return std::tanh(x); }},   {"exp", [](double x) { return std::exp(x); }},
      {"log10", [](double x) { return std::log10(x); }}, {"fabs", [](double x) { return std::fabs(x); }},
      {"radians", [](double x) { return x * M_PI / 180.0; }},
      {"degrees", [](double x) { return x * 180.0 / M_PI; }}};
  if (auto it = kUnary.find(fn); it != kUnary.end()) {
    need(1, 1);
    return Value::ofFloat(it->second(number(fn, args[0])));
  }
  if (fn == "sqrt") {
    need(1, 1);
    const double x = number(fn, args[0]);
    if (x < 0) fail("sqrt() of a negative number (" + repr(args[0]) + ")");
    return Value::ofFloat(std::sqrt(x));
  }
  if (fn == "log") {
    need(1, 2);
    const double x = number(fn, args[0]);
    if (x <= 0) fail("log() of a number <= 0 (" + repr(args[0]) + ")");
    return Value::ofFloat(args.size() == 2 ? std::log(x) / std::log(number(fn, args[1])) : std::log(x));
  }
  if (fn == "atan2" || fn == "pow" || fn == "hypot" || fn == "fmod") {
    need(2, 2);
    const double y = number(fn, args[0]);
    const double x = number(fn, args[1]);
    if (fn == "atan2") return Value::ofFloat(std::atan2(y, x));
    if (fn == "hypot") return Value::ofFloat(std::hypot(y, x));
    if (fn == "fmod") return Value::ofFloat(std::fmod(y, x));
    return Value::ofFloat(std::pow(y, x));
  }
  if (fn == "floor" || fn == "ceil" || fn == "trunc") {
    need(1, 1);
    const double x = number(fn, args[0]);
    return Value::ofInt(static_cast<long long>(fn == "floor" ? std::floor(x) : fn == "ceil" ? std::ceil(x) : std::trunc(x)));
  }
  if (fn == "abs") {
    need(1, 1);
    if (integral(args[0])) return Value::ofInt(std::llabs(asInt(args[0])));
    return Value::ofFloat(std::fabs(number(fn, args[0])));
  }
  if (fn == "round") {
    need(1, 2);
    const double x = number(fn, args[0]);
    if (args.size() == 1) {
      // Python rounds halves to even.
      double r = std::nearbyint(x);
      return Value::ofInt(static_cast<long long>(r));
    }
    const double scale = std::pow(10.0, number(fn, args[1]));
    return Value::ofFloat(std::nearbyint(x * scale) / scale);
  }
  if (fn == "min" || fn == "max" || fn == "sum") {
    std::vector<Value> items = args;
    if (args.size() == 1 && args[0].kind == Value::Kind::List) items = *args[0].list;
    if (items.empty()) fail(fn + "() of nothing");
    if (fn == "sum") {
      Value total = Value::ofInt(0);
      for (const auto& v : items) total = numeric("+", total, v);
      return total;
    }
    Value best = items[0];
    for (const auto& v : items) {
      if (compare(fn == "min" ? "<" : ">", v, best)) best = v;
    }
    return best;
  }
  if (fn == "int") {
    need(1, 1);
    if (args[0].kind == Value::Kind::String) {
      const Value v = literal(args[0].text);
      if (v.kind != Value::Kind::Int) fail("int() cannot read '" + args[0].text + "'");
      return v;
    }
    return Value::ofInt(static_cast<long long>(std::trunc(number(fn, args[0]))));
  }
  if (fn == "float") {
    need(1, 1);
    if (args[0].kind == Value::Kind::String) {
      const Value v = literal(args[0].text);
      if (!v.isNumber() || v.kind == Value::Kind::Bool) fail("float() cannot read '" + args[0].text + "'");
      return Value::ofFloat(asDouble(v));
    }
    return Value::ofFloat(number(fn, args[0]));
  }
  if (fn == "bool") {
    need(1, 1);
    return Value::ofBool(truthy(args[0]));
  }
  if (fn == "str") {
    need(1, 1);
    return Value::ofString(str(args[0]));
  }
  if (fn == "len") {
    need(1, 1);
    if (args[0].kind == Value::Kind::String) return Value::ofInt(static_cast<long long>(args[0].text.size()));
    if (args[0].kind == Value::Kind::List) return Value::ofInt(static_cast<long long>(args[0].list->size()));
    if (args[0].kind == Value::Kind::Dict) return Value::ofInt(static_cast<long long>(args[0].dict->size()));
    fail("len() of a " + typeName(args[0]));
  }
  if (fn == "list") {
    need(1, 1);
    if (args[0].kind == Value::Kind::List) return args[0];
    fail("list() of a " + typeName(args[0]));
  }
  if (fn == "load_yaml") {
    need(1, 1);
    if (args[0].kind != Value::Kind::String) fail("load_yaml() needs a file name");
    return names.loadYaml(args[0].text);
  }
  fail("unknown function '" + fn + "'");
}

class Parser {
 public:
  Parser(const std::string& expression, Names& names) : tokens_(tokenize(expression)), names_(names) {}

  Value parseAll() {
    Value v = conditional(true);
    if (peek().kind != Token::Kind::End) fail("unexpected '" + peek().text + "'");
    return v;
  }

 private:
  // Brackets, parentheses and unary operators nest at most this deep: the
  // parser recurses once per level, and a deeper text would exhaust the stack.
  static constexpr int kMaxNesting = 100;
  struct Nesting {
    explicit Nesting(Parser& parser) : parser_(parser) {
      if (++parser_.nesting_ > kMaxNesting) {
        fail("the expression nests more than " + std::to_string(kMaxNesting) +
                     " levels of brackets, parentheses or unary operators");
      }
    }
    ~Nesting() { --parser_.nesting_; }
    Nesting(const Nesting&) = delete;
    Nesting& operator=(const Nesting&) = delete;
    Parser& parser_;
  };

  const Token& peek() const { return tokens_[pos_]; }
  bool isOp(const char* op) const { return peek().kind == Token::Kind::Op && peek().text == op; }
  bool isWord(const char* word) const { return peek().kind == Token::Kind::Name && peek().text == word; }
  void expect(const char* op) {
    if (!isOp(op)) fail(std::string("expected '") + op + "'" + (peek().kind == Token::Kind::End ? " at the end" : " before '" + peek().text + "'"));
    ++pos_;
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
      } else if (isWord("not") && tokens_[pos_ + 1].kind == Token::Kind::Name && tokens_[pos_ + 1].text == "in") {
        op = "not in";
        pos_ += 2;
      } else {
        break;
      }
      Value right = arith(live);
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
      if (live) v = numeric(op.c_str(), v, rhs);
    }
    return v;
  }

  Value term(bool live) {
    Value v = unary(live);
    while (isOp("*") || isOp("/") || isOp("//") || isOp("%")) {
      const std::string op = peek().text;
      ++pos_;
      Value rhs = unary(live);
      if (live) v = numeric(op.c_str(), v, rhs);
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
      if (!v.isNumber()) fail(std::string("unary ") + (negate ? "-" : "+") + " of a " + typeName(v) + " (" + repr(v) + ")");
      if (!negate) return integral(v) ? Value::ofInt(asInt(v)) : v;
      if (integral(v) && asInt(v) != std::numeric_limits<long long>::min()) return Value::ofInt(-asInt(v));
      return Value::ofFloat(-asDouble(v));
    }
    return power(live);
  }

  Value power(bool live) {
    Value base = postfix(live);
    if (isOp("**")) {
      ++pos_;
      Value exponent = unary(live);
      if (live) return numeric("**", base, exponent);
    }
    return base;
  }

  Value postfix(bool live) {
    Value v;
    std::string callee;
    if (peek().kind == Token::Kind::Name && tokens_[pos_ + 1].kind == Token::Kind::Op && tokens_[pos_ + 1].text == "(") {
      callee = peek().text;
      pos_ += 2;
      std::vector<Value> args;
      while (!isOp(")")) {
        args.push_back(conditional(live));
        if (!isOp(",")) break;
        ++pos_;
      }
      expect(")");
      if (live) {
        std::string fn = callee;
        for (const char* prefix : {"math.", "xacro."}) {
          if (fn.rfind(prefix, 0) == 0) fn = fn.substr(std::string(prefix).size());
        }
        v = callBuiltin(fn, args, names_);
      }
    } else {
      v = atom(live);
    }
    while (isOp("[")) {
      ++pos_;
      Value index = conditional(live);
      expect("]");
      if (live) v = subscript(v, index);
    }
    return v;
  }

  static Value subscript(const Value& v, const Value& index) {
    if (v.kind == Value::Kind::List || v.kind == Value::Kind::String) {
      if (!integral(index)) fail("an index must be an int, not " + typeName(index));
      const long long size = static_cast<long long>(v.kind == Value::Kind::List ? v.list->size() : v.text.size());
      long long i = asInt(index);
      if (i < 0) i += size;
      if (i < 0 || i >= size) fail("index " + std::to_string(asInt(index)) + " out of range (size " + std::to_string(size) + ")");
      return v.kind == Value::Kind::List ? (*v.list)[static_cast<std::size_t>(i)]
                                         : Value::ofString(v.text.substr(static_cast<std::size_t>(i), 1));
    }
    if (v.kind == Value::Kind::Dict) {
      const auto it = v.dict->find(str(index));
      if (it == v.dict->end()) fail("key " + repr(index) + " not in the dict");
      return it->second;
    }
    fail("a " + typeName(v) + " cannot be indexed");
  }

  Value atom(bool live) {
    const Token t = peek();
    ++pos_;
    switch (t.kind) {
      case Token::Kind::Number: return t.number;
      case Token::Kind::String: return Value::ofString(t.text);
      case Token::Kind::End: fail("the expression ends too early");
      case Token::Kind::Name: return name(t.text, live);
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
      std::map<std::string, Value> items;
      while (!isOp("}")) {
        const Value key = conditional(live);
        expect(":");
        items[str(key)] = conditional(live);
        if (!isOp(",")) break;
        ++pos_;
      }
      expect("}");
      return Value::ofDict(std::move(items));
    }
    fail("unexpected '" + t.text + "'");
  }

  Value name(const std::string& n, bool live) {
    if (n == "True") return Value::ofBool(true);
    if (n == "False") return Value::ofBool(false);
    if (n == "None") return Value::none();
    if (!live) return Value::none();
    if (auto v = names_.lookup(n)) return *v;
    std::string bare = n;
    if (bare.rfind("math.", 0) == 0) bare = bare.substr(5);
    if (bare == "pi") return Value::ofFloat(M_PI);
    if (bare == "e") return Value::ofFloat(M_E);
    if (bare == "tau") return Value::ofFloat(2.0 * M_PI);
    if (bare == "inf") return Value::ofFloat(HUGE_VAL);
    if (bare == "nan") return Value::ofFloat(std::nan(""));
    fail("name '" + n + "' is not defined");
  }

  std::vector<Token> tokens_;
  std::size_t pos_ = 0;
  int nesting_ = 0;
  Names& names_;
};

}  // namespace

Value evaluate(const std::string& expression, Names& names) { return Parser(expression, names).parseAll(); }

}  // namespace servoloop::xacro
