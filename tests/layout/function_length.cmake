# Function lengths: no function over 120 lines outside tests (the scan's default folders); a
# longer one fails the test, named. The fixtures show the scan fails a 121-line function (exit 1)
# and passes a 120-line one.
find_package(Python3 COMPONENTS Interpreter QUIET)
set(function_fixtures ${CMAKE_CURRENT_BINARY_DIR}/fixtures)
if(Python3_Interpreter_FOUND)
  set(scan ${PROJECT_SOURCE_DIR}/scripts/function_lengths.py)
  add_test(NAME layout/function_length
    COMMAND ${Python3_EXECUTABLE} ${scan} --root ${PROJECT_SOURCE_DIR})
  # A function of 120 lines and one of 121: a two-line signature, body_lines statements, a return
  # and the closing brace.
  foreach(total 120 121)
    math(EXPR body_lines "${total} - 4")
    string(REPEAT "  ++n;\n" ${body_lines} body)
    file(WRITE ${function_fixtures}/function_${total}/sfm/a.cc
      "namespace comic {\n\n// Counts.\nint Count(int n,\n          int m) {\n${body}  return n + m;\n}\n\n}  // namespace comic\n")
  endforeach()
  add_test(NAME layout/function_length_accepts_120_lines
    COMMAND ${Python3_EXECUTABLE} ${scan} --root ${function_fixtures}/function_120 sfm)
  set_tests_properties(layout/function_length_accepts_120_lines PROPERTIES
    PASS_REGULAR_EXPRESSION "^0 function\\(s\\) over 120")
  add_test(NAME layout/function_length_rejects_121_lines
    COMMAND ${Python3_EXECUTABLE} ${scan} --root ${function_fixtures}/function_121 sfm)
  set_tests_properties(layout/function_length_rejects_121_lines PROPERTIES
    PASS_REGULAR_EXPRESSION "sfm/a.cc:4: Count 121 lines")
endif()
