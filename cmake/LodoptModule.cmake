# lodopt_module(NAME [PUBLIC deps...] [PRIVATE deps...])
# One library per source folder: include/<name>/ is public, src/ is private. Sources are
# globbed so that adding a file needs no CMake edit. A module with no sources yet is an
# interface library, so later modules can already name it. Every module is installed with its
# headers and exported as lodopt::NAME (cmake/LodoptPackage.cmake).
function(lodopt_module name)
  cmake_parse_arguments(ARG "" "" "PUBLIC;PRIVATE" ${ARGN})
  file(GLOB_RECURSE sources CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/src/*.cpp)
  set(public_include $<BUILD_INTERFACE:${CMAKE_CURRENT_SOURCE_DIR}/include> $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
  if(sources)
    add_library(lodopt_${name} STATIC ${sources})
    target_include_directories(lodopt_${name} PUBLIC ${public_include} PRIVATE ${CMAKE_CURRENT_SOURCE_DIR}/src)
    target_link_libraries(lodopt_${name} PUBLIC ${ARG_PUBLIC} PRIVATE ${ARG_PRIVATE})
    set_target_properties(lodopt_${name} PROPERTIES POSITION_INDEPENDENT_CODE ON)
    if(LODOPT_SANITIZE)
      # An instrumented static library needs the sanitizer runtimes wherever it is linked,
      # including a project that links the installed package.
      target_link_options(lodopt_${name} INTERFACE -fsanitize=address,undefined)
    endif()
  else()
    add_library(lodopt_${name} INTERFACE)
    target_include_directories(lodopt_${name} INTERFACE ${public_include})
    target_link_libraries(lodopt_${name} INTERFACE ${ARG_PUBLIC})
  endif()
  set_target_properties(lodopt_${name} PROPERTIES EXPORT_NAME ${name})
  add_library(lodopt::${name} ALIAS lodopt_${name})
  install(TARGETS lodopt_${name} EXPORT lodoptTargets ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR})
  install(DIRECTORY ${CMAKE_CURRENT_SOURCE_DIR}/include/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
endfunction()

# lodopt_test(MODULE deps...): tests/<module>/*.cpp become one GoogleTest executable.
function(lodopt_test module)
  file(GLOB sources CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/${module}/*.cpp)
  if(NOT sources)
    return()
  endif()
  add_executable(${module}_tests ${sources})
  target_link_libraries(${module}_tests PRIVATE ${ARGN} GTest::gtest_main GTest::gmock)
  # The tree's, the build's and the programs' paths come from one generated header
  # (tests/CMakeLists.txt), included by the tests that need one, not from compile definitions:
  # a definition holding an absolute path would make every test object differ between two
  # checkouts, and ccache would compile them all again in a fresh clone.
  target_include_directories(${module}_tests PRIVATE ${LODOPT_TEST_PATHS_DIR})
  gtest_discover_tests(${module}_tests DISCOVERY_TIMEOUT 60 PROPERTIES TIMEOUT 600)
endfunction()
