# Every dependency is a Debian package. A missing one stops configuration with the package name.
find_package(PkgConfig)

macro(lodopt_missing debian_package what)
  message(FATAL_ERROR "lodopt: ${what} not found. Install the Debian package: apt-get install ${debian_package}")
endmacro()

if(NOT PkgConfig_FOUND)
  lodopt_missing(pkg-config "pkg-config")
endif()

find_package(OpenCV 4 QUIET COMPONENTS core imgproc imgcodecs)
if(NOT OpenCV_FOUND)
  lodopt_missing(libopencv-dev "OpenCV 4 (core, imgproc, imgcodecs)")
endif()

# OpenImageIO's CMake config names the tool binaries, so it needs openimageio-tools as well.
find_package(OpenImageIO QUIET CONFIG)
if(NOT OpenImageIO_FOUND)
  lodopt_missing("libopenimageio-dev openimageio-tools" "OpenImageIO")
endif()

pkg_check_modules(OSMESA QUIET IMPORTED_TARGET osmesa)
if(NOT OSMESA_FOUND)
  lodopt_missing(libosmesa6-dev "OSMesa (software OpenGL)")
endif()

find_package(glm QUIET CONFIG)
if(NOT glm_FOUND)
  lodopt_missing(libglm-dev "GLM")
endif()

find_package(TinyGLTF QUIET CONFIG)
if(NOT TinyGLTF_FOUND)
  lodopt_missing("libtinygltf-dev libstb-dev" "tinygltf")
endif()
if(NOT EXISTS /usr/include/stb/stb_image.h)
  lodopt_missing(libstb-dev "stb headers")
endif()

find_package(nlohmann_json 3 QUIET CONFIG)
if(NOT nlohmann_json_FOUND)
  lodopt_missing(nlohmann-json3-dev "nlohmann-json")
endif()

find_package(meshoptimizer QUIET CONFIG)
if(NOT meshoptimizer_FOUND)
  lodopt_missing(libmeshoptimizer-dev "meshoptimizer")
endif()

find_package(CLI11 QUIET CONFIG)
if(NOT CLI11_FOUND)
  lodopt_missing(libcli11-dev "CLI11")
endif()

find_package(Threads REQUIRED)

if(LODOPT_BUILD_TESTS)
  find_package(GTest QUIET CONFIG)
  if(NOT GTest_FOUND)
    lodopt_missing(libgtest-dev "GoogleTest")
  endif()
endif()
if(LODOPT_BUILD_BENCH)
  find_package(benchmark QUIET CONFIG)
  if(NOT benchmark_FOUND)
    lodopt_missing(libbenchmark-dev "Google Benchmark")
  endif()
endif()
