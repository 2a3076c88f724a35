# Shared part of the cross toolchain files (toolchain-aarch64.cmake,
# toolchain-armhf.cmake): Debian 12's cross compilers (crossbuild-essential-*)
# with the target's libraries from Debian multiarch (libfoo-dev:arm64 in
# /usr/lib/aarch64-linux-gnu), headers shared in /usr/include.
# The including file sets XR_CROSS_TRIPLET, XR_QEMU_ARCH and
# CMAKE_SYSTEM_PROCESSOR first.
set(CMAKE_SYSTEM_NAME Linux)

set(CMAKE_C_COMPILER ${XR_CROSS_TRIPLET}-gcc)
set(CMAKE_CXX_COMPILER ${XR_CROSS_TRIPLET}-g++)

# CMAKE_LIBRARY_ARCHITECTURE makes find_library and find_package (cmake
# configs in /usr/lib/<triplet>/cmake) look in the multiarch directories.
set(CMAKE_LIBRARY_ARCHITECTURE ${XR_CROSS_TRIPLET})
set(CMAKE_FIND_ROOT_PATH /usr/${XR_CROSS_TRIPLET})
set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY BOTH)
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE BOTH)
set(CMAKE_FIND_ROOT_PATH_MODE_PACKAGE BOTH)

# pkg-config (libgpiod, libsystemd) must report the target's .pc files only.
set(ENV{PKG_CONFIG_LIBDIR} "/usr/lib/${XR_CROSS_TRIPLET}/pkgconfig:/usr/share/pkgconfig")
set(ENV{PKG_CONFIG_SYSROOT_DIR} "")

# Test binaries (gtest discovery, ctest) run under qemu-user. Debian's
# qemu-user-static installs qemu-<arch>-static; qemu-user has qemu-<arch>.
#
# `-L /` and not `-L /usr/<triplet>`: the loader and libc must come from ONE
# glibc build. Under `-L /usr/<triplet>` qemu takes the program interpreter
# from the cross toolchain's copy (libc6-<arch>-cross, Debian 2.36-8cross1)
# while that loader, reading the host's /etc/ld.so.cache, maps libc.so.6 from
# multiarch libc6:<arch> (2.36-9+deb12u14). The two builds' _rtld_global
# differ in size (4512 vs 4520 bytes on arm64), so libc's first
# pthread_create walks a corrupt stack cache list forever: 100 % CPU, no
# system call, signals never delivered. `-L /` takes both from multiarch
# libc6:<arch>, the same glibc a Raspberry Pi runs. tests/arm/emulator_check.sh
# (ctest arm.emulator_*) checks the pairing and that the daemon starts its
# threads and stops on SIGTERM.
find_program(XR_QEMU_USER NAMES qemu-${XR_QEMU_ARCH}-static qemu-${XR_QEMU_ARCH})
if(XR_QEMU_USER)
  set(XR_QEMU_PREFIX / CACHE PATH "qemu-user -L prefix: where the target's loader and libraries are found")
  set(CMAKE_CROSSCOMPILING_EMULATOR ${XR_QEMU_USER} -L ${XR_QEMU_PREFIX})
endif()
