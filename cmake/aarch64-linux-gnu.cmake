# Cross build for 64-bit ARM Linux on a Debian x86-64 host (scripts/arm.sh): the Debian cross compiler
# (g++-aarch64-linux-gnu) and the arm64 libraries of multiarch (dpkg --add-architecture arm64; libhwy-dev:arm64,
# libtbb-dev:arm64, libgtest-dev:arm64 in /usr/lib/aarch64-linux-gnu). Programs built here run under qemu-user:
# CMAKE_CROSSCOMPILING_EMULATOR makes ctest and gtest_discover_tests run them through qemu-aarch64, and QEMU_CPU in
# the environment picks the emulated CPU (e.g. max,sve=on). They run with multiarch's arm64 loader and C library
# (libc6:arm64, /lib/ld-linux-aarch64.so.1), which the arm64 packages above bring: not with QEMU_LD_PREFIX (or -L)
# set to /usr/aarch64-linux-gnu, whose loader (the cross compiler's glibc build) would then load multiarch's
# libc.so.6 for the arm64 libraries, a different build of glibc, and the first thread created loops for ever in
# pthread_create.
set(CMAKE_SYSTEM_NAME Linux)
set(CMAKE_SYSTEM_PROCESSOR aarch64)
set(CMAKE_C_COMPILER aarch64-linux-gnu-gcc)
set(CMAKE_CXX_COMPILER aarch64-linux-gnu-g++)
set(CMAKE_LIBRARY_ARCHITECTURE aarch64-linux-gnu)
set(CMAKE_FIND_ROOT_PATH /usr/aarch64-linux-gnu)
# Multiarch: the arm64 packages install into the host's /usr (lib/aarch64-linux-gnu), headers shared; programs
# (pkg-config, qemu) are the host's.
set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY BOTH)
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE BOTH)
set(CMAKE_FIND_ROOT_PATH_MODE_PACKAGE BOTH)
find_program(RTM_QEMU_AARCH64 NAMES qemu-aarch64 qemu-aarch64-static)
if(RTM_QEMU_AARCH64)
  set(CMAKE_CROSSCOMPILING_EMULATOR ${RTM_QEMU_AARCH64})
endif()
