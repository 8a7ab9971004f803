# An engine adapter end to end: a small forest exported as OBJ, drawn by the engine's sample
# (OpenSceneGraph's, OGRE's) from a standard view with shadowkit's technique ADAPTER (default
# tsm) and with the engine's own technique OWN, each mask scored against the ray-traced truth
# and put beside `eval`'s figure for the same set-up, EVAL_OPTIONS (default --technique ADAPTER;
# engine_sample_check.py says what must hold). VIEW (default --view aerial --size 640x360) is the
# view's options for setup, score and eval alike: with `--sun off --light spot:...` the sample
# draws that spot light's shadows and `score --light` scores them.
#   cmake -DSHADOWKIT=... -DSAMPLE=... -DOWN=... -DWORK=... [-DADAPTER=csm "-DEVAL_OPTIONS=..."]
#         ["-DVIEW=..."] -P engine_sample_test.cmake
if(NOT ADAPTER)
  set(ADAPTER tsm)
endif()
if(NOT EVAL_OPTIONS)
  set(EVAL_OPTIONS "--technique ${ADAPTER}")
endif()
separate_arguments(eval_options UNIX_COMMAND "${EVAL_OPTIONS}")
file(REMOVE_RECURSE "${WORK}")
file(MAKE_DIRECTORY "${WORK}")
find_program(XVFB_RUN xvfb-run)
if(NOT XVFB_RUN)
  message("SKIP: no Xvfb (apt install xvfb): the engines' Debian builds draw through GLX only")
  return()
endif()
set(forest --trees 300 --terrain-size 256) # a dense patch: a third of the view in shadow
if(VIEW)
  separate_arguments(view UNIX_COMMAND "${VIEW}")
else()
  set(view --view aerial --size 640x360)
endif()
function(run)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${ARGN}: exit ${rc}: ${out} ${err}")
  endif()
  message("${out}")
endfunction()
run(${SHADOWKIT} export ${forest} --out "${WORK}/forest.obj")
execute_process(COMMAND ${SHADOWKIT} setup ${view} ${forest} OUTPUT_FILE "${WORK}/camera.json" RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "shadowkit setup: exit ${rc}")
endif()
file(WRITE "${WORK}/shots.txt"
     "${WORK}/camera.json ${ADAPTER} ${WORK}/adapter.png\n${WORK}/camera.json ${OWN} ${WORK}/own.png\n")
run(${XVFB_RUN} -a ${SAMPLE} "${WORK}/forest.obj" --shots "${WORK}/shots.txt" --size 640x360)
foreach(mask adapter own)
  run(${SHADOWKIT} score "${WORK}/${mask}.png" ${forest} ${view} --json "${WORK}/${mask}.json")
endforeach()
run(${SHADOWKIT} eval ${forest} ${view} ${eval_options} --json "${WORK}/eval.json")
find_program(PYTHON NAMES python3 REQUIRED)
run(${PYTHON} "${CMAKE_CURRENT_LIST_DIR}/engine_sample_check.py" "${WORK}/adapter.png" "${WORK}/adapter.json"
    "${WORK}/own.json" "${WORK}/eval.json")
