// SPDX-License-Identifier: MIT
// What every test executable shares: the one temporary directory type, the one
// process runner (shell commands and the built CLI), data paths.
#pragma once
#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <random>
#include <string>

namespace tstest {

/// A fresh directory under the system temp dir, removed on destruction.
struct TempDir {
  std::filesystem::path path;
  TempDir() {
    std::random_device rd;
    path = std::filesystem::temp_directory_path() /
           ("ts_test_" + std::to_string(rd()) + std::to_string(rd()));
    std::filesystem::create_directories(path);
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path, ec);
  }
  std::string operator/(const std::string& name) const { return (path / name).string(); }
};

struct CliResult {
  int status = -1;
  std::string output;  ///< stdout and stderr together
};

/// Runs a shell command line and captures its output (stdout and stderr; end
/// the command with `2>/dev/null` for stdout alone). status: the exit code, or
/// -1 when the shell could not start or the command died from a signal.
inline CliResult run_shell(const std::string& command) {
  std::string cmd = "{ " + command + "\n} 2>&1";
  CliResult r;
  FILE* p = popen(cmd.c_str(), "r");
  if (!p) return r;
  std::array<char, 4096> buf;
  std::size_t n;
  while ((n = fread(buf.data(), 1, buf.size(), p)) > 0) r.output.append(buf.data(), n);
  int st = pclose(p);
  r.status = WIFEXITED(st) ? WEXITSTATUS(st) : -1;
  return r;
}

/// Whether `tool` is a command on the PATH.
inline bool have_tool(const std::string& tool) {
  return run_shell("command -v '" + tool + "' >/dev/null").status == 0;
}

/// Runs the built CLI (TS_CLI) with `args` (shell syntax) and captures its output.
inline CliResult run_cli(const std::string& args) {
  return run_shell(std::string(TS_CLI) + " " + args);
}

/// Runs the built CLI under a wrapper command (e.g. "xvfb-run -a").
inline CliResult run_cli_prefixed(const std::string& prefix, const std::string& args) {
  return run_shell(prefix + " " + std::string(TS_CLI) + " " + args);
}

/// run_cli with `dir` as the working directory.
inline CliResult run_cli_in(const std::string& dir, const std::string& args) {
  return run_shell("cd '" + dir + "' && " + std::string(TS_CLI) + " " + args);
}

/// Every path under `dir` (links not followed) with its type, size and
/// modification time: equal before and after a run when it touched nothing.
inline std::map<std::string, std::string> snapshot(const std::filesystem::path& dir) {
  namespace fs = std::filesystem;
  std::map<std::string, std::string> s;
  for (const auto& e : fs::recursive_directory_iterator(dir)) {
    std::error_code ec;
    const auto st = fs::symlink_status(e.path(), ec);
    std::string info = std::to_string(int(st.type()));
    if (fs::is_regular_file(st))
      info += " " + std::to_string(fs::file_size(e.path(), ec)) + " " +
              std::to_string(fs::last_write_time(e.path(), ec).time_since_epoch().count());
    s[fs::relative(e.path(), dir).string()] = info;
  }
  return s;
}

/// ../shared/data beside the repository, or "" when it is absent.
inline std::string shared_data() {
  // TS_SHARED_DATA overrides (a worktree whose parent holds no shared/).
  if (const char* env = std::getenv("TS_SHARED_DATA"); env && std::filesystem::is_directory(env))
    return env;
  std::filesystem::path p = std::filesystem::path(TS_SOURCE_DIR).parent_path() / "shared" / "data";
  return std::filesystem::is_directory(p) ? p.string() : std::string();
}

}  // namespace tstest
