# The browser code of report.html and the chart pages (report/web): bundled with esbuild
# (npm) at build time and embedded into the library, so an installed snapfit writes
# self-contained pages. Needs node and report/web/node_modules (`npm ci --prefix
# report/web`, which .ci/setup runs). -DSNAPFIT_WEB_REPORT=OFF builds without them:
# `snapfit run` then writes every other file but no report.html, and says so.
option(SNAPFIT_WEB_REPORT "Embed the browser code of report.html and the chart pages (needs node and npm)" ON)
set(SNAPFIT_WEB_ASSETS_CPP ${PROJECT_BINARY_DIR}/generated/embedded_web_assets.cpp)
set(SNAPFIT_WEB_DIR ${PROJECT_SOURCE_DIR}/report/web)
set(snapfit_web_off_hint "or configure with -DSNAPFIT_WEB_REPORT=OFF (no report.html, no chart pages)")

if(NOT SNAPFIT_WEB_REPORT)
  message(STATUS "SNAPFIT_WEB_REPORT is OFF: snapfit writes no report.html and no chart pages")
  execute_process(COMMAND ${CMAKE_COMMAND} -DOUTPUT=${SNAPFIT_WEB_ASSETS_CPP} -P
                          ${PROJECT_SOURCE_DIR}/cmake/EmbedWebAssets.cmake COMMAND_ERROR_IS_FATAL ANY)
  return()
endif()

find_program(SNAPFIT_NODE node)
if(NOT SNAPFIT_NODE)
  message(FATAL_ERROR "SNAPFIT_WEB_REPORT needs node to bundle report/web: install Node.js and npm, then run "
                      "`npm ci --prefix report/web` (bash .ci/setup does both), ${snapfit_web_off_hint}")
endif()
set(snapfit_hidden_lock ${SNAPFIT_WEB_DIR}/node_modules/.package-lock.json)
if(NOT EXISTS ${snapfit_hidden_lock})
  message(FATAL_ERROR "report/web/node_modules is missing: run `npm ci --prefix report/web` (bash .ci/setup does), "
                      "${snapfit_web_off_hint}")
endif()
if(${SNAPFIT_WEB_DIR}/package-lock.json IS_NEWER_THAN ${snapfit_hidden_lock})
  message(FATAL_ERROR "report/web/package-lock.json is newer than report/web/node_modules: run "
                      "`npm ci --prefix report/web` (bash .ci/setup does), ${snapfit_web_off_hint}")
endif()
message(STATUS "report.html and chart pages: bundling report/web with ${SNAPFIT_NODE}")

file(GLOB snapfit_web_sources CONFIGURE_DEPENDS ${SNAPFIT_WEB_DIR}/src/*)
set(snapfit_web_out ${PROJECT_BINARY_DIR}/generated/web)
set(snapfit_web_bundle ${snapfit_web_out}/run_report.js ${snapfit_web_out}/run_report.css
                       ${snapfit_web_out}/chart_page.js ${snapfit_web_out}/chart_page.css
                       ${snapfit_web_out}/live_page.js ${snapfit_web_out}/live_page.css)
add_custom_command(
  OUTPUT ${snapfit_web_bundle}
  COMMAND ${CMAKE_COMMAND} -E rm -rf ${snapfit_web_out}
  COMMAND ${SNAPFIT_NODE} ${SNAPFIT_WEB_DIR}/build.mjs --out ${snapfit_web_out}
  DEPENDS ${snapfit_web_sources} ${SNAPFIT_WEB_DIR}/build.mjs ${SNAPFIT_WEB_DIR}/package-lock.json
  COMMENT "Bundling report/web (three.js, uPlot) with esbuild"
  VERBATIM)
add_custom_command(
  OUTPUT ${SNAPFIT_WEB_ASSETS_CPP}
  COMMAND ${CMAKE_COMMAND} -DOUTPUT=${SNAPFIT_WEB_ASSETS_CPP} -DASSET_DIR=${snapfit_web_out} -P
          ${PROJECT_SOURCE_DIR}/cmake/EmbedWebAssets.cmake
  DEPENDS ${snapfit_web_bundle} ${PROJECT_SOURCE_DIR}/cmake/EmbedWebAssets.cmake
          ${PROJECT_SOURCE_DIR}/cmake/GeneratedList.cmake
  COMMENT "Embedding the bundled report/web into the library"
  VERBATIM)
