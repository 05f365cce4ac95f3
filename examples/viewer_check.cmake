# Writes the spatial arm's page and plays it in headless Chromium (software
# WebGL); prints what the page reports about itself (#status), and keeps a
# screenshot (viewer/spatial_arm.png) for docs/.
file(MAKE_DIRECTORY ${WORK})
execute_process(COMMAND ${EXAMPLE} --csv ${WORK}/spatial_arm.csv --html ${WORK}/spatial_arm.html RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "spatial_arm --html failed")
endif()
set(flags --no-sandbox --use-angle=swiftshader --enable-unsafe-swiftshader --window-size=920,800 --virtual-time-budget=6000)
execute_process(COMMAND ${CHROMIUM} ${flags} --dump-dom file://${WORK}/spatial_arm.html
                OUTPUT_VARIABLE dom ERROR_QUIET TIMEOUT 120 RESULT_VARIABLE rc)
string(REGEX MATCH "<div id=\"status\"[^>]*>[^<]*" status "${dom}")
message("page: ${status}")
execute_process(COMMAND ${CHROMIUM} ${flags} --screenshot=${WORK}/spatial_arm.png file://${WORK}/spatial_arm.html
                OUTPUT_QUIET ERROR_QUIET TIMEOUT 120)
