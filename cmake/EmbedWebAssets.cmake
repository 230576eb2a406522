# Script mode (cmake -DOUTPUT=FILE [-DASSET_DIR=DIR] -P EmbedWebAssets.cmake): embeds the
# bundled browser code (report/web/build.mjs writes DIR/*.js and DIR/*.css) into a C++ file
# as raw string literals, one entry {file name, text} of snapfit::embedded_web_assets()
# each. Without ASSET_DIR the list is empty: a build without the web report.
include(${CMAKE_CURRENT_LIST_DIR}/GeneratedList.cmake)
snapfit_generated_list_opening(body "cmake/EmbedWebAssets.cmake from report/web" "report/web_assets.h" WebAsset
                               embedded_web_assets)
set(files "")
if(ASSET_DIR)
  file(GLOB files ${ASSET_DIR}/*.js ${ASSET_DIR}/*.css)
  list(SORT files)
  if(NOT files)
    message(FATAL_ERROR "${ASSET_DIR} holds no bundled .js or .css file")
  endif()
endif()
foreach(file ${files})
  get_filename_component(name ${file} NAME)
  snapfit_read_raw_string_text(text ${file} snapfit_web)
  # The page inlines the text in <script> or <style>, which must not end early.
  string(TOLOWER "${text}" lower)
  string(FIND "${lower}" "</script" early_script)
  string(FIND "${lower}" "</style" early_style)
  if(NOT early_script EQUAL -1 OR NOT early_style EQUAL -1)
    message(FATAL_ERROR "${file} contains </script or </style, which would end its inline element")
  endif()
  # A raw string literal holds at most what the compiler allows in one token; pieces of
  # 60,000 characters, concatenated by the compiler, stay well within any limit.
  string(LENGTH "${text}" length)
  string(APPEND body "      {\"${name}\",\n")
  set(at 0)
  while(at LESS length)
    string(SUBSTRING "${text}" ${at} 60000 piece)
    string(APPEND body "       R\"snapfit_web(${piece})snapfit_web\"\n")
    math(EXPR at "${at} + 60000")
  endwhile()
  string(APPEND body "      },\n")
endforeach()
string(APPEND body "${SNAPFIT_GENERATED_LIST_CLOSING}")
# Built from a bundle: always written, so the build sees it newer than the bundle. Without
# one (configure time): written only when changed, so a reconfigure rebuilds nothing.
if(ASSET_DIR)
  file(WRITE ${OUTPUT} "${body}")
else()
  snapfit_write_if_changed(${OUTPUT} "${body}")
endif()
