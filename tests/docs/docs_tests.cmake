# The documentation site's tests, read by docs/CMakeLists.txt when the site can be built.
#   docs_build_warning_free   cmake --build --target docs: Doxygen and Sphinx, every warning an
#                             error (sets up the fixture docs_html: the tests below need the site)
#   docs_links_resolve        every page within two links of index.html, no broken internal link
#   docs_render_in_chromium   index, Python and C++ API pages in headless Chromium
add_test(NAME docs_build_warning_free
         COMMAND ${CMAKE_COMMAND} --build ${PROJECT_BINARY_DIR} --target docs)
set_tests_properties(docs_build_warning_free PROPERTIES LABELS "docs" TIMEOUT 600
                     FIXTURES_SETUP docs_html)
add_test(NAME docs_links_resolve
         COMMAND /usr/bin/python3 ${PROJECT_SOURCE_DIR}/tests/docs/check_links.py
                 ${ROTGEN_DOCS_OUT}/html --depth 2)
set_tests_properties(docs_links_resolve PROPERTIES LABELS "docs" FIXTURES_REQUIRED docs_html)
find_program(ROTGEN_DOCS_CHROMIUM NAMES chromium chromium-browser)
rotgen_optional(ROTGEN_DOCS_CHROMIUM "chromium, for the documentation site's browser test (Debian: chromium)")
if(ROTGEN_DOCS_CHROMIUM)
  add_test(NAME docs_render_in_chromium
           COMMAND /usr/bin/python3 ${PROJECT_SOURCE_DIR}/tests/docs/test_render.py
                   --html ${ROTGEN_DOCS_OUT}/html --chromium ${ROTGEN_DOCS_CHROMIUM})
  set_tests_properties(docs_render_in_chromium PROPERTIES LABELS "docs" TIMEOUT 300
                       FIXTURES_REQUIRED docs_html)
endif()
