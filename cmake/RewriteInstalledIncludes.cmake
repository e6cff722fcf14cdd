# Run by `cmake --install` after the headers are copied (cmake/ComicInstall.cmake): in the
# installed copies under COMIC_INSTALLED_INCLUDE_DIR, rewrites the project-relative includes
#   #include "io/core/error.h"  ->  #include "comic/io/core/error.h"
# (likewise render/, frontend/ and sfm/), so that the installed headers resolve against
# <prefix>/include alone and never against a consumer's own io/... headers. System includes
# (<...>) and any other quoted include are left as they are. Rewriting is idempotent: an already rewritten line no
# longer starts with "io/", so installing twice gives the same files.
if(NOT COMIC_INSTALLED_INCLUDE_DIR)
  message(FATAL_ERROR "RewriteInstalledIncludes.cmake: COMIC_INSTALLED_INCLUDE_DIR is not set")
endif()
file(GLOB_RECURSE headers "${COMIC_INSTALLED_INCLUDE_DIR}/*.h")
set(rewritten 0)
foreach(header ${headers})
  file(READ "${header}" text)
  string(REGEX REPLACE "#include \"(io|render|frontend|sfm)/" "#include \"comic/\\1/" new_text "${text}")
  if(NOT new_text STREQUAL text)
    file(WRITE "${header}" "${new_text}")
    math(EXPR rewritten "${rewritten} + 1")
  endif()
endforeach()
message(STATUS "Rewrote the project includes of ${rewritten} installed headers to comic/...")
