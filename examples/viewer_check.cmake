# Writes an example's page (NAME: spatial_arm or robot_arm) and plays it in
# headless Chromium (software WebGL); prints what the page reports about
# itself (#status), and keeps a screenshot (viewer/NAME.png) for docs/.
file(MAKE_DIRECTORY ${WORK})
execute_process(COMMAND ${EXAMPLE} --csv ${WORK}/${NAME}.csv --html ${WORK}/${NAME}.html RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "${NAME} --html failed")
endif()
set(flags --no-sandbox --use-angle=swiftshader --enable-unsafe-swiftshader --window-size=920,800 --virtual-time-budget=6000)
execute_process(COMMAND ${CHROMIUM} ${flags} --dump-dom file://${WORK}/${NAME}.html
                OUTPUT_VARIABLE dom ERROR_QUIET TIMEOUT 120 RESULT_VARIABLE rc)
string(REGEX MATCH "<div id=\"status\"[^>]*>[^<]*" status "${dom}")
message("page: ${status}")
execute_process(COMMAND ${CHROMIUM} ${flags} --screenshot=${WORK}/${NAME}.png file://${WORK}/${NAME}.html
                OUTPUT_QUIET ERROR_QUIET TIMEOUT 120)
