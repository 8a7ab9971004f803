# examples/minimal_gl as a consumer builds it: install shadowkit into a scratch prefix, configure
# and build the example against the installed package, draw its frame with and without shadows,
# with PCF and PCSS, in OpenGL's depth convention and as a reversed-Z engine, under Xvfb (or the
# display there is), and check that the shadows darken the ground and that both conventions draw
# the same frame; then the same at night under a spot and a point lamp (--lamps: the installed
# shadowkit_local_shadows.glsl).
#   cmake -DBUILD_DIR=... -DSOURCE_DIR=... -DWORK=... -P minimal_gl_test.cmake
file(REMOVE_RECURSE "${WORK}")
execute_process(COMMAND ${CMAKE_COMMAND} --install "${BUILD_DIR}" --prefix "${WORK}/prefix" RESULT_VARIABLE rc OUTPUT_QUIET)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "install failed")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} -S "${SOURCE_DIR}/examples/minimal_gl" -B "${WORK}/build" "-DCMAKE_PREFIX_PATH=${WORK}/prefix"
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "minimal_gl: configure against the installed package failed: ${out} ${err}")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} --build "${WORK}/build" RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "minimal_gl: build failed: ${out} ${err}")
endif()

find_program(XVFB_RUN xvfb-run)
if(XVFB_RUN)
  set(launcher ${XVFB_RUN} -a -s "-screen 0 1024x768x24")
elseif(DEFINED ENV{DISPLAY})
  set(launcher "")
else()
  message("SKIP: built, but no Xvfb (apt install xvfb) and no display to draw in: GLFW needs one")
  return()
endif()
# Each frame and its flags: PCF and PCSS, each as an OpenGL program and as a reversed-Z one.
set(frames shadows no-shadows pcss reversed-z pcss-reversed-z lamps lamps-no-shadows lamps-pcss lamps-reversed-z
           lamps-pcss-reversed-z)
set(flags_shadows "")
set(flags_no-shadows --no-shadows)
set(flags_pcss --pcss)
set(flags_reversed-z --reversed-z)
set(flags_pcss-reversed-z --pcss --reversed-z)
set(flags_lamps --lamps)
set(flags_lamps-no-shadows --lamps --no-shadows)
set(flags_lamps-pcss --lamps --pcss)
set(flags_lamps-reversed-z --lamps --reversed-z)
set(flags_lamps-pcss-reversed-z --lamps --pcss --reversed-z)
foreach(frame ${frames})
  execute_process(COMMAND ${launcher} "${WORK}/build/minimal_gl" "${WORK}/${frame}.png" ${flags_${frame}}
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0 OR NOT EXISTS "${WORK}/${frame}.png")
    message(FATAL_ERROR "minimal_gl ${flags_${frame}}: exit ${rc}: ${out} ${err}")
  endif()
  message("${out}")
endforeach()
find_program(PYTHON NAMES python3 REQUIRED)
# Shadows darken the ground, with either filter; a reversed-Z engine draws the same frames; PCSS's
# frame is not PCF's (its search read the depths: without them it falls back to the hard test). The
# lamps alike: their shadows darken the ground, 1 − distance / range draws what distance / range
# does, and the 70 cm lamps' penumbrae are not the hard test's edges.
foreach(check "shadows.png;no-shadows.png" "pcss.png;no-shadows.png" "--same;shadows.png;reversed-z.png"
        "--same;pcss.png;pcss-reversed-z.png" "--differ;shadows.png;pcss.png"
        "lamps.png;lamps-no-shadows.png" "lamps-pcss.png;lamps-no-shadows.png" "--same;lamps.png;lamps-reversed-z.png"
        "--same;lamps-pcss.png;lamps-pcss-reversed-z.png" "--differ;lamps.png;lamps-pcss.png")
  set(arguments)
  foreach(a ${check})
    if(a MATCHES "^--")
      list(APPEND arguments "${a}")
    else()
      list(APPEND arguments "${WORK}/${a}")
    endif()
  endforeach()
  execute_process(COMMAND ${PYTHON} "${SOURCE_DIR}/tests/shadow_png_check.py" ${arguments}
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  message("${check}: ${out}")
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "minimal_gl (${check}): ${out} ${err}")
  endif()
endforeach()
