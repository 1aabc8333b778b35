// DriveLink: POSIX shared memory (shm_open, mmap) for the drive image.
#include "shm_drive/drive_link.hpp"

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <ctime>
#include <new>
#include <stdexcept>
#include <utility>

namespace shm_drive {
namespace {

std::string objectName(const std::string& name) { return name.starts_with("/") ? name : "/" + name; }

void* map(int fd, const std::string& name) {
  void* memory = mmap(nullptr, sizeof(DriveImage), PROT_READ | PROT_WRITE, MAP_SHARED, fd, 0);
  const int error = errno;
  close(fd);
  if (memory == MAP_FAILED) {
    throw std::runtime_error("drive link '" + name + "': mmap failed: " + std::strerror(error));
  }
  return memory;
}

}  // namespace

std::int64_t DriveLink::nowNs() noexcept {
  timespec ts{};
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return static_cast<std::int64_t>(ts.tv_sec) * 1000000000 + ts.tv_nsec;
}

DriveLink DriveLink::create(const std::string& name, std::uint32_t joint_count, bool unlink_on_close) {
  if (joint_count == 0 || joint_count > kMaxJoints) {
    throw std::runtime_error("drive link '" + name + "': " + std::to_string(joint_count) +
                             " joints; a drive has 1 to " + std::to_string(kMaxJoints));
  }
  const std::string object = objectName(name);
  const int fd = shm_open(object.c_str(), O_RDWR | O_CREAT, 0600);
  if (fd < 0) {
    throw std::runtime_error("drive link '" + name + "': shm_open(" + object + ") failed: " + std::strerror(errno));
  }
  // An object of that name already there: a drive that was killed (take it
  // over: a plugin still attached sees the new drive), a drive still running
  // (refuse), or something else (refuse rather than overwrite it).
  struct stat info {};
  if (fstat(fd, &info) != 0) {
    const int error = errno;
    close(fd);
    throw std::runtime_error("drive link '" + name + "': fstat failed: " + std::strerror(error));
  }
  const auto size = static_cast<std::size_t>(info.st_size);
  if (size != 0 && size != sizeof(DriveImage)) {
    close(fd);
    throw std::runtime_error("'/dev/shm" + object + "' exists and is not a drive image; choose another drive name");
  }
  if (size == 0 && ftruncate(fd, sizeof(DriveImage)) != 0) {
    const int error = errno;
    close(fd);
    throw std::runtime_error("drive link '" + name + "': ftruncate failed: " + std::strerror(error));
  }
  void* memory = map(fd, name);
  if (size != 0) {
    const auto* existing = static_cast<const DriveImage*>(memory);
    if (existing->magic.load(std::memory_order_acquire) != kMagic) {
      munmap(memory, sizeof(DriveImage));
      throw std::runtime_error("'/dev/shm" + object + "' exists and is not a drive image; choose another drive name");
    }
    // A running drive beats at 10 Hz at least: watch for 250 ms.
    const std::int64_t beat = existing->heartbeat_ns.load(std::memory_order_acquire);
    const timespec pause{0, 250000000};
    nanosleep(&pause, nullptr);
    if (existing->heartbeat_ns.load(std::memory_order_acquire) != beat) {
      munmap(memory, sizeof(DriveImage));
      throw std::runtime_error("a drive named '" + name + "' is running already; stop it or choose another name");
    }
  }
  // The image's atomics begin their lifetime here (a killed drive's are
  // replaced): zero counts, velocities and commands, no heartbeat yet.
  auto* image = new (memory) DriveImage{};
  image->joint_count.store(joint_count, std::memory_order_relaxed);
  image->magic.store(kMagic, std::memory_order_release);
  return DriveLink(object, image, unlink_on_close);
}

DriveLink DriveLink::attach(const std::string& name) {
  const std::string object = objectName(name);
  const int fd = shm_open(object.c_str(), O_RDWR, 0);
  if (fd < 0) {
    throw std::runtime_error("no drive '" + name + "' (shm_open " + object + ": " + std::strerror(errno) +
                             "); start the drive process first: servoloop_example_drive --name " + name);
  }
  struct stat info {};
  if (fstat(fd, &info) != 0 || static_cast<std::size_t>(info.st_size) < sizeof(DriveImage)) {
    close(fd);
    throw std::runtime_error("'/dev/shm" + object + "' is not a drive image (too small); is another program using "
                             "the name? choose another drive name");
  }
  // The drive constructed the image; this process only maps it.
  auto* image = static_cast<DriveImage*>(map(fd, name));
  if (image->magic.load(std::memory_order_acquire) != kMagic) {
    munmap(image, sizeof(DriveImage));
    throw std::runtime_error("'/dev/shm" + object + "' is not a drive image (wrong magic); choose another drive name");
  }
  return DriveLink(object, image, false);
}

DriveLink::DriveLink(DriveLink&& other) noexcept
    : name_(std::move(other.name_)), image_(std::exchange(other.image_, nullptr)),
      unlink_on_close_(std::exchange(other.unlink_on_close_, false)) {}

DriveLink::~DriveLink() {
  if (image_ == nullptr) return;
  munmap(image_, sizeof(DriveImage));
  if (unlink_on_close_) shm_unlink(name_.c_str());
}

}  // namespace shm_drive
