# SPDX-License-Identifier: MIT
# ts_module(NAME DIRS dir... [PUBLIC deps...] [PRIVATE deps...]): the static
# library terrasprite_NAME (alias and exported name terrasprite::NAME) from
# src/<dir>/*.cpp, appended to TS_MODULES. Compile flags live in this file,
# nowhere else (SIMD clone macros and vector types: src/common/simd.h).
set(TS_MODULES "")

# One precompiled header of the standard and third-party headers most
# sources include, built once and reused by every module: with a module
# compiled as one unity file, parsing them is still a fifth of its time, and
# a header built per target would cost as much as it saves. Only headers
# that need no link dependency of their own. GCC refuses a header built
# under other flags, so sources with their own (ts_fast_sqrt,
# ts_no_fp_traps) and the executables (-fPIE, the header is -fPIC) compile
# without it.
add_library(ts_pch OBJECT ${PROJECT_SOURCE_DIR}/cmake/pch.cpp)
target_link_libraries(ts_pch PRIVATE fmt::fmt nlohmann_json::nlohmann_json TBB::tbb glm::glm)
target_precompile_headers(ts_pch PRIVATE <algorithm> <cmath> <functional> <map> <memory>
  <optional> <string> <vector> <fmt/format.h> <nlohmann/json.hpp> <tbb/parallel_for.h>
  <glm/glm.hpp>)
set(TS_MODULE_DIRS "")
function(ts_module name)
  cmake_parse_arguments(M "" "" "DIRS;PUBLIC;PRIVATE" ${ARGN})
  set(srcs "")
  foreach(dir ${M_DIRS})
    file(GLOB dir_srcs CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/src/${dir}/*.cpp)
    list(APPEND srcs ${dir_srcs})
  endforeach()
  set(t terrasprite_${name})
  add_library(${t} STATIC ${srcs})
  add_library(terrasprite::${name} ALIAS ${t})
  set_target_properties(${t} PROPERTIES EXPORT_NAME ${name})
  target_include_directories(${t}
    PUBLIC $<BUILD_INTERFACE:${PROJECT_SOURCE_DIR}/include> $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>
    PRIVATE ${PROJECT_SOURCE_DIR}/src)
  target_compile_options(${t} PRIVATE ${TS_WARNINGS})
  ts_unity(${t} 0)
  target_precompile_headers(${t} REUSE_FROM ts_pch)
  target_link_libraries(${t} PUBLIC ${M_PUBLIC} PRIVATE ${M_PRIVATE})
  set(TS_MODULES ${TS_MODULES} ${t} PARENT_SCOPE)
  set(TS_MODULE_DIRS ${TS_MODULE_DIRS} ${M_DIRS} PARENT_SCOPE)
endfunction()

# A per-pixel loop whose sqrt should compile to the exact vector instruction:
# sqrt without errno (a pragma in the file is not enough for GCC to vectorise
# it). Not -ffast-math: values stay IEEE (the ray caster relies on inf/NaN).
function(ts_fast_sqrt source)
  if(CMAKE_CXX_COMPILER_ID MATCHES "GNU|Clang")
    set_source_files_properties(${PROJECT_SOURCE_DIR}/${source} PROPERTIES COMPILE_OPTIONS -fno-math-errno
      SKIP_PRECOMPILE_HEADERS ON)
  endif()
endfunction()

# A per-pixel loop with a division whose if-conversion GCC refuses while a
# float operation may trap (it keeps a branch, and the loop does not
# vectorise): assume no floating-point traps (nothing here enables them).
# Values stay IEEE.
function(ts_no_fp_traps source)
  if(CMAKE_CXX_COMPILER_ID MATCHES "GNU|Clang")
    set_source_files_properties(${PROJECT_SOURCE_DIR}/${source} PROPERTIES COMPILE_OPTIONS -fno-trapping-math
      SKIP_PRECOMPILE_HEADERS ON)
  endif()
endfunction()

# Every src/<dir> with sources must belong to a module: a new directory that
# no ts_module() line names fails the configure step instead of silently
# leaving its code out of the library.
function(ts_check_modules_cover_src)
  file(GLOB dirs LIST_DIRECTORIES true ${PROJECT_SOURCE_DIR}/src/*)
  foreach(d ${dirs})
    get_filename_component(name ${d} NAME)
    file(GLOB cpp ${d}/*.cpp)
    if(IS_DIRECTORY ${d} AND cpp AND NOT name IN_LIST TS_MODULE_DIRS)
      message(FATAL_ERROR "src/${name} has sources but no ts_module() line in CMakeLists.txt names it")
    endif()
  endforeach()
endfunction()

# Code that only parses, checks and calls the library (the CLI, the tests)
# or writes its results (the report writers):
# -O1 compiles it in about two thirds of -O3's time (CLI11 and GoogleTest
# expand to much code), and none of it is on a hot path. The other modules keep
# the build type's flags. docs/results/2026-12-07-build-times.md.
function(ts_light_optimisation target)
  if(CMAKE_CXX_COMPILER_ID MATCHES "GNU|Clang")
    target_compile_options(${target} PRIVATE $<$<CONFIG:Release>:-O1>)
  endif()
endfunction()

# With TERRASPRITE_UNITY, `target`'s sources compile as unity files of
# `batch` sources each (0: one file for all): the heavy third-party headers
# (nlohmann/json, CLI11, fmt, TBB, the standard library) are parsed and their
# templates generated once per unity file instead of once per source, which
# takes the cold build to a fraction of its time
# (docs/results/2026-12-07-unity-build.md). Sources with their own compile
# options (ts_fast_sqrt, ts_no_fp_traps) stay separate. The code stays valid
# without it: the sanitizer build compiles every source alone.
function(ts_unity target batch)
  if(TERRASPRITE_UNITY)
    set_target_properties(${target} PROPERTIES UNITY_BUILD ON UNITY_BUILD_BATCH_SIZE ${batch})
  endif()
endfunction()
