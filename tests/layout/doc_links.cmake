# Every relative link and #anchor in README.md and docs/*.md resolves (scripts/check_doc_links.py,
# GitHub's anchor rule): a heading swallowed by a table row once left two README links dangling.
# The fixture shows the check fails on a missing anchor and a missing file.
find_package(Python3 COMPONENTS Interpreter QUIET)
if(Python3_Interpreter_FOUND)
  set(links ${PROJECT_SOURCE_DIR}/scripts/check_doc_links.py)
  add_test(NAME layout/doc_links COMMAND ${Python3_EXECUTABLE} ${links} ${PROJECT_SOURCE_DIR})
  set(links_fixture ${CMAKE_CURRENT_BINARY_DIR}/fixtures/doc_links)
  file(WRITE ${links_fixture}/README.md
    "# Top `code`: here\n\n[ok](#top-code-here) [gone](docs/a.md#nowhere) [none](docs/b.md)\n")
  file(WRITE ${links_fixture}/docs/a.md "# A\n\n[back](../README.md#top-code-here)\n")
  add_test(NAME layout/doc_links_rejects_broken_links
    COMMAND ${Python3_EXECUTABLE} ${links} ${links_fixture})
  set_tests_properties(layout/doc_links_rejects_broken_links PROPERTIES
    PASS_REGULAR_EXPRESSION "README.md:3: docs/a.md#nowhere \\(no such anchor\\).*README.md:3: docs/b.md \\(no such file\\).*2 broken")
endif()
