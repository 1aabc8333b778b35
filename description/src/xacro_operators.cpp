#include "xacro_operators.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace servoloop::xacro {

void fail(const std::string& message) { throw ExpressionError(message); }

bool isIntegral(const Value& v) { return v.kind == Value::Kind::Int || v.kind == Value::Kind::Bool; }

long long toInt(const Value& v) { return v.kind == Value::Kind::Bool ? (v.boolean ? 1 : 0) : v.integer; }

Value binaryOp(const std::string& op, const Value& a, const Value& b) {
  if (op == "+" && a.kind == Value::Kind::String && b.kind == Value::Kind::String) {
    if (a.text.size() + b.text.size() > kMaxStringBytes) {
      fail("'" + a.text.substr(0, 20) + "...' + '" + b.text.substr(0, 20) + "...' would make a string over " +
           std::to_string(kMaxStringBytes) + " bytes");
    }
    return Value::ofString(a.text + b.text);
  }
  if (op == "+" && a.kind == Value::Kind::List && b.kind == Value::Kind::List) {
    std::vector<Value> items(*a.list);
    items.insert(items.end(), b.list->begin(), b.list->end());
    return Value::ofList(std::move(items));
  }
  if (op == "*" && a.kind == Value::Kind::String && isIntegral(b)) {
    const long long times = std::max(toInt(b), 0LL);
    if (times > 0 && static_cast<long long>(a.text.size()) > static_cast<long long>(kMaxStringBytes) / times) {
      fail("'" + a.text.substr(0, 20) + "' * " + std::to_string(times) + " would make a string over " +
           std::to_string(kMaxStringBytes) + " bytes");
    }
    std::string out;
    for (long long k = 0; k < times; ++k) out += a.text;
    return Value::ofString(out);
  }
  if (!a.isNumber() || !b.isNumber()) {
    fail("unsupported operand types for " + op + ": " + typeName(a) + " (" + repr(a) + ") and " + typeName(b) +
         " (" + repr(b) + ")");
  }
  if (isIntegral(a) && isIntegral(b) && op != "/") {
    // Python's integers have no bound; a result beyond 64 bits is taken as a
    // float here (below), as no robot description needs one exactly.
    const long long x = toInt(a);
    const long long y = toInt(b);
    long long r = 0;
    if (op == "+" && !__builtin_add_overflow(x, y, &r)) return Value::ofInt(r);
    if (op == "-" && !__builtin_sub_overflow(x, y, &r)) return Value::ofInt(r);
    if (op == "*" && !__builtin_mul_overflow(x, y, &r)) return Value::ofInt(r);
    if ((op == "//" || op == "%") && y == 0) fail("integer division or modulo by zero");
    if ((op == "//" || op == "%") && !(y == -1 && x == std::numeric_limits<long long>::min())) {
      long long q = x / y;
      if ((x % y != 0) && ((x < 0) != (y < 0))) --q;
      return op == "//" ? Value::ofInt(q) : Value::ofInt(x - q * y);
    }
    if (op == "**" && y >= 0) {
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
  if (op == "+") return Value::ofFloat(x + y);
  if (op == "-") return Value::ofFloat(x - y);
  if (op == "*") return Value::ofFloat(x * y);
  if (op == "/") {
    if (y == 0.0) fail("division by zero");
    return Value::ofFloat(x / y);
  }
  if (op == "//" || op == "%") {
    if (y == 0.0) fail("float division or modulo by zero");
    const double q = std::floor(x / y);
    return op == "//" ? Value::ofFloat(q) : Value::ofFloat(x - q * y);
  }
  if (op == "**") return Value::ofFloat(std::pow(x, y));
  fail("unknown operator " + op);
}

bool equal(const Value& a, const Value& b) {
  if (a.isNumber() && b.isNumber()) return asDouble(a) == asDouble(b);
  if (a.kind != b.kind) return false;
  switch (a.kind) {
    case Value::Kind::None: return true;
    case Value::Kind::String: return a.text == b.text;
    case Value::Kind::List:
      return a.list->size() == b.list->size() && std::equal(a.list->begin(), a.list->end(), b.list->begin(), equal);
    case Value::Kind::Dict:
      // Equal dicts hold the same keys with equal values, in any order.
      return a.dict->size() == b.dict->size() && std::all_of(a.dict->begin(), a.dict->end(), [&](const auto& kv) {
               const Value* other = b.find(kv.first);
               return other != nullptr && equal(kv.second, *other);
             });
    default: return false;
  }
}

namespace {

// -1, 0 or 1 as a is ordered before, with or after b; lists compare item by
// item, as Python's.
int ordering(const std::string& op, const Value& a, const Value& b) {
  if (a.isNumber() && b.isNumber()) return asDouble(a) < asDouble(b) ? -1 : (asDouble(a) > asDouble(b) ? 1 : 0);
  if (a.kind == Value::Kind::String && b.kind == Value::Kind::String) {
    const int order = a.text.compare(b.text);
    return order < 0 ? -1 : (order > 0 ? 1 : 0);
  }
  if (a.kind == Value::Kind::List && b.kind == Value::Kind::List) {
    for (std::size_t i = 0; i < a.list->size() && i < b.list->size(); ++i) {
      if (!equal((*a.list)[i], (*b.list)[i])) return ordering(op, (*a.list)[i], (*b.list)[i]);
    }
    return a.list->size() < b.list->size() ? -1 : (a.list->size() > b.list->size() ? 1 : 0);
  }
  fail("'" + op + "' cannot compare " + typeName(a) + " (" + repr(a) + ") with " + typeName(b) + " (" + repr(b) + ")");
}

}  // namespace

bool compare(const std::string& op, const Value& a, const Value& b) {
  if (op == "==") return equal(a, b);
  if (op == "!=") return !equal(a, b);
  if (op == "in" || op == "not in") {
    bool found = false;
    if (b.kind == Value::Kind::String && a.kind == Value::Kind::String) {
      found = b.text.find(a.text) != std::string::npos;
    } else if (b.kind == Value::Kind::String) {
      fail("'in <str>' needs a str on its left, not " + aTypeName(a) + " (" + repr(a) + ")");
    } else if (b.kind == Value::Kind::List) {
      found = std::any_of(b.list->begin(), b.list->end(), [&](const Value& x) { return equal(a, x); });
    } else if (b.kind == Value::Kind::Dict) {
      found = b.find(str(a)) != nullptr;
    } else {
      fail("'in' needs a str, list or dict on its right, not " + aTypeName(b) + " (" + repr(b) + ")");
    }
    return op == "in" ? found : !found;
  }
  const int order = ordering(op, a, b);
  if (op == "<") return order < 0;
  if (op == "<=") return order <= 0;
  if (op == ">") return order > 0;
  return order >= 0;
}

SliceBounds sliceBounds(long long length, std::optional<long long> start, std::optional<long long> stop,
                        long long step) {
  // As CPython's PySlice_AdjustIndices.
  auto adjust = [&](std::optional<long long> bound, long long if_missing) {
    if (!bound) return if_missing;
    long long b = *bound;
    if (b < 0) {
      b = b < -length ? (step < 0 ? -1 : 0) : b + length;
    } else if (b >= length) {
      b = step < 0 ? length - 1 : length;
    }
    return b;
  };
  SliceBounds bounds;
  bounds.step = step;
  bounds.start = adjust(start, step < 0 ? length - 1 : 0);
  const long long end = adjust(stop, step < 0 ? -1 : length);
  if (step > 0 && end > bounds.start) bounds.count = (end - bounds.start - 1) / step + 1;
  if (step < 0 && end < bounds.start) bounds.count = (bounds.start - end - 1) / (-step) + 1;
  return bounds;
}

}  // namespace servoloop::xacro
