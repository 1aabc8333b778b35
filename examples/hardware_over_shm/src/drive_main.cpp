// servoloop_example_drive: a stand-in for a fieldbus master and its motor
// drives. It simulates one motor per joint on its own clock (a rotor of
// inertia J with viscous friction b, driven by the torque command:
// J·dω/dt = τ − b·ω), measures each with an incremental encoder, and
// publishes the counts, velocities and a heartbeat in shared memory
// (drive_link.hpp) every cycle, taking torque commands from it.
//
//   servoloop_example_drive --name servoloop_example_drive --joints 1
//
// SIGINT or SIGTERM end it (and with --unlink remove the shared-memory
// object); killed, it leaves the object behind with a heartbeat that stops,
// which is how the hardware plugin notices.
#include <csignal>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <exception>
#include <string>

#include <CLI/CLI.hpp>

#include "shm_drive/drive_link.hpp"

namespace {

volatile std::sig_atomic_t g_stop = 0;
void onSignal(int) { g_stop = 1; }

struct Motor {
  double angle = 0.0;     // rad
  double velocity = 0.0;  // rad/s
};

}  // namespace

int main(int argc, char** argv) {
  std::string name = "servoloop_example_drive";
  unsigned joints = 1;
  double counts_per_rev = 4096.0;
  double inertia = 0.01;  // kg·m²
  double damping = 0.05;  // N·m·s/rad
  double rate_hz = 4000.0;
  bool unlink = false;
  CLI::App app{"A simulated motor drive behind shared memory, for servoloop's hardware_over_shm example"};
  app.add_option("--name", name, "Shared-memory object name (/dev/shm/NAME)")->capture_default_str();
  app.add_option("--joints", joints, "Motors (1 to 16)")->check(CLI::Range(1u, 16u))->capture_default_str();
  app.add_option("--counts-per-rev", counts_per_rev, "Encoder counts per revolution")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  app.add_option("--inertia", inertia, "Rotor inertia, kg·m²")->check(CLI::PositiveNumber)->capture_default_str();
  app.add_option("--damping", damping, "Viscous friction, N·m·s/rad")->check(CLI::NonNegativeNumber)->capture_default_str();
  app.add_option("--rate", rate_hz, "Drive cycle rate, Hz")->check(CLI::Range(10.0, 100000.0))->capture_default_str();
  app.add_flag("--unlink", unlink, "Remove the shared-memory object on exit");
  CLI11_PARSE(app, argc, argv);

  std::signal(SIGINT, onSignal);
  std::signal(SIGTERM, onSignal);
  try {
    const shm_drive::DriveLink link = shm_drive::DriveLink::create(name, joints, unlink);
    shm_drive::DriveImage& image = link.image();
    Motor motors[shm_drive::kMaxJoints];
    const double counts_per_rad = counts_per_rev / (2.0 * M_PI);
    const auto period_ns = static_cast<std::int64_t>(std::llround(1e9 / rate_hz));
    std::int64_t next_ns = shm_drive::DriveLink::nowNs();
    std::int64_t previous_ns = next_ns;
    std::printf("drive '%s': %u motor(s) at %.0f Hz, %.0f counts/rev\n", name.c_str(), joints, rate_hz, counts_per_rev);
    std::fflush(stdout);
    while (g_stop == 0) {
      const std::int64_t now_ns = shm_drive::DriveLink::nowNs();
      const double dt = static_cast<double>(now_ns - previous_ns) * 1e-9;  // the drive's own clock
      previous_ns = now_ns;
      for (unsigned j = 0; j < joints; ++j) {
        Motor& m = motors[j];
        double torque = image.torque_command[j].load(std::memory_order_relaxed);
        if (!std::isfinite(torque)) torque = 0.0;  // a drive ignores garbage
        m.velocity += (torque - damping * m.velocity) / inertia * dt;  // semi-implicit Euler
        m.angle += m.velocity * dt;
        image.encoder_counts[j].store(std::llround(m.angle * counts_per_rad), std::memory_order_relaxed);
        image.velocity_counts_per_s[j].store(m.velocity * counts_per_rad, std::memory_order_relaxed);
      }
      image.heartbeat_ns.store(now_ns, std::memory_order_release);
      next_ns += period_ns;
      const timespec wake{static_cast<time_t>(next_ns / 1000000000), static_cast<long>(next_ns % 1000000000)};
      clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &wake, nullptr);
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  }
  return 0;
}
