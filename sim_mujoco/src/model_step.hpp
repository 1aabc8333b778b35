#pragma once
// One step of a MuJoCo model as mj_step takes it, split so that sensors can
// read the step's own forward pass.
#include <mujoco/mujoco.h>

namespace servoloop::sim_mujoco {

// Real-time. mj_step's sequence (checks, forward pass, integration) with two
// additions: `capture` runs after the forward pass and mj_rnePostConstraint
// (interaction forces at the state the step starts from), and after the
// integration every body's pose and velocity is brought up to date
// (mj_kinematics, mj_comPos, mj_comVel), so link states match the joint
// state the step ends in. The next step's forward pass recomputes all of
// it, so the motion is the same as with mj_step.
template <class Capture>
void stepModel(const mjModel* m, mjData* d, Capture&& capture) noexcept {
  if (m->opt.integrator != mjINT_EULER && m->opt.integrator != mjINT_RK4) {
    mj_step(m, d);
    return;
  }
  mj_checkPos(m, d);
  mj_checkVel(m, d);
  mj_forward(m, d);
  mj_checkAcc(m, d);
  mj_rnePostConstraint(m, d);
  capture();
  if (m->opt.integrator == mjINT_RK4) {
    mj_RungeKutta(m, d, 4);
  } else {
    mj_Euler(m, d);
  }
  mj_kinematics(m, d);
  mj_comPos(m, d);
  mj_comVel(m, d);
}

}  // namespace servoloop::sim_mujoco
