// SPDX-License-Identifier: MIT
// ffmpeg as a child process: raw RGBA on its stdin, H.264 MP4 out. A writer
// thread owns the pipe, so the caller's next frame renders while this one is
// encoded; the bounded queue keeps memory flat when the encoder is slower.
#include "terrasprite/output/video_writer.h"

#include <fcntl.h>
#include <fmt/format.h>
#include <poll.h>
#include <signal.h>
#include <spawn.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cassert>
#include <cerrno>
#include <chrono>
#include <condition_variable>
#include <cstdlib>
#include <cstring>
#include <deque>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <optional>
#include <thread>
#include <vector>

#include "terrasprite/common/error.h"
#include "terrasprite/output/interrupt_cleanup.h"
#include "terrasprite/output/output_file.h"

extern char** environ;

namespace terrasprite {

namespace fs = std::filesystem;

namespace {

constexpr std::array kPresets = {"ultrafast", "superfast", "veryfast", "faster",   "fast",
                                 "medium",    "slow",      "slower",   "veryslow", "placebo"};

std::string ffmpeg_program(const VideoOptions& o) {
  if (!o.ffmpeg.empty()) return o.ffmpeg;
  const char* env = std::getenv("TERRASPRITE_FFMPEG");
  return env && *env ? env : "ffmpeg";
}

/// Whether the (non-blocking) pipe `fd` can take bytes within `seconds`, or
/// has failed (the write then says how); false when the reader is stuck.
bool pipe_accepts_within(int fd, double seconds) {
  pollfd p{fd, POLLOUT, 0};
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  for (;;) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
        deadline - std::chrono::steady_clock::now());
    const int n = ::poll(&p, 1, int(std::max<long long>(0, left.count())));
    if (n > 0) return true;
    if (n == 0) return false;
    if (errno != EINTR) return true;
  }
}

/// The last non-empty line ffmpeg wrote on stderr (its error), or "".
std::string last_line(const std::string& file) {
  std::ifstream in(file);
  std::string line, last;
  while (std::getline(in, line))
    if (line.find_first_not_of(" \t\r") != std::string::npos) last = line;
  return last;
}

}  // namespace

void validate_video_options(const VideoOptions& o, const std::string& option) {
  if (!(o.fps > 0 && o.fps <= 1000))
    throw InputError(fmt::format("{} --fps {}: must be in (0, 1000]", option, o.fps));
  if (o.crf < 0 || o.crf > 51)
    throw InputError(fmt::format("{} --crf {}: must be between 0 and 51", option, o.crf));
  if (!(o.stall_seconds > 0 && o.stall_seconds <= 86400))
    throw InputError(
        fmt::format("{}: stall_seconds {:g}: must be in (0, 86400]", option, o.stall_seconds));
  if (std::find(kPresets.begin(), kPresets.end(), o.preset) == kPresets.end())
    throw InputError(
        fmt::format("{} --preset {}: not an x264 preset (ultrafast .. placebo)", option, o.preset));
}

struct VideoWriter::Impl {
  std::string file, partial, log;
  int width = 0, height = 0, enc_w = 0, enc_h = 0;
  std::size_t queue_cap = 4;
  pid_t pid = -1;
  int pipe_fd = -1;
  int frames = 0;
  bool finished = false;

  std::mutex m;
  std::condition_variable cv;
  std::deque<std::vector<std::uint8_t>> queue;
  bool closing = false;
  std::string write_error;  // set by the writer thread; empty while all is well
  std::thread writer;
  std::optional<CleanupOnInterrupt> guard;      // the partial file goes on an interrupt
  std::optional<CleanupOnInterrupt> log_guard;  // and so does ffmpeg's log
  double stall_s = 60;

  void spawn(const VideoOptions& o);
  void write_loop();
  void stop_child(bool kill_it, int* status);
  void discard();
  [[noreturn]] void fail(const std::string& why);
};

