# Checks the one-way include order between the project's folders (see the top-level
# CMakeLists.txt). Run as a script:
#
#   cmake -DSOURCE_DIR=<tree to check> -P cmake/CheckIncludeOrder.cmake
#
# Every #include "x/y.h" in a .h/.cc under io/, render/, frontend/, sfm/, apps/ or python/ is looked
# up: the
# including file's layer (longest matching path prefix below) must list the included file's layer.
# Fails with one line per violation. In the spirit of Chromium's DEPS include_rules / checkdeps.

if(NOT SOURCE_DIR)
  message(FATAL_ERROR "CheckIncludeOrder: pass -DSOURCE_DIR=<tree>")
endif()

# Layers, most specific prefix first. frontend/detector_factory is the one file of frontend/'s
# common room that may see the detectors it constructs.
set(layers
  frontend/detector_factory frontend/comic frontend/baselines frontend/matching
  frontend/evaluation frontend sfm/evaluation sfm/colmap sfm/run sfm apps python
  io/core io/image io/colmap io/report io/datasets io render)

# What each layer may include (besides itself).
# io/'s rooms: core (errors, files, staged outputs) under everything; image, colmap and report
# side by side on core; datasets (ground truth and calibration files) over image and colmap.
set(allowed_io/core "")
set(allowed_io/image io/core)
set(allowed_io/colmap io/core)
set(allowed_io/report io/core)
set(allowed_io/datasets io/core io/image io/colmap)
set(io_all io/core io/image io/colmap io/report io/datasets)
set(allowed_io ${io_all})
set(allowed_frontend ${io_all})
set(allowed_frontend/comic ${io_all} frontend)
set(allowed_frontend/baselines ${io_all} frontend)
set(allowed_frontend/detector_factory ${io_all} frontend frontend/comic frontend/baselines)
set(allowed_frontend/matching ${io_all} frontend frontend/comic frontend/baselines
  frontend/detector_factory)
set(allowed_frontend/evaluation ${io_all} frontend frontend/comic frontend/baselines
  frontend/detector_factory frontend/matching)
set(frontend_all frontend frontend/comic frontend/baselines frontend/detector_factory
  frontend/matching frontend/evaluation)
set(allowed_sfm ${io_all} ${frontend_all})
set(allowed_sfm/evaluation ${io_all} ${frontend_all} sfm)
set(allowed_sfm/colmap ${io_all} ${frontend_all} sfm sfm/evaluation)
# sfm/run: the runs behind the apps and the Python module, over every other library folder.
set(allowed_sfm/run ${io_all} ${frontend_all} sfm sfm/evaluation sfm/colmap)
# The renderer stands on io/ alone, beside frontend/ and sfm/ (neither includes it).
set(allowed_render ${io_all})
set(allowed_apps ${io_all} render ${frontend_all} sfm sfm/evaluation sfm/colmap sfm/run)
# The Python bindings sit where the apps do: over every library, under nothing.
set(allowed_python ${io_all} render ${frontend_all} sfm sfm/evaluation sfm/colmap sfm/run)

function(layer_of path out)
  foreach(layer ${layers})
    string(LENGTH "${layer}" n)
    string(SUBSTRING "${path}" 0 ${n} head)
    if(head STREQUAL layer)
      string(SUBSTRING "${path}" ${n} 1 next)
      if(next STREQUAL "/" OR next STREQUAL "." OR next STREQUAL "")
        set(${out} ${layer} PARENT_SCOPE)
        return()
      endif()
    endif()
  endforeach()
  set(${out} "" PARENT_SCOPE)
endfunction()

file(GLOB_RECURSE sources RELATIVE ${SOURCE_DIR}
  ${SOURCE_DIR}/io/*.h ${SOURCE_DIR}/io/*.cc
  ${SOURCE_DIR}/render/*.h ${SOURCE_DIR}/render/*.cc
  ${SOURCE_DIR}/frontend/*.h ${SOURCE_DIR}/frontend/*.cc
  ${SOURCE_DIR}/sfm/*.h ${SOURCE_DIR}/sfm/*.cc
  ${SOURCE_DIR}/apps/*.h ${SOURCE_DIR}/apps/*.cc
  ${SOURCE_DIR}/python/*.h ${SOURCE_DIR}/python/*.cc)
list(SORT sources)

set(violations 0)
set(checked 0)
foreach(src ${sources})
  layer_of(${src} from)
  if(NOT from)
    continue()
  endif()
  file(STRINGS ${SOURCE_DIR}/${src} includes REGEX "^[ \t]*#[ \t]*include[ \t]*\"")
  foreach(line ${includes})
    string(REGEX REPLACE "^[^\"]*\"([^\"]+)\".*$" "\\1" target "${line}")
    layer_of(${target} to)
    if(NOT to OR to STREQUAL from)
      continue()
    endif()
    math(EXPR checked "${checked} + 1")
    list(FIND allowed_${from} ${to} found)
    if(found EQUAL -1)
      message("include order: ${src} (${from}) includes ${target} (${to}), not allowed")
      math(EXPR violations "${violations} + 1")
    endif()
  endforeach()
endforeach()

# With -DCHECK_READMES=ON every folder holding sources opens with a README.md of five lines at
# most, saying which paper section or job it holds and what it may include.
if(CHECK_READMES)
  set(folders "")
  foreach(src ${sources})
    get_filename_component(dir ${src} DIRECTORY)
    list(APPEND folders ${dir})
  endforeach()
  list(REMOVE_DUPLICATES folders)
  foreach(dir ${folders})
    if(NOT EXISTS ${SOURCE_DIR}/${dir}/README.md)
      message("layout: ${dir}/ has no README.md")
      math(EXPR violations "${violations} + 1")
    else()
      file(READ ${SOURCE_DIR}/${dir}/README.md readme)
      string(REGEX MATCHALL "\n" newlines "${readme}")
      list(LENGTH newlines n)
      if(n GREATER 5)
        message("layout: ${dir}/README.md has ${n} lines, at most 5")
        math(EXPR violations "${violations} + 1")
      endif()
    endif()
  endforeach()
endif()

list(LENGTH sources num_sources)
if(violations GREATER 0)
  message(FATAL_ERROR "include order: ${violations} violation(s) in ${num_sources} files")
endif()
message("include order: ${num_sources} files, ${checked} includes across folders, all in order")
