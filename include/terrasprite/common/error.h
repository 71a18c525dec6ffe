// SPDX-License-Identifier: MIT
// The two kinds of user-facing failure. Programmer errors are asserts instead.
#pragma once
#include <stdexcept>
#include <string>

namespace terrasprite {

/// Bad data or usage from a user or a file (missing, corrupt, unsupported,
/// absurd sizes). The message names the input and the problem in one line.
/// The CLI prints it and exits with status 2.
class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// No usable GL device (no EGL display, no GL 4.5 core context).
/// The CLI prints it and exits with status 3.
class DeviceError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace terrasprite
