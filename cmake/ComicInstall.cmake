# `cmake --install build --prefix P` installs the CMake package comic:
#   P/lib/libcomic_{io,render,frontend,sfm}.a the static libraries (position-independent)
#   P/include/comic/{io,render,frontend,sfm}/ their headers, under comic/ so that they never shadow
#                                             a consumer's own io/... or sfm/... headers
#   P/bin/comic_*                             the apps
#   P/lib/cmake/comic/comicConfig.cmake       find_package(comic) -> comic::io, comic::render,
#                                             comic::frontend, comic::sfm (with their dependencies
#                                             found again)
#
# In the tree our headers include each other as "io/core/error.h"; the installed copies must say
# "comic/io/core/error.h". Rather than spell every include in the tree with a comic/ prefix, the
# install step copies the headers and then rewrites, in the installed copies only, the
# project-relative includes ("io/", "render/", "frontend/", "sfm/") to "comic/...": see
# cmake/RewriteInstalledIncludes.cmake. The installed headers then need nothing but
# -I<prefix>/include, which the targets carry.
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

set(COMIC_INSTALL_CMAKEDIR ${CMAKE_INSTALL_LIBDIR}/cmake/comic)

set_target_properties(comic_io PROPERTIES EXPORT_NAME io)
set_target_properties(comic_frontend PROPERTIES EXPORT_NAME frontend)
set_target_properties(comic_sfm PROPERTIES EXPORT_NAME sfm)
set_target_properties(comic_render PROPERTIES EXPORT_NAME render)
install(TARGETS comic_io comic_render comic_frontend comic_sfm
  EXPORT comicTargets
  ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
  LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
  INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})

foreach(module io render frontend sfm)
  install(DIRECTORY ${PROJECT_SOURCE_DIR}/${module}/
    DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/comic/${module}
    FILES_MATCHING PATTERN "*.h")
endforeach()
install(CODE "set(COMIC_INSTALLED_INCLUDE_DIR \"\$ENV{DESTDIR}\${CMAKE_INSTALL_PREFIX}/${CMAKE_INSTALL_INCLUDEDIR}/comic\")")
install(SCRIPT ${PROJECT_SOURCE_DIR}/cmake/RewriteInstalledIncludes.cmake)

install(EXPORT comicTargets
  NAMESPACE comic::
  FILE comicTargets.cmake
  DESTINATION ${COMIC_INSTALL_CMAKEDIR})
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/comicConfig.cmake.in
  ${PROJECT_BINARY_DIR}/comicConfig.cmake
  INSTALL_DESTINATION ${COMIC_INSTALL_CMAKEDIR})
# 0.x: a consumer asking for 0.1 accepts 0.1.y only (the API is not stable across minor versions).
write_basic_package_version_file(${PROJECT_BINARY_DIR}/comicConfigVersion.cmake
  VERSION ${PROJECT_VERSION}
  COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/comicConfig.cmake ${PROJECT_BINARY_DIR}/comicConfigVersion.cmake
  DESTINATION ${COMIC_INSTALL_CMAKEDIR})
