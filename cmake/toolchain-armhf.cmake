# Cross-build for 32-bit Raspberry Pi OS / Debian 12 armhf (ARMv7 hard-float:
# Pi 2/3/4 and Zero 2 W on a 32-bit image) from an x86-64 Debian 12 host with
# multiarch armhf libraries (`make deps-cross`; docs/install.md):
#   cmake -S . -B build-armhf -G Ninja -DCMAKE_TOOLCHAIN_FILE=cmake/toolchain-armhf.cmake
set(CMAKE_SYSTEM_PROCESSOR armv7l)
set(XR_CROSS_TRIPLET arm-linux-gnueabihf)
set(XR_QEMU_ARCH arm)
include(${CMAKE_CURRENT_LIST_DIR}/toolchain-debian-multiarch.cmake)
