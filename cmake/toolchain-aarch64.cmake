# Cross-build for Raspberry Pi OS 64-bit / Debian 12 arm64 from an x86-64
# Debian 12 host with multiarch arm64 libraries (see docs/install.md):
#   cmake -S . -B build-arm64 -G Ninja -DCMAKE_TOOLCHAIN_FILE=cmake/toolchain-aarch64.cmake
set(CMAKE_SYSTEM_NAME Linux)
set(CMAKE_SYSTEM_PROCESSOR aarch64)

set(XR_CROSS_TRIPLET aarch64-linux-gnu)
set(CMAKE_C_COMPILER ${XR_CROSS_TRIPLET}-gcc)
set(CMAKE_CXX_COMPILER ${XR_CROSS_TRIPLET}-g++)

# Debian multiarch: arm64 libraries in /usr/lib/aarch64-linux-gnu, headers
# shared in /usr/include. CMAKE_LIBRARY_ARCHITECTURE makes find_library and
# find_package (cmake configs in /usr/lib/aarch64-linux-gnu/cmake) look there.
set(CMAKE_LIBRARY_ARCHITECTURE ${XR_CROSS_TRIPLET})
set(CMAKE_FIND_ROOT_PATH /usr/${XR_CROSS_TRIPLET})
set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY BOTH)
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE BOTH)
set(CMAKE_FIND_ROOT_PATH_MODE_PACKAGE BOTH)

# pkg-config (libgpiod, libsystemd) must report the arm64 .pc files only.
set(ENV{PKG_CONFIG_LIBDIR} "/usr/lib/${XR_CROSS_TRIPLET}/pkgconfig:/usr/share/pkgconfig")
set(ENV{PKG_CONFIG_SYSROOT_DIR} "")

# Run arm64 test binaries (gtest discovery, ctest) under qemu-user.
find_program(XR_QEMU_AARCH64 qemu-aarch64)
if(XR_QEMU_AARCH64)
  set(CMAKE_CROSSCOMPILING_EMULATOR ${XR_QEMU_AARCH64} -L /usr/${XR_CROSS_TRIPLET})
endif()
