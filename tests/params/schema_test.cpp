// params::Schema, the declarative reader every YAML reader uses: each case
// below is a mistake a user makes in a file, and what they get back.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "log_capture.hpp"
#include "servoloop/core/errors.hpp"
#include "servoloop/params/parameters_yaml.hpp"
#include "servoloop/params/schema.hpp"
#include "thrown_message.hpp"

namespace servoloop::params {
namespace {

using ::testing::HasSubstr;
using servoloop::testing::thrownMessage;

// A motor's settings, as a reader would declare them.
Schema motorSchema(UnknownKeys unknown) {
  return Schema("motor settings",
                {
                    {"max_effort", ValueType::number, "effort limit (N·m)", {.min = 0.0, .min_exclusive = true, .default_number = 10.0}},
                    {"gear_ratio", ValueType::number, "reduction", {.min = 1.0, .max = 200.0, .default_number = 1.0}},
                    {"poles", ValueType::integer, "pole pairs", {.min = 1, .max = 64, .default_number = 7}},
                    {"inverted", ValueType::boolean, "the direction is reversed"},
                    {"name", ValueType::text, "a label", {.required = true}},
                    {"joints", ValueType::text_list, "driven joints"},
                    {"offsets", ValueType::number_list, "offsets (rad)"},
                },
                unknown);
}

Parameters view(const std::string& yaml) { return parametersFromYaml(YAML::Load(yaml), "/robot/motor"); }

TEST(Schema, ValuesAndDeclaredDefaults) {
  const Schema schema = motorSchema(UnknownKeys::error);
  const Parameters given = view("{name: m1, max_effort: 2.5, poles: 4, inverted: true, joints: [a, b]}");
  EXPECT_TRUE(schema.check(given).empty());
  EXPECT_EQ(schema.number(given, "max_effort"), 2.5);
  EXPECT_EQ(schema.integer(given, "poles"), 4);
  EXPECT_TRUE(schema.boolean(given, "inverted"));
  EXPECT_EQ(schema.text(given, "name"), "m1");
  EXPECT_EQ(schema.textList(given, "joints"), (std::vector<std::string>{"a", "b"}));
  // Absent keys read as declared.
  EXPECT_EQ(schema.number(given, "gear_ratio"), 1.0);
  EXPECT_FALSE(schema.boolean(view("{name: m1}"), "inverted"));
  EXPECT_EQ(schema.integer(view("{name: m1}"), "poles"), 7);
}

TEST(Schema, WrongTypesAndRangesNameThePathTheExpectationAndTheValue) {
  const Schema schema = motorSchema(UnknownKeys::error);
  const auto errorOf = [&](const std::string& yaml) {
    return thrownMessage<ConfigError>([&] { schema.check(view(yaml)); });
  };
  EXPECT_THAT(errorOf("{name: m, max_effort: strong}"),
              HasSubstr("/robot/motor/max_effort: expected a number, got 'strong' (effort limit (N·m))"));
  EXPECT_THAT(errorOf("{name: m, max_effort: 0}"), HasSubstr("/robot/motor/max_effort: expected a number > 0, got '0'"));
  EXPECT_THAT(errorOf("{name: m, max_effort: .nan}"), HasSubstr("/robot/motor/max_effort: expected a number"));
  EXPECT_THAT(errorOf("{name: m, gear_ratio: 500}"),
              HasSubstr("/robot/motor/gear_ratio: expected a number from 1 to 200, got '500'"));
  EXPECT_THAT(errorOf("{name: m, poles: 2.5}"), HasSubstr("/robot/motor/poles: expected a whole number"));
  EXPECT_THAT(errorOf("{name: m, inverted: maybe}"),
              HasSubstr("/robot/motor/inverted: expected a boolean (true or false), got 'maybe'"));
  EXPECT_THAT(errorOf("{name: m, joints: a}"), HasSubstr("/robot/motor/joints: expected a list of names"));
  EXPECT_THAT(errorOf("{name: m, offsets: [0, x]}"), HasSubstr("/robot/motor/offsets[1]: expected a number, got 'x'"));
  EXPECT_THAT(errorOf("{max_effort: 1}"), HasSubstr("/robot/motor/name: missing (a label)"));
  EXPECT_THAT(errorOf("[1, 2]"), HasSubstr("/robot/motor: expected a map of motor settings (max_effort, gear_ratio"));
  // The typed reads check as check() does.
  EXPECT_THAT(thrownMessage<ConfigError>([&] { schema.number(view("{gear_ratio: 0.5}"), "gear_ratio"); }),
              HasSubstr("expected a number from 1 to 200, got '0.5'"));
}

TEST(Schema, UnknownKeysAreAnErrorAWarningOrAllowedWithTheClosestKnownKey) {
  const std::string yaml = "{name: m, max_efort: 3, colour: red}";
  EXPECT_THAT(thrownMessage<ConfigError>([&] { motorSchema(UnknownKeys::error).check(view(yaml)); }),
              HasSubstr("/robot/motor: unknown key 'max_efort'; did you mean 'max_effort'? (the motor settings are: "
                        "max_effort, gear_ratio, poles, inverted, name, joints, offsets)"));

  servoloop::test::LogCapture log;
  const auto unknown = motorSchema(UnknownKeys::warn).check(view(yaml));
  EXPECT_EQ(unknown, (std::vector<std::string>{"max_efort", "colour"}));
  EXPECT_EQ(log.count("unknown key 'max_efort' is ignored; did you mean 'max_effort'?"), 1u) << log.text();
  // Nothing near 'colour': no suggestion.
  EXPECT_EQ(log.count("unknown key 'colour' is ignored (the motor settings are"), 1u) << log.text();

  servoloop::test::LogCapture quiet;
  EXPECT_EQ(motorSchema(UnknownKeys::allow).check(view(yaml)).size(), 2u);
  EXPECT_EQ(quiet.count("unknown key"), 0u) << quiet.text();
}

TEST(Schema, DescribeListsEveryKeyWithTypeRangeDefaultAndMeaning) {
  const std::string text = motorSchema(UnknownKeys::error).describe();
  EXPECT_THAT(text, HasSubstr("max_effort: a number > 0, default 10 — effort limit (N·m)\n"));
  EXPECT_THAT(text, HasSubstr("gear_ratio: a number from 1 to 200, default 1 — reduction\n"));
  EXPECT_THAT(text, HasSubstr("name: a text, required — a label\n"));
}

}  // namespace
}  // namespace servoloop::params
