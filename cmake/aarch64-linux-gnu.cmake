# Cross-compiling for 64-bit ARM Linux with Debian's cross compiler (gcc-aarch64-linux-gnu) and the
# arm64 builds of the libraries (dpkg --add-architecture arm64): `make test-arm64` configures with
# -DCMAKE_TOOLCHAIN_FILE=cmake/aarch64-linux-gnu.cmake and runs the results under qemu-user.
set(CMAKE_SYSTEM_NAME Linux)
set(CMAKE_SYSTEM_PROCESSOR aarch64)
set(CMAKE_C_COMPILER aarch64-linux-gnu-gcc)
# Libraries and pkg-config files of the arm64 packages, never the host's.
set(ENV{PKG_CONFIG_LIBDIR} "/usr/lib/aarch64-linux-gnu/pkgconfig:/usr/share/pkgconfig")
set(ENV{PKG_CONFIG_SYSROOT_DIR} "")
set(CMAKE_FIND_ROOT_PATH /usr/aarch64-linux-gnu /usr/lib/aarch64-linux-gnu)
set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY BOTH)
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE BOTH)
# ctest runs the test executables through the emulator.
find_program(SGAPI_QEMU_AARCH64 NAMES qemu-aarch64-static qemu-aarch64)
if(SGAPI_QEMU_AARCH64)
  set(CMAKE_CROSSCOMPILING_EMULATOR ${SGAPI_QEMU_AARCH64})
endif()
