# The web page beside the program (docs/web.md "The page"): `cmake --build` makes
# build/web/coinroll.html with tools/build_page.sh wherever Debian's emscripten, node and the page's
# npm modules are installed (tools/setup.sh installs all three), so that `coinroll export` works after
# the plain build and `cmake --install` ships the page. Elsewhere the build says what is missing and
# goes on without it; COINROLL_PAGE=OFF leaves it out (sanitizer and fuzz builds always do: the page
# holds em++'s module, which an instrumented build would not change).
option(COINROLL_PAGE "Build the web page build/web/coinroll.html where emscripten, node and web/node_modules are" ON)

function(coinroll_add_web_page)
  if(NOT COINROLL_PAGE OR COINROLL_SANITIZE OR COINROLL_FUZZ)
    return()
  endif()
  find_program(COINROLL_EMCMAKE emcmake)
  find_program(COINROLL_NODE node)
  if(NOT COINROLL_EMCMAKE OR NOT COINROLL_NODE OR NOT EXISTS ${PROJECT_SOURCE_DIR}/web/node_modules/esbuild)
    message(STATUS "The web page (coinroll export) is not built: it needs Debian's emscripten, node and "
                   "web/node_modules (tools/setup.sh installs them)")
    return()
  endif()
  # What the page is made of: the core's sources (src/wasm/CMakeLists.txt lists what it takes of
  # them), the page's own, the shaders, the examples and the coin's face. `coinroll schema` is read
  # from the program, a dependency of its own.
  file(GLOB_RECURSE inputs CONFIGURE_DEPENDS
       ${PROJECT_SOURCE_DIR}/src/physics/* ${PROJECT_SOURCE_DIR}/src/integrate/* ${PROJECT_SOURCE_DIR}/src/scene/*
       ${PROJECT_SOURCE_DIR}/src/pipeline/* ${PROJECT_SOURCE_DIR}/src/render/* ${PROJECT_SOURCE_DIR}/src/wasm/*
       ${PROJECT_SOURCE_DIR}/web/src/* ${PROJECT_SOURCE_DIR}/shaders/* ${PROJECT_SOURCE_DIR}/examples/*.json)
  set(page ${PROJECT_BINARY_DIR}/web/coinroll.html)
  add_custom_command(OUTPUT ${page}
                     COMMAND ${PROJECT_SOURCE_DIR}/tools/build_page.sh ${PROJECT_BINARY_DIR}
                     DEPENDS coinroll ${inputs} ${PROJECT_SOURCE_DIR}/web/build.mjs
                             ${PROJECT_SOURCE_DIR}/web/package-lock.json ${PROJECT_SOURCE_DIR}/assets/coin_face.png
                             ${PROJECT_SOURCE_DIR}/tools/build_page.sh ${PROJECT_SOURCE_DIR}/tools/build_wasm.sh
                     WORKING_DIRECTORY ${PROJECT_SOURCE_DIR}
                     COMMENT "Building the web page (the WebAssembly core, then web/build.mjs)"
                     VERBATIM)
  add_custom_target(coinroll_page ALL DEPENDS ${page})
endfunction()
