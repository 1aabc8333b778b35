#pragma once
// The link between the drive process and the hardware plugin: one POSIX
// shared-memory object (/dev/shm/<name>) holding the drive's state and the
// plugin's commands — a stand-in for a fieldbus master's process image.
//
//   drive  → plugin: encoder counts and velocities of each joint, and a
//                    heartbeat (the drive's CLOCK_MONOTONIC at its last cycle);
//   plugin → drive:  a torque command per joint (N·m).
//
// Every field is a lock-free atomic, so the two processes never race on
// memory and neither side ever waits for the other: the plugin's read() and
// write() are a few loads and stores, safe on the real-time thread.
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <string>

namespace shm_drive {

inline constexpr std::uint64_t kMagic = 0x315f564952445653;  // "SVDRIV_1"
inline constexpr std::size_t kMaxJoints = 16;

struct DriveImage {
  std::atomic<std::uint64_t> magic{0};
  std::atomic<std::uint32_t> joint_count{0};
  std::atomic<std::int64_t> heartbeat_ns{0};  // written last in each drive cycle (release)
  std::atomic<std::int64_t> encoder_counts[kMaxJoints]{};
  std::atomic<double> velocity_counts_per_s[kMaxJoints]{};
  std::atomic<double> torque_command[kMaxJoints]{};  // written by the plugin
};
static_assert(std::atomic<double>::is_always_lock_free && std::atomic<std::int64_t>::is_always_lock_free,
              "the drive image needs lock-free atomics to be shared between processes");

// A mapping of the drive image. Move-only; unmaps on destruction (and, for the
// drive that created it with unlink_on_close, removes the object).
class DriveLink {
 public:
  // The drive's side: creates the object (or takes over one a killed drive
  // left behind, so a plugin still attached to it sees the new drive) and
  // initialises it for joint_count joints. Throws std::runtime_error when a
  // drive of that name is still running (its heartbeat moves within 250 ms)
  // or the name holds something else.
  static DriveLink create(const std::string& name, std::uint32_t joint_count, bool unlink_on_close);
  // The plugin's side: attaches to a drive's object. Throws std::runtime_error
  // naming the object and what to do when there is none or it is not a drive's.
  static DriveLink attach(const std::string& name);

  DriveLink(DriveLink&& other) noexcept;
  DriveLink& operator=(DriveLink&&) = delete;
  DriveLink(const DriveLink&) = delete;
  ~DriveLink();

  DriveImage& image() const { return *image_; }

  // CLOCK_MONOTONIC in ns: the clock the heartbeat is in (shared by every
  // process on the machine).
  static std::int64_t nowNs() noexcept;

 private:
  DriveLink(std::string name, DriveImage* image, bool unlink_on_close)
      : name_(std::move(name)), image_(image), unlink_on_close_(unlink_on_close) {}

  std::string name_;
  DriveImage* image_ = nullptr;
  bool unlink_on_close_ = false;
};

}  // namespace shm_drive
