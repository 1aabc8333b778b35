#include "servoloop/sim_mujoco/mujoco_world.hpp"

#include <algorithm>
#include <string>
#include <vector>

#include <mujoco/mujoco.h>

#include "mjcf_compile.hpp"
#include "model_step.hpp"
#include "servoloop/core/errors.hpp"
#include "servoloop/core/logging.hpp"
#include "servoloop/sim_mujoco/mujoco_physics.hpp"

namespace servoloop::sim_mujoco {

void MujocoWorld::ModelDeleter::operator()(mjModel_* model) const noexcept { mj_deleteModel(model); }
void MujocoWorld::DataDeleter::operator()(mjData_* data) const noexcept { mj_deleteData(data); }

MujocoWorld::MujocoWorld() = default;
MujocoWorld::~MujocoWorld() = default;

void MujocoWorld::init(const hardware_interface::SimulatedWorldSettings& settings) {
  if (initialised_) throw Error("mujoco world: init() called twice");
  settings_ = settings;
  initialised_ = true;
}

ReturnType MujocoWorld::step() noexcept {
  if (!model_) return ReturnType::ok;
  const bool sensors =
      std::any_of(members_.begin(), members_.end(), [](const Member& member) { return member.robot->hasSensors(); });
  if (sensors) {
    stepModel(model_.get(), data_.get(), [this]() noexcept {
      for (const Member& member : members_) member.robot->captureSensorData();
    });
  } else {
    mj_step(model_.get(), data_.get());
  }
  return ReturnType::ok;
}

void MujocoWorld::restart() {
  if (!model_) return;
  mjData& d = *data_;
  const std::vector<mjtNum> qpos(d.qpos, d.qpos + model_->nq);
  const std::vector<mjtNum> qvel(d.qvel, d.qvel + model_->nv);
  mj_resetData(model_.get(), data_.get());
  std::copy(qpos.begin(), qpos.end(), d.qpos);
  std::copy(qvel.begin(), qvel.end(), d.qvel);
  mj_forward(model_.get(), data_.get());
}

std::string MujocoWorld::robotName(const std::string& prefix) const {
  for (const Member& member : members_) {
    if (member.prefix == prefix) return member.name;
  }
  return "";
}

std::string MujocoWorld::newPrefix() { return "r" + std::to_string(next_prefix_++) + "/"; }

void MujocoWorld::add(MujocoPhysics& robot, MjcfParts parts, const std::string& source_name,
                      const std::string& robot_name) {
  if (!initialised_) throw Error("mujoco world: a robot joined a world that was not initialised");
  std::vector<Member> members = members_;
  members.push_back(Member{&robot, std::move(parts), robot.namePrefix(), robot_name});
  rebuild(std::move(members), source_name);
}

void MujocoWorld::remove(MujocoPhysics& robot) noexcept {
  std::vector<Member> members;
  for (const Member& member : members_) {
    if (member.robot != &robot) members.push_back(member);
  }
  if (members.size() == members_.size()) return;
  try {
    rebuild(std::move(members), "mujoco world");
  } catch (const std::exception& e) {
    // The others compiled before; a model without one of them should too.
    logger().error("mujoco world: taking a robot out failed: {}; its bodies stay in the world", e.what());
    std::erase_if(members_, [&](const Member& member) { return member.robot == &robot; });
  }
}

void MujocoWorld::rebuild(std::vector<Member> members, const std::string& source_name) {
  std::unique_ptr<mjModel_, ModelDeleter> model;
  std::unique_ptr<mjData_, DataDeleter> data;
  std::string mjcf;
  if (!members.empty()) {
    std::vector<const MjcfParts*> parts;
    for (const Member& member : members) parts.push_back(&member.parts);
    mjcf = mjcfOfWorld(settings_, parts);
    model.reset(compileMjcf(mjcf, source_name));
    data.reset(mj_makeData(model.get()));
    if (!data) throw Error(source_name + ": MuJoCo could not allocate the world's simulation data");
    // What stays carries its state over, joint by joint (names are unique
    // in the world: each robot's carry its prefix).
    if (model_) {
      const mjModel& from = *model_;
      const mjData& old = *data_;
      mjData& d = *data;
      for (int j = 0; j < model->njnt; ++j) {
        const char* name = mj_id2name(model.get(), mjOBJ_JOINT, j);
        const int before = name == nullptr ? -1 : mj_name2id(&from, mjOBJ_JOINT, name);
        if (before < 0) continue;
        const int type = model->jnt_type[j];
        const int qpos_count = type == mjJNT_FREE ? 7 : type == mjJNT_BALL ? 4 : 1;
        const int dof_count = type == mjJNT_FREE ? 6 : type == mjJNT_BALL ? 3 : 1;
        std::copy_n(old.qpos + from.jnt_qposadr[before], qpos_count, d.qpos + model->jnt_qposadr[j]);
        std::copy_n(old.qvel + from.jnt_dofadr[before], dof_count, d.qvel + model->jnt_dofadr[j]);
        std::copy_n(old.qacc_warmstart + from.jnt_dofadr[before], dof_count,
                    d.qacc_warmstart + model->jnt_dofadr[j]);
      }
      d.time = old.time;
    }
    mj_forward(model.get(), data.get());
  }
  // From here on nothing throws: the world and every robot move to the new model.
  std::swap(model_, model);
  std::swap(data_, data);
  mjcf_ = std::move(mjcf);
  members_ = std::move(members);
  for (const Member& member : members_) member.robot->bind(model_.get(), data_.get());
}

}  // namespace servoloop::sim_mujoco
