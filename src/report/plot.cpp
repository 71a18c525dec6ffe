// SPDX-License-Identifier: MIT
#include "terrasprite/report/plot.h"

#include <fmt/format.h>
#include <sys/wait.h>

#include <cstdlib>
#include <fstream>

#include "terrasprite/common/error.h"

namespace terrasprite::report {

void write_text(const std::string& path, const std::string& text) {
  std::ofstream f(path);
  f << text;
  f.close();  // a write the buffer held fails here (a full disk, a file-size limit)
  if (!f) throw InputError(fmt::format("{}: cannot write (disk full or file too large?)", path));
}

std::string run_gnuplot(const std::string& dir, const std::string& script) {
  if (std::system("command -v gnuplot >/dev/null 2>&1") != 0)
    return "gnuplot not found (install gnuplot-nox)";
  const int rc =
      std::system(fmt::format("cd '{}' && gnuplot '{}' > gnuplot.log 2>&1", dir, script).c_str());
  if (rc == 0) return {};
  std::ifstream log(dir + "/gnuplot.log");
  std::string line, first;
  while (std::getline(log, line))
    if (!line.empty() && line.find_first_not_of(" \t^") != std::string::npos) {
      first = line;
      break;
    }
  const int status = WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
  return fmt::format("gnuplot {} failed (exit {}){}{}", script, status, first.empty() ? "" : ": ",
                     first);
}

}  // namespace terrasprite::report
