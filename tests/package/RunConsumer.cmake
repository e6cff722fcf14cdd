# ctest package/consumer: installs the build tree into WORK_DIR/prefix, builds the consumer project
# against it and runs it. Fails on any step's non-zero exit, on a find_package(comic) that found
# something other than the prefix, or on headers left with un-prefixed project includes.
foreach(var COMIC_BINARY_DIR CONSUMER_SOURCE_DIR WORK_DIR CMAKE_COMMAND_PATH EXPECTED_VERSION)
  if(NOT ${var})
    message(FATAL_ERROR "RunConsumer.cmake: ${var} is not set")
  endif()
endforeach()
set(prefix ${WORK_DIR}/prefix)
set(consumer_build ${WORK_DIR}/consumer_build)
file(REMOVE_RECURSE ${prefix} ${consumer_build})

function(run_step what)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${what} failed (${rc}):\n${out}\n${err}")
  endif()
  set(step_output "${out}${err}" PARENT_SCOPE)
endfunction()

run_step("cmake --install" ${CMAKE_COMMAND_PATH} --install ${COMIC_BINARY_DIR} --prefix ${prefix})

# The installed layout: libraries, the package files, headers under include/comic/, the apps.
foreach(file lib/libcomic_io.a lib/libcomic_render.a lib/libcomic_frontend.a lib/libcomic_sfm.a
             lib/cmake/comic/comicConfig.cmake lib/cmake/comic/comicConfigVersion.cmake
             lib/cmake/comic/comicTargets.cmake include/comic/io/core/error.h
             include/comic/frontend/detector_factory.h include/comic/sfm/reconstruction.h
             include/comic/render/rasterizer.h
             bin/comic_detect bin/comic_sfm)
  if(NOT EXISTS ${prefix}/${file})
    message(FATAL_ERROR "not installed: ${prefix}/${file}")
  endif()
endforeach()
if(EXISTS ${prefix}/include/io OR EXISTS ${prefix}/include/frontend OR EXISTS ${prefix}/include/sfm
   OR EXISTS ${prefix}/include/render)
  message(FATAL_ERROR "headers installed outside include/comic/")
endif()
file(GLOB_RECURSE headers ${prefix}/include/comic/*.h)
list(LENGTH headers header_count)
if(header_count LESS 50)
  message(FATAL_ERROR "only ${header_count} headers installed under include/comic/")
endif()
foreach(header ${headers})
  file(STRINGS ${header} bad REGEX "#include \"(io|render|frontend|sfm)/")
  if(bad)
    message(FATAL_ERROR "${header} still includes a project header without comic/: ${bad}")
  endif()
endforeach()

run_step("configuring the consumer" ${CMAKE_COMMAND} -S ${CONSUMER_SOURCE_DIR} -B ${consumer_build}
  -DCMAKE_BUILD_TYPE=Release -DCMAKE_PREFIX_PATH=${prefix} -DCOMIC_EXPECTED_VERSION=${EXPECTED_VERSION})
if(NOT step_output MATCHES "comic ${EXPECTED_VERSION} found in ${prefix}/")
  message(FATAL_ERROR "find_package(comic) did not report the install prefix:\n${step_output}")
endif()
run_step("building the consumer" ${CMAKE_COMMAND} --build ${consumer_build})
run_step("running the consumer" ${consumer_build}/comic_consumer)
message(STATUS "${step_output}")
