# add_engine_sample_test(NAME SAMPLE OWN ADAPTER EVAL [VIEW]): an engine adapter end to end under
# Xvfb (engine_sample_test.cmake): the sample target SAMPLE draws the adapter's ADAPTER and the
# engine's own OWN, each mask scored against the truth beside `eval` with EVAL (its options for
# the same set-up), from VIEW (the view's options; `aerial` by default). Included by each
# adapter's CMakeLists.txt.
function(add_engine_sample_test name sample own adapter eval)
  add_test(NAME ${name}
           COMMAND ${CMAKE_COMMAND} -DSHADOWKIT=$<TARGET_FILE:shadowkit> -DSAMPLE=$<TARGET_FILE:${sample}>
                   -DOWN=${own} -DADAPTER=${adapter} "-DEVAL_OPTIONS=${eval}" "-DVIEW=${ARGN}"
                   -DWORK=${CMAKE_CURRENT_BINARY_DIR}/${name} -P ${PROJECT_SOURCE_DIR}/adapters/engine_sample_test.cmake)
  set_tests_properties(${name} PROPERTIES LABELS gl SKIP_REGULAR_EXPRESSION "SKIP:")
endfunction()

# add_engine_sample_input_test(NAME SAMPLE): the sample refuses a camera or shots file that is a
# pipe or a directory in one line (engine_sample_input_test.cmake); no display needed.
function(add_engine_sample_input_test name sample)
  add_test(NAME ${name}
           COMMAND ${CMAKE_COMMAND} -DSAMPLE=$<TARGET_FILE:${sample}> -DWORK=${CMAKE_CURRENT_BINARY_DIR}/${name}
                   -P ${PROJECT_SOURCE_DIR}/adapters/engine_sample_input_test.cmake)
endfunction()

# A spot light behind and above the camera, shining into the view over the patch: the camera
# sees part of its cone, so the adapter's map narrows to it (tools/measure-engine-spots.sh's
# "behind" lamp). For add_engine_sample_test's VIEW, with the spot's map size as EVAL.
set(SHADOWKIT_ENGINE_SPOT_VIEW
    "--view aerial --eye 0,40,0 --dir 0,-0.7,-1 --sun off --size 640x360 --light spot:0,50,15,0,-1,-0.6,100,80")
# A point light above and ahead of the camera, outside the view, lighting the patch the camera
# sees (tools/measure-engine-points.sh's "ahead" lamp): the adapters' one map over what the camera
# sees, where OSG's own misses the view (about 25 % wrong) and OGRE's 120° leaves parts out (7 %).
# EVAL's cube of 2048² faces beside it.
set(SHADOWKIT_ENGINE_POINT_VIEW
    "--view aerial --eye 0,40,0 --dir 0,-0.7,-1 --sun off --size 640x360 --light point:0,50,-45,60")
# A point light 12 m up among what the camera sees (tools/measure-engine-points.sh's "among-c"
# lamp): no one map holds it; OGRE's own errs about 49 %, the adapter's aimed map about 3 %, and
# its cube faces (the sample's `cube`, six shadow textures) within a few tenths of EVAL's cube.
set(SHADOWKIT_ENGINE_POINT_AMONG_VIEW
    "--view aerial --eye 0,40,0 --dir 0,-0.7,-1 --sun off --size 640x360 --light point:-20,12,-60,50")
