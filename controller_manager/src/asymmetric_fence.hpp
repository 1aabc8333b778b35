#pragma once
// Asymmetric memory fences, for a store-then-load handshake between the
// real-time thread (which runs it every cycle) and a non-real-time thread
// (which runs it rarely), as userspace RCU does it.
//
// Both sides of such a handshake store one flag and then load the other's;
// each needs a full fence between the two, or the load may overtake the store
// (x86 allows that). A full fence (a locked instruction, about 5 ns and a
// drained store buffer) on every real-time cycle is avoidable: the real-time
// side only stops the compiler from reordering (light()), and the other side
// makes every running thread of the process execute a full fence (heavy():
// membarrier(2), a few microseconds). Either the heavy fence interrupts the
// real-time thread between its store and its load, which then sees the other
// side's store, or it comes before that store or after that load, and the
// usual argument for two full fences applies.
//
// Kernels (or seccomp filters) without membarrier's private expedited command
// make available() false; both sides then use seq_cst operations.
#include <atomic>

namespace servoloop::controller_manager::asymmetric_fence {

// Non-real-time. Registers the process for membarrier's private expedited
// command the first time; every call returns the first call's answer.
bool available() noexcept;

// Real-time side, only when available(): a compiler barrier.
inline void light() noexcept { std::atomic_signal_fence(std::memory_order_seq_cst); }

// Non-real-time side: a full fence on every running thread of the process
// when available(), else a full fence on this thread.
void heavy() noexcept;

}  // namespace servoloop::controller_manager::asymmetric_fence
