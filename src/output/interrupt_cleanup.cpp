// SPDX-License-Identifier: MIT
// SIGINT/SIGTERM/SIGHUP handled by a thread in sigwait(), not a signal handler, so
// the clean-up may use the filesystem library and a mutex safely.
#include "terrasprite/output/interrupt_cleanup.h"

#include <fmt/format.h>
#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

namespace terrasprite {
namespace {

namespace fs = std::filesystem;

struct Registry {
  std::mutex mutex;
  std::vector<fs::path> paths;
};

Registry& registry() {
  static Registry* r = new Registry;  // leaked: the waiting thread may outlive static destructors
  return *r;
}

[[noreturn]] void clean_up_and_exit(int sig) {
  Registry& r = registry();
  std::lock_guard lock(r.mutex);  // held until _exit: no commit can start meanwhile
  std::string removed;
  for (const fs::path& p : r.paths) {
    std::error_code ec;
    // A file may be created inside while we remove: try a few times.
    for (int attempt = 0; attempt < 3 && fs::exists(fs::symlink_status(p, ec)); ++attempt)
      fs::remove_all(p, ec);
    removed += (removed.empty() ? "" : ", ") + p.string();
  }
  const char* name = sig == SIGINT    ? "SIGINT"
                     : sig == SIGTERM ? "SIGTERM"
                     : sig == SIGHUP  ? "SIGHUP (the terminal closed)"
                                      : "a signal";
  fmt::print(stderr, "terrasprite: interrupted by {}; {}\n", name,
             removed.empty() ? std::string("no partial output to remove")
                             : "removed partial output " + removed);
  std::fflush(stderr);
  _exit(128 + sig);
}

}  // namespace

void install_interrupt_cleanup() {
  sigset_t set;
  sigemptyset(&set);
  sigaddset(&set, SIGINT);
  sigaddset(&set, SIGTERM);
  sigaddset(&set, SIGHUP);
  pthread_sigmask(SIG_BLOCK, &set, nullptr);
  // Past a file-size limit a write then fails with EFBIG, which every writer
  // reports as an error (and the partial output goes), instead of the signal
  // ending the process with the partial output left behind.
  signal(SIGXFSZ, SIG_IGN);
  registry();  // constructed before the thread can need it
  std::thread([set] {
    int sig = 0;
    while (sigwait(&set, &sig) != 0) {
    }
    clean_up_and_exit(sig);
  }).detach();
}

void run_unless_interrupted(const std::function<void()>& step) {
  std::lock_guard lock(registry().mutex);  // the clean-up holds it until _exit
  step();
}

CleanupOnInterrupt::CleanupOnInterrupt(fs::path path) : path_(std::move(path)) {
  Registry& r = registry();
  std::lock_guard lock(r.mutex);
  r.paths.push_back(path_);
}

CleanupOnInterrupt::~CleanupOnInterrupt() {
  if (registered_) release_after([] {});
}

void CleanupOnInterrupt::release_after(const std::function<void()>& step) {
  Registry& r = registry();
  std::lock_guard lock(r.mutex);
  step();  // may throw: the path stays registered
  auto it = std::find(r.paths.begin(), r.paths.end(), path_);
  if (it != r.paths.end()) r.paths.erase(it);
  registered_ = false;
}

}  // namespace terrasprite
