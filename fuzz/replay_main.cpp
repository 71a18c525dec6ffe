// SPDX-License-Identifier: MIT
// Replays fuzz corpora through a fuzz target with the ordinary compiler (no
// libFuzzer): every file under each argument (file or directory) is fed to
// LLVMFuzzerTestOneInput once. A crash or an escaping exception fails the run.
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size);

namespace {

void replay(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  const std::vector<char> bytes((std::istreambuf_iterator<char>(in)), {});
  LLVMFuzzerTestOneInput(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size());
}

}  // namespace

int main(int argc, char** argv) {
  long long n = 0;
  for (int a = 1; a < argc; ++a) {
    const std::filesystem::path root(argv[a]);
    if (std::filesystem::is_directory(root)) {
      for (const auto& e : std::filesystem::recursive_directory_iterator(root))
        if (e.is_regular_file()) replay(e.path()), ++n;
    } else {
      replay(root), ++n;
    }
  }
  std::printf("replayed %lld inputs\n", n);
  return n > 0 ? 0 : 1;
}
