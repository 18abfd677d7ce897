# Every dependency is a Debian package. A missing one stops configuration with the package name.
find_package(PkgConfig)

macro(lodopt_missing debian_package what)
  message(FATAL_ERROR "lodopt: ${what} not found. Install the Debian package: apt-get install ${debian_package}")
endmacro()

if(NOT PkgConfig_FOUND)
  lodopt_missing(pkg-config "pkg-config")
endif()

find_package(OpenCV 4 QUIET COMPONENTS core imgproc)
if(NOT OpenCV_FOUND)
  lodopt_missing(libopencv-dev "OpenCV 4 (core, imgproc)")
endif()

# Image files (renderer/src/image_io.cpp): small libraries, so that a lodopt process starts fast.
find_package(PNG QUIET)
if(NOT PNG_FOUND)
  lodopt_missing(libpng-dev "libpng")
endif()
find_package(JPEG QUIET)
if(NOT JPEG_FOUND)
  lodopt_missing(libjpeg-dev "libjpeg")
endif()
find_package(OpenEXR QUIET CONFIG)
if(NOT OpenEXR_FOUND)
  lodopt_missing(libopenexr-dev "OpenEXR")
endif()

pkg_check_modules(OSMESA QUIET IMPORTED_TARGET osmesa)
if(NOT OSMESA_FOUND)
  lodopt_missing(libosmesa6-dev "OSMesa (software OpenGL)")
endif()
# EGL (libglvnd's libEGL): the renderer's second backend, headless on a GPU's driver or Mesa's.
pkg_check_modules(EGL QUIET IMPORTED_TARGET egl)
if(NOT EGL_FOUND)
  lodopt_missing(libegl-dev "EGL (headless OpenGL on a GPU)")
endif()

# Butteraugli (metrics/src/judge.cpp): the judge that scores answers and that no search reads.
pkg_check_modules(JXL QUIET IMPORTED_TARGET libjxl)
if(NOT JXL_FOUND)
  lodopt_missing(libjxl-dev "libjxl (butteraugli)")
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

# Compressed glTF (scenes/src/gltf_draco.cpp, KHR_draco_mesh_compression; gltf_materials_views.cpp,
# EXT_texture_webp).
find_package(draco QUIET CONFIG)
if(NOT draco_FOUND)
  lodopt_missing(libdraco-dev "Draco")
endif()
pkg_check_modules(WEBP QUIET IMPORTED_TARGET libwebp)
if(NOT WEBP_FOUND)
  lodopt_missing(libwebp-dev "libwebp")
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

# LODOPT_PAGMO and LODOPT_MPI: AUTO (the default) builds a feature when its package is found, ON
# requires it (the quick start passes ON, so CI cannot silently lose it), OFF leaves it out even
# when the package is installed.
function(lodopt_feature_mode variable)
  set(${variable} AUTO CACHE STRING "AUTO (if found), ON (required) or OFF")
  set_property(CACHE ${variable} PROPERTY STRINGS AUTO ON OFF)
  string(TOUPPER "${${variable}}" mode)
  if(mode MATCHES "^(OFF|0|FALSE|NO|N)$")
    set(mode OFF)
  elseif(mode MATCHES "^(ON|1|TRUE|YES|Y)$")
    set(mode ON)
  elseif(NOT mode STREQUAL "AUTO")
    message(FATAL_ERROR "lodopt: ${variable}=${${variable}}: expected AUTO, ON or OFF")
  endif()
  set(${variable}_MODE ${mode} PARENT_SCOPE)
endfunction()

# pagmo2's optimizers as peers of lodopt's searches (optimizer/pagmo, docs/optimizer.md "Peers:
# pagmo2").
lodopt_feature_mode(LODOPT_PAGMO)
set(LODOPT_WITH_PAGMO OFF)
if(NOT LODOPT_PAGMO_MODE STREQUAL "OFF")
  find_package(pagmo QUIET CONFIG)
endif()
if(LODOPT_PAGMO_MODE STREQUAL "OFF")
  message(STATUS "lodopt: LODOPT_PAGMO=OFF: building without the pagmo:* algorithms")
elseif(pagmo_FOUND)
  set(LODOPT_WITH_PAGMO ON)
  message(STATUS "lodopt: pagmo2 ${pagmo_VERSION} found: the pagmo:* algorithms are built")
elseif(LODOPT_PAGMO_MODE STREQUAL "ON")
  lodopt_missing(libpagmo-dev "pagmo2 (LODOPT_PAGMO=ON)")
else()
  message(STATUS "lodopt: pagmo2 not found (libpagmo-dev): building without the pagmo:* algorithms")
endif()

# Open MPI for `mpirun -np N lodopt sweep` (cli/src/sweep_queue.cpp, docs/sweep.md); without it
# sweep runs on one machine and with --shard.
lodopt_feature_mode(LODOPT_MPI)
set(LODOPT_WITH_MPI OFF)
if(NOT LODOPT_MPI_MODE STREQUAL "OFF")
  find_package(MPI QUIET COMPONENTS C)
endif()
if(LODOPT_MPI_MODE STREQUAL "OFF")
  message(STATUS "lodopt: LODOPT_MPI=OFF: sweep runs on one machine and in shards only")
elseif(MPI_C_FOUND)
  set(LODOPT_WITH_MPI ON)
  find_program(LODOPT_MPIRUN NAMES mpirun mpiexec)
  message(STATUS "lodopt: MPI ${MPI_C_VERSION} found: sweep runs under mpirun")
elseif(LODOPT_MPI_MODE STREQUAL "ON")
  lodopt_missing(libopenmpi-dev "MPI (LODOPT_MPI=ON)")
else()
  message(STATUS "lodopt: MPI not found (libopenmpi-dev): sweep runs on one machine and in shards only")
endif()
