// The action registry: serving, listing, sending goals by name and type,
// withdrawing an action when its registration goes, and the goal JSON of
// control_msgs/FollowJointTrajectory (node/action_json.hpp).
#include <memory>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "thrown_message.hpp"
#include "servoloop/core/errors.hpp"
#include "servoloop/node/action_json.hpp"
#include "servoloop/realtime/action_registry.hpp"

namespace servoloop::realtime {
namespace {

using servoloop::testing::thrownMessage;

using ::testing::HasSubstr;

// A server that records the goals it gets and ends each as told.
class RecordingServer : public ActionServer {
 public:
  class Goal : public ActionGoal {
   public:
    GoalState state() const override { return state_; }
    void cancel() override { state_ = GoalState::canceled; }
    bool feedback(void*) const override { return false; }
    void result(void* out) const override { static_cast<control_msgs::FollowJointTrajectoryResult*>(out)->error_code = 7; }
    GoalState state_ = GoalState::active;
  };
  std::shared_ptr<ActionGoal> sendGoal(const void* goal) override {
    last_goal = *static_cast<const control_msgs::FollowJointTrajectoryGoal*>(goal);
    ++goals;
    return std::make_shared<Goal>();
  }
  control_msgs::FollowJointTrajectoryGoal last_goal;
  int goals = 0;
};

constexpr const char* kType = "control_msgs/FollowJointTrajectory";

TEST(ActionRegistry, ServesListsSendsAndWithdraws) {
  ActionRegistry registry;
  auto server = std::make_shared<RecordingServer>();
  {
    ActionRegistration registration = registry.add("arm/follow_joint_trajectory", kType, server);
    ASSERT_EQ(registry.list().size(), 1u);
    EXPECT_EQ(registry.list()[0].name, "/arm/follow_joint_trajectory");
    EXPECT_EQ(registry.list()[0].type, kType);

    const auto goal = node::sendGoalJson(
        registry, "/arm/follow_joint_trajectory", "",
        {{"trajectory", {{"joint_names", {"a"}}, {"points", {{{"positions", {1.0}}, {"time_from_start", 2.0}}}}}},
         {"goal_tolerance", {{{"name", "a"}, {"position", 0.1}}}},
         {"goal_time_tolerance", 0.5}});
    EXPECT_EQ(server->goals, 1);
    EXPECT_EQ(server->last_goal.trajectory.joint_names, std::vector<std::string>{"a"});
    EXPECT_DOUBLE_EQ(server->last_goal.trajectory.points.at(0).time_from_start, 2.0);
    EXPECT_DOUBLE_EQ(server->last_goal.goal_tolerance.at(0).position, 0.1);
    EXPECT_DOUBLE_EQ(server->last_goal.goal_time_tolerance, 0.5);
    EXPECT_EQ(node::resultJson(kType, *goal)["error_code"], 7);
    EXPECT_TRUE(node::feedbackJson(kType, *goal).is_null());

    EXPECT_THAT(thrownMessage([&] { (void)registry.add("/arm/follow_joint_trajectory", kType, server); }),
                HasSubstr("already served"));
    EXPECT_THAT(thrownMessage([&] { registry.sendGoal("/arm/follow_joint_trajectory", "other_msgs/Other", nullptr); }),
                HasSubstr("is of type control_msgs/FollowJointTrajectory"));
    EXPECT_THAT(thrownMessage([&] { registry.sendGoal("/arm/nothing", kType, nullptr); }),
                HasSubstr("actions are: /arm/follow_joint_trajectory"));
  }
  EXPECT_TRUE(registry.list().empty());  // the registration went: so did the action
  EXPECT_THAT(thrownMessage([&] { registry.sendGoal("/arm/follow_joint_trajectory", kType, nullptr); }),
              HasSubstr("serves no action"));
}

TEST(ActionRegistry, RegistrationMayOutliveTheRegistry) {
  ActionRegistration registration;
  {
    ActionRegistry registry;
    registration = registry.add("/a", kType, std::make_shared<RecordingServer>());
  }
  registration.reset();  // nothing to withdraw from: no crash
  EXPECT_FALSE(registration.active());
}

TEST(ActionRegistry, GoalJsonErrorsNameTheField) {
  ActionRegistry registry;
  ActionRegistration registration = registry.add("/a", kType, std::make_shared<RecordingServer>());
  const auto send = [&](const nlohmann::json& goal) { node::sendGoalJson(registry, "/a", kType, goal); };
  EXPECT_THAT(thrownMessage([&] { send({{"trajectry", nlohmann::json::object()}}); }), HasSubstr("field 'trajectry'"));
  EXPECT_THAT(thrownMessage([&] { send({{"goal_tolerance", {{{"position", 0.1}}}}}); }),
              HasSubstr("goal_tolerance[0].name"));
  EXPECT_THAT(thrownMessage([&] { send({{"goal_time_tolerance", nullptr}}); }), HasSubstr("goal_time_tolerance"));
  EXPECT_THAT(thrownMessage([&] { send({{"trajectory", {{"points", {{{"positions", {nullptr}}}}}}}}); }),
              HasSubstr("points[0].positions[0] is nan"));
  EXPECT_THAT(thrownMessage([&] { node::sendGoalJson(registry, "/a", "x_msgs/X", nlohmann::json::object()); }),
              HasSubstr("unknown action type 'x_msgs/X'"));
}

}  // namespace
}  // namespace servoloop::realtime
