# Small helpers in the spirit of COLMAP's COLMAP_ADD_LIBRARY / COLMAP_ADD_TEST.
#
#   comic_add_library(NAME comic_io SRCS a.cc b.cc PUBLIC_DEPS OpenCV... PRIVATE_DEPS ...)
#   comic_add_executable(NAME comic_detect SRCS main.cc DEPS comic_frontend)
#   comic_add_test(NAME frontend/comic/comic_detector SRCS comic_detector_test.cc DEPS comic_frontend)
#
# Tests are registered with gtest_discover_tests; every test case is named
# "<NAME>.<Suite>.<Case>" so `ctest -R frontend/` selects a module.

set(COMIC_WARNING_FLAGS -Wall -Wextra)

function(comic_add_library)
  cmake_parse_arguments(ARG "" "NAME" "SRCS;PUBLIC_DEPS;PRIVATE_DEPS" ${ARGN})
  add_library(${ARG_NAME} STATIC ${ARG_SRCS})
  # In the tree, headers are found as "io/...", "frontend/...", "sfm/..."; once installed they live
  # under include/comic/ (cmake/ComicInstall.cmake), so a consumer's -I<prefix>/include never lets
  # our io/core/error.h shadow one of its own.
  target_include_directories(${ARG_NAME} PUBLIC $<BUILD_INTERFACE:${PROJECT_SOURCE_DIR}>
                                                $<INSTALL_INTERFACE:include>)
  # Position-independent, so the archives link into the Python module (python/) and into a
  # consumer's shared library.
  set_target_properties(${ARG_NAME} PROPERTIES POSITION_INDEPENDENT_CODE ON)
  target_compile_options(${ARG_NAME} PRIVATE ${COMIC_WARNING_FLAGS})
  target_link_libraries(${ARG_NAME} PUBLIC ${ARG_PUBLIC_DEPS} PRIVATE ${ARG_PRIVATE_DEPS})
endfunction()

function(comic_add_executable)
  cmake_parse_arguments(ARG "" "NAME" "SRCS;DEPS" ${ARGN})
  add_executable(${ARG_NAME} ${ARG_SRCS})
  target_compile_options(${ARG_NAME} PRIVATE ${COMIC_WARNING_FLAGS})
  target_link_libraries(${ARG_NAME} PRIVATE ${ARG_DEPS})
endfunction()

function(comic_add_test)
  cmake_parse_arguments(ARG "" "NAME;TIMEOUT" "SRCS;DEPS" ${ARGN})
  string(REPLACE "/" "_" target "test_${ARG_NAME}")
  add_executable(${target} ${ARG_SRCS})
  target_compile_options(${target} PRIVATE ${COMIC_WARNING_FLAGS})
  # The sanitizer build (scripts/sanitize.sh) compiles the tests themselves at -O0: they are thin
  # callers of the libraries, which stay at -O1, and an instrumented -O1 compile of a gtest file
  # takes about 1.6x as long.
  if(COMIC_SANITIZE)
    target_compile_options(${target} PRIVATE -O0)
  endif()
  target_link_libraries(${target} PRIVATE ${ARG_DEPS} comic_test_support GTest::gtest_main)
  if(NOT ARG_TIMEOUT)
    set(ARG_TIMEOUT 600)
  endif()
  gtest_discover_tests(${target}
    TEST_PREFIX "${ARG_NAME}."
    WORKING_DIRECTORY ${PROJECT_SOURCE_DIR}
    DISCOVERY_TIMEOUT 60
    PROPERTIES TIMEOUT ${ARG_TIMEOUT})
endfunction()

# Adds one test executable per tests/<module>/<concept>_test.cc in the calling directory,
# named "<module>/<concept>" (e.g. tests/frontend/comic/comic_detector_test.cc -> frontend/comic/comic_detector).
function(comic_add_module_tests MODULE)
  cmake_parse_arguments(ARG "" "" "DEPS" ${ARGN})
  file(GLOB test_sources CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/*_test.cc)
  foreach(src ${test_sources})
    get_filename_component(stem ${src} NAME_WE)
    string(REGEX REPLACE "_test$" "" concept ${stem})
    comic_add_test(NAME ${MODULE}/${concept} SRCS ${src} DEPS ${ARG_DEPS})
  endforeach()
endfunction()
