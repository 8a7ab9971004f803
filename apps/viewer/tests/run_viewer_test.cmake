# Viewer smoke test under Xvfb (or the display there is): ten frames of a small forest with
# the evaluation against truth, then `render --state` of the saved options must give the same
# image as the viewer's last frame. Skipped, saying why, with neither Xvfb nor a display.
#   cmake -DVIEWER=<shadowkit-viewer> -DSHADOWKIT=<shadowkit> -DWORK=<dir> -P run_viewer_test.cmake
cmake_minimum_required(VERSION 3.22)
file(MAKE_DIRECTORY "${WORK}")
find_program(XVFB_RUN xvfb-run)
if(XVFB_RUN)
  set(launcher ${XVFB_RUN} -a -s "-screen 0 1024x768x24")
elseif(DEFINED ENV{DISPLAY})
  set(launcher "")
else()
  message("SKIP: no Xvfb (apt install xvfb) and no display: the viewer needs a window")
  return()
endif()
set(small --trees 300 --terrain-size 200 --terrain-resolution 32 --size 320x180 --map-size 1024)
execute_process(COMMAND ${launcher} ${VIEWER} ${small} --technique lispsm --frames 10 --truth
                        --screenshot "${WORK}/viewer.png" --save-state "${WORK}/state.json" --window-shot "${WORK}/window.png"
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "viewer: exit ${rc}: ${out} ${err}")
endif()
if(NOT out MATCHES "drew 10 frames" OR NOT EXISTS "${WORK}/viewer.png" OR NOT EXISTS "${WORK}/window.png")
  message(FATAL_ERROR "viewer: did not draw its frames or write its pictures: ${out} ${err}")
endif()
# Shadows where truth has them, and few errors.
string(REGEX MATCH "wrong ([0-9.]+) % of ([0-9]+) valid pixels, ([0-9]+) drawn in shadow" m "${out}")
if(NOT m OR CMAKE_MATCH_3 LESS 500 OR CMAKE_MATCH_1 GREATER 5)
  message(FATAL_ERROR "viewer: the frame shows too few shadows or too many errors: ${out}")
endif()
execute_process(COMMAND ${SHADOWKIT} render --state "${WORK}/state.json" --out "${WORK}/render.png"
                RESULT_VARIABLE rc OUTPUT_QUIET ERROR_VARIABLE err)
file(SHA256 "${WORK}/viewer.png" a)
file(SHA256 "${WORK}/render.png" b)
if(NOT rc EQUAL 0 OR NOT a STREQUAL b)
  message(FATAL_ERROR "render --state: not the viewer's image (rc ${rc}) ${err}")
endif()
message("viewer: ${m}; render --state gives the same image")
