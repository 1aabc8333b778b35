// Reading a request's fields (ipc_protocol.hpp): a field of the wrong type is
// one error naming the request, the field, what it must be and the value
// given; nlohmann's own words never reach the client.
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "servoloop/core/errors.hpp"
#include "servoloop/ipc/ipc_protocol.hpp"

namespace servoloop::ipc {
namespace {

using nlohmann::json;

template <class Read>
std::string errorOf(Read read) {
  try {
    read();
  } catch (const Error& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(IpcRequestField, WrongTypesNameTheRequestTheFieldTheTypeAndTheValue) {
  const json stats = json::parse(R"({"op": "control.stats", "reset": "yes"})");
  EXPECT_EQ(errorOf([&] { requestBool(stats, "reset", false); }),
            "control.stats: 'reset' must be true or false, got \"yes\"");
  const json swap = json::parse(R"({"op": "control.switch", "timeout": "soon", "start": 3})");
  EXPECT_EQ(errorOf([&] { requestNumber(swap, "timeout", 0.0, "a number of seconds"); }),
            "control.switch: 'timeout' must be a number of seconds, got \"soon\"");
  EXPECT_EQ(errorOf([&] { requestString(swap, "start", ""); }), "control.switch: 'start' must be a string, got 3");
  EXPECT_EQ(errorOf([&] { requireRequestString(swap, "name"); }),
            "control.switch: 'name' is required (a non-empty string)");
  EXPECT_EQ(errorOf([&] { requireRequestUnsigned(json{{"op", "action.status"}, {"goal_id", -1}}, "goal_id"); }),
            "action.status: 'goal_id' must be a whole number >= 0, got -1");
  // A long value is cut short.
  const std::string shown = errorOf([&] { requestBool(json{{"op", "x"}, {"f", std::string(500, 'a')}}, "f", false); });
  EXPECT_LT(shown.size(), 200u) << shown;
}

TEST(IpcRequestField, AbsentOrNullFieldsGiveTheFallbackAndGoodOnesTheirValue) {
  const json request = json::parse(R"({"op": "control.switch", "timeout": 2.5, "start_asap": true, "strictness": null})");
  EXPECT_DOUBLE_EQ(requestNumber(request, "timeout", 0.0), 2.5);
  EXPECT_TRUE(requestBool(request, "start_asap", false));
  EXPECT_FALSE(requestBool(request, "absent", false));
  EXPECT_EQ(requestString(request, "strictness", "strict"), "strict");
  EXPECT_DOUBLE_EQ(requestNumber(json{{"op", "x"}, {"n", 3}}, "n", 0.0), 3.0);
}

TEST(IpcRequestField, AJsonExceptionIsToldInTheSameStyle) {
  const json request = json::parse(R"({"op": "control.stats", "reset": "yes"})");
  try {
    (void)request["reset"].get<bool>();
    FAIL() << "nlohmann accepted a string as a boolean";
  } catch (const json::exception& e) {
    const std::string text = describeJsonException(request, e);
    EXPECT_EQ(text.find("[json.exception"), std::string::npos) << text;
    EXPECT_NE(text.find("control.stats: the request has a field of the wrong type or value (a field must be boolean "
                        "but is string)"),
              std::string::npos)
        << text;
  }
}

}  // namespace
}  // namespace servoloop::ipc