void VideoWriter::Impl::spawn(const VideoOptions& o) {
  const std::string prog = ffmpeg_program(o);
  const std::vector<std::string> args = {prog,
                                         "-hide_banner",
                                         "-loglevel",
                                         "error",
                                         "-y",
                                         "-f",
                                         "rawvideo",
                                         "-pix_fmt",
                                         "rgba",
                                         "-s",
                                         fmt::format("{}x{}", enc_w, enc_h),
                                         "-framerate",
                                         fmt::format("{}", o.fps),
                                         "-i",
                                         "pipe:0",
                                         "-an",
                                         "-c:v",
                                         "libx264",
                                         "-preset",
                                         o.preset,
                                         "-crf",
                                         std::to_string(o.crf),
                                         "-pix_fmt",
                                         "yuv420p",
                                         "-metadata",
                                         "comment=" + generator_name(),
                                         "-movflags",
                                         "+faststart",
                                         "-f",
                                         "mp4",
                                         partial};
  std::vector<char*> argv;
  for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);

  int fds[2];
  if (pipe2(fds, O_CLOEXEC) != 0)
    throw InputError(
        fmt::format("{}: cannot create a pipe to ffmpeg ({})", file, std::strerror(errno)));
  std::string log_tmpl = (fs::temp_directory_path() / "terrasprite_ffmpeg_XXXXXX").string();
  int log_fd = mkstemp(log_tmpl.data());
  log = log_fd >= 0 ? log_tmpl : "";
  if (!log.empty()) log_guard.emplace(log);

  posix_spawn_file_actions_t fa;
  posix_spawn_file_actions_init(&fa);
  posix_spawn_file_actions_adddup2(&fa, fds[0], 0);
  posix_spawn_file_actions_addopen(&fa, 1, "/dev/null", O_WRONLY, 0);
  if (log_fd >= 0) posix_spawn_file_actions_adddup2(&fa, log_fd, 2);
  int rc = posix_spawnp(&pid, prog.c_str(), &fa, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&fa);
  close(fds[0]);
  if (log_fd >= 0) close(log_fd);
  if (rc != 0) {
    close(fds[1]);
    if (!log.empty()) fs::remove(log);
    throw InputError(fmt::format("{}: cannot run {} ({}); install ffmpeg or set TERRASPRITE_FFMPEG",
                                 file, prog, std::strerror(rc)));
  }
  pipe_fd = fds[1];
  fcntl(pipe_fd, F_SETFL, fcntl(pipe_fd, F_GETFL) | O_NONBLOCK);
}

// Runs on the writer thread. SIGPIPE is blocked here so a dead encoder turns
// into EPIPE (an error message), not the death of the whole process.
void VideoWriter::Impl::write_loop() {
  sigset_t pipe_set;
  sigemptyset(&pipe_set);
  sigaddset(&pipe_set, SIGPIPE);
  pthread_sigmask(SIG_BLOCK, &pipe_set, nullptr);
  for (;;) {
    std::vector<std::uint8_t> buf;
    {
      std::unique_lock lock(m);
      cv.wait(lock, [&] { return !queue.empty() || closing; });
      if (queue.empty()) return;
      buf = std::move(queue.front());
      queue.pop_front();
    }
    cv.notify_all();
    std::size_t done = 0;
    while (done < buf.size()) {
      if (!pipe_accepts_within(pipe_fd, stall_s)) {
        std::lock_guard lock(m);
        write_error = fmt::format("ffmpeg read nothing for {:g} s", stall_s);
        queue.clear();
        cv.notify_all();
        return;
      }
      ssize_t n = ::write(pipe_fd, buf.data() + done, buf.size() - done);
      if (n < 0 && (errno == EINTR || errno == EAGAIN)) continue;
      if (n <= 0) {
        const std::string why = std::strerror(errno);
        timespec zero{0, 0};
        while (sigtimedwait(&pipe_set, nullptr, &zero) > 0) {
        }
        std::lock_guard lock(m);
        write_error = why;
        queue.clear();
        cv.notify_all();
        return;
      }
      done += std::size_t(n);
    }
  }
}

void VideoWriter::Impl::stop_child(bool kill_it, int* status) {
  {
    std::lock_guard lock(m);
    closing = true;
    if (kill_it) queue.clear();
  }
  cv.notify_all();
  if (kill_it && pid > 0) ::kill(pid, SIGKILL);
  if (writer.joinable()) writer.join();
  if (pipe_fd >= 0) close(pipe_fd);
  pipe_fd = -1;
  int st = 0;
  if (pid > 0)
    while (waitpid(pid, &st, 0) < 0 && errno == EINTR) {
    }
  pid = -1;
  if (status) *status = st;
}

void VideoWriter::Impl::discard() {
  std::error_code ec;
  fs::remove(partial, ec);
  if (!log.empty()) fs::remove(log, ec);
  log.clear();
  log_guard.reset();
}

