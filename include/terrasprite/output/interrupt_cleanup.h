// SPDX-License-Identifier: MIT
// What an interrupted run (SIGINT, SIGTERM, SIGHUP) leaves behind: nothing of its own.
#pragma once
#include <filesystem>
#include <functional>

namespace terrasprite {

/// Blocks SIGINT, SIGTERM and SIGHUP in the calling thread and starts one
/// thread that waits for them; ignores SIGXFSZ, so a write past a file-size
/// limit fails (EFBIG) and is reported like a full disk. Call it first thing in main(), before any
/// other thread exists, so every later thread inherits the blocked mask. On a signal that thread
/// removes every path currently registered with a CleanupOnInterrupt, prints one line on stderr
/// naming them, and exits with status 128 + signal. Without this call the registry below is inert
/// (tests, library users).
void install_interrupt_cleanup();

/// Runs `step` (e.g. creating a directory inside a registered path) unless an
/// interrupt clean-up has begun; then it blocks until the process exits, so
/// nothing is recreated behind the clean-up.
void run_unless_interrupted(const std::function<void()>& step);

/// Blocks forever if an interrupt clean-up has begun (the process is about to
/// exit with 128 + signal); returns at once otherwise. main() calls it before
/// reporting an error, so a failure caused by the clean-up is not reported
/// in place of the interrupt.
inline void hold_if_interrupted() {
  run_unless_interrupted([] {});
}

/// Registers a file or directory that this process created and that must not
/// survive an interrupt (a `.partial` output, a temporary file beside a
/// target). The destructor only unregisters; removing the path on an ordinary
/// failure stays the owner's job.
class CleanupOnInterrupt {
 public:
  explicit CleanupOnInterrupt(std::filesystem::path path);
  ~CleanupOnInterrupt();
  CleanupOnInterrupt(const CleanupOnInterrupt&) = delete;
  CleanupOnInterrupt& operator=(const CleanupOnInterrupt&) = delete;

  /// Runs `step` (e.g. the rename that puts a finished output in place) while
  /// no interrupt cleanup can run, then unregisters the path. An interrupt
  /// arriving meanwhile waits and then finds the output complete.
  void release_after(const std::function<void()>& step);

 private:
  std::filesystem::path path_;
  bool registered_ = true;
};

}  // namespace terrasprite
