// SPDX-License-Identifier: MIT
#include "terrasprite/terrain/png_writer.h"

#include <algorithm>
#include <condition_variable>
#include <deque>
#include <exception>
#include <mutex>
#include <thread>
#include <utility>

#include "terrasprite/terrain/image_io.h"

namespace terrasprite {

struct PngWriter::Impl {
  std::size_t limit;
  std::mutex mutex;
  std::condition_variable changed;
  std::deque<std::pair<Image, std::string>> queue;
  bool busy = false;  // the worker is writing an image taken off the queue
  bool closing = false;
  std::exception_ptr error;
  std::thread worker;

  explicit Impl(int queue_images) : limit(std::size_t(std::max(1, queue_images))) {
    worker = std::thread([this] { work(); });
  }

  ~Impl() {
    {
      std::lock_guard lock(mutex);
      closing = true;
    }
    changed.notify_all();
    worker.join();
  }

  void work() {
    std::unique_lock lock(mutex);
    for (;;) {
      changed.wait(lock, [&] { return closing || !queue.empty(); });
      if (queue.empty()) return;  // closing, nothing left
      auto [image, path] = std::move(queue.front());
      queue.pop_front();
      busy = true;
      lock.unlock();
      std::exception_ptr failed;
      try {
        save_png(image, path);
      } catch (...) {
        failed = std::current_exception();
      }
      lock.lock();
      busy = false;
      if (failed && !error) error = failed;
      if (error) queue.clear();
      changed.notify_all();
    }
  }

  void rethrow(std::unique_lock<std::mutex>& lock) {
    if (!error) return;
    std::exception_ptr e = std::exchange(error, nullptr);
    lock.unlock();
    std::rethrow_exception(e);
  }
};

PngWriter::PngWriter(int queue_images) : impl_(std::make_unique<Impl>(queue_images)) {}

PngWriter::~PngWriter() = default;

void PngWriter::push(Image image, std::string path) {
  Impl& s = *impl_;
  std::unique_lock lock(s.mutex);
  s.changed.wait(lock, [&] { return s.error || s.queue.size() < s.limit; });
  s.rethrow(lock);
  s.queue.emplace_back(std::move(image), std::move(path));
  s.changed.notify_all();
}

void PngWriter::finish() {
  Impl& s = *impl_;
  std::unique_lock lock(s.mutex);
  s.changed.wait(lock, [&] { return s.queue.empty() && !s.busy; });
  s.rethrow(lock);
}

}  // namespace terrasprite
