// SPDX-License-Identifier: MIT
// The translation unit ts_pch's precompiled header is built with (see
// cmake/modules.cmake); it compiles to nothing.
