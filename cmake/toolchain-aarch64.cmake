# Cross-build for Raspberry Pi OS 64-bit / Debian 12 arm64 (Pi 3/4/5, Zero 2 W)
# from an x86-64 Debian 12 host with multiarch arm64 libraries (`make
# deps-cross`; docs/install.md):
#   cmake -S . -B build-arm64 -G Ninja -DCMAKE_TOOLCHAIN_FILE=cmake/toolchain-aarch64.cmake
set(CMAKE_SYSTEM_PROCESSOR aarch64)
set(XR_CROSS_TRIPLET aarch64-linux-gnu)
set(XR_QEMU_ARCH aarch64)
include(${CMAKE_CURRENT_LIST_DIR}/toolchain-debian-multiarch.cmake)
