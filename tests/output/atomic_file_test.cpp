// SPDX-License-Identifier: MIT
// replace_file_atomically: the whole file or nothing, and a temporary file
// that an interrupt removes. Cost: well under 0.1 s.
#include "terrasprite/output/atomic_file.h"

#include <fcntl.h>
#include <gtest/gtest.h>
#include <poll.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "terrasprite/output/interrupt_cleanup.h"
#include "test_util.h"

namespace ts = terrasprite;
namespace fs = std::filesystem;

namespace {

TEST(ReplaceFileAtomically, WritesTheWholeFileAndLeavesNoTemporary) {
  tstest::TempDir t;
  const fs::path file = t.path / "sub" / "entry";
  ASSERT_TRUE(ts::replace_file_atomically(file, "first"));
  ASSERT_TRUE(ts::replace_file_atomically(file, "second"));
  std::ifstream in(file);
  EXPECT_EQ(std::string(std::istreambuf_iterator<char>(in), {}), "second");
  EXPECT_EQ(std::distance(fs::directory_iterator(file.parent_path()), {}), 1);
  fs::create_directories(t.path / "dir");
  EXPECT_FALSE(ts::replace_file_atomically(t.path / "dir", "x")) << "a directory is in the way";
  EXPECT_EQ(std::distance(fs::directory_iterator(t.path), {}), 2) << "no temporary left";
}

// A child writes an entry through a FIFO at its temporary name; once it is
// blocked writing (the parent has read a byte), SIGTERM: the interrupt
// clean-up removes the temporary name and the entry never appears.
TEST(ReplaceFileAtomically, AnInterruptRemovesTheTemporaryFile) {
  tstest::TempDir t;
  const fs::path file = t.path / "entry";
  int go[2];
  ASSERT_EQ(pipe(go), 0);
  const pid_t child = fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    ts::install_interrupt_cleanup();
    char c;
    if (read(go[0], &c, 1) != 1) _exit(90);
    ts::replace_file_atomically(file, std::string(1 << 20, 'x'));
    _exit(91);  // the signal ends it first
  }
  const fs::path tmp = file.string() + "." + std::to_string(child) + ".tmp";
  ASSERT_EQ(mkfifo(tmp.c_str(), 0600), 0);
  // Read-write (Linux): the reader never sees end-of-file before the child opens it.
  const int reader = open(tmp.c_str(), O_RDWR);
  ASSERT_GE(reader, 0);
  ASSERT_EQ(write(go[1], "g", 1), 1);
  pollfd in{reader, POLLIN, 0};
  ASSERT_EQ(poll(&in, 1, 60000), 1) << "the child never wrote";
  char c;
  ASSERT_EQ(read(reader, &c, 1), 1);  // the child is writing: its temporary is registered
  kill(child, SIGTERM);
  int status = 0;
  ASSERT_EQ(waitpid(child, &status, 0), child);
  close(reader);
  EXPECT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 128 + SIGTERM);
  EXPECT_FALSE(fs::exists(fs::symlink_status(tmp))) << "the temporary file survived";
  EXPECT_FALSE(fs::exists(file));
}

}  // namespace