void VideoWriter::Impl::fail(const std::string& why) {
  std::string detail = log.empty() ? "" : last_line(log);
  stop_child(true, nullptr);
  discard();
  finished = true;
  throw InputError(fmt::format("{}: video encoding failed ({}{}{})", file, why,
                               detail.empty() ? "" : ": ", detail));
}

VideoWriter::VideoWriter(std::string file, int width, int height, const VideoOptions& options)
    : impl_(std::make_unique<Impl>()) {
  validate_video_options(options);
  if (width < 1 || height < 1)
    throw InputError(fmt::format("{}: video size {}x{} is empty", file, width, height));
  Impl& s = *impl_;
  s.file = std::move(file);
  fs::path dir = fs::path(s.file).parent_path();
  if (!dir.empty() && !fs::is_directory(dir))
    throw InputError(fmt::format("{}: directory {} does not exist", s.file, dir.string()));
  s.partial = create_temp_beside(s.file);
  if (s.partial.empty())
    throw InputError(
        fmt::format("{}: cannot write in its directory ({})", s.file, std::strerror(errno)));
  s.width = width;
  s.height = height;
  s.enc_w = width + (width & 1);
  s.enc_h = height + (height & 1);
  s.queue_cap = std::size_t(std::max(1, options.queue_frames));
  s.guard.emplace(s.partial);
  s.stall_s = options.stall_seconds;
  try {
    s.spawn(options);
  } catch (...) {
    s.discard();
    throw;
  }
  s.writer = std::thread([&s] { s.write_loop(); });
}

VideoWriter::~VideoWriter() {
  if (impl_->finished) return;
  impl_->stop_child(true, nullptr);
  impl_->discard();
}

void VideoWriter::push(const Image& frame) {
  Impl& s = *impl_;
  assert(frame.width == s.width && frame.height == s.height);
  if (s.finished) throw InputError(fmt::format("{}: video already finished", s.file));
  // Copy (and pad: repeat the last column / row) outside the lock.
  std::vector<std::uint8_t> buf(std::size_t(s.enc_w) * s.enc_h * 4);
  const std::size_t in_row = std::size_t(s.width) * 4, out_row = std::size_t(s.enc_w) * 4;
  for (int y = 0; y < s.enc_h; ++y) {
    const std::uint8_t* src = frame.rgba.data() + std::size_t(std::min(y, s.height - 1)) * in_row;
    std::uint8_t* dst = buf.data() + std::size_t(y) * out_row;
    std::memcpy(dst, src, in_row);
    if (s.enc_w > s.width) std::memcpy(dst + in_row, src + in_row - 4, 4);
  }
  std::string err;
  {
    std::unique_lock lock(s.m);
    s.cv.wait(lock, [&] { return s.queue.size() < s.queue_cap || !s.write_error.empty(); });
    err = s.write_error;
    if (err.empty()) s.queue.push_back(std::move(buf));
  }
  if (!err.empty()) s.fail(err);
  s.cv.notify_all();
  ++s.frames;
}

void VideoWriter::finish() {
  Impl& s = *impl_;
  if (s.finished) return;
  int status = 0;
  s.stop_child(false, &status);
  std::string why;
  if (!s.write_error.empty())
    why = s.write_error;
  else if (WIFSIGNALED(status))
    why = fmt::format("ffmpeg killed by signal {}", WTERMSIG(status));
  else if (WEXITSTATUS(status) != 0)
    why = fmt::format("ffmpeg exited with status {}", WEXITSTATUS(status));
  if (!why.empty()) s.fail(why);
  // The temporary file was created 0600; the video gets the usual umask-derived mode.
  const mode_t mask = umask(0);
  umask(mask);
  chmod(s.partial.c_str(), 0666 & ~mask);
  std::error_code ec;
  s.guard->release_after([&] { fs::rename(s.partial, s.file, ec); });
  if (ec) s.fail(fmt::format("cannot move {} into place: {}", s.partial, ec.message()));
  s.discard();
  s.finished = true;
}

int VideoWriter::frames() const {
  return impl_->frames;
}
bool VideoWriter::padded() const {
  return impl_->enc_w != impl_->width || impl_->enc_h != impl_->height;
}
int VideoWriter::encoded_width() const {
  return impl_->enc_w;
}
int VideoWriter::encoded_height() const {
  return impl_->enc_h;
}
const std::string& VideoWriter::file() const {
  return impl_->file;
}

}  // namespace terrasprite
