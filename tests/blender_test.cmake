# The Blender bridge with Debian's blender: build a scene in Blender and render
# its photo with Cycles, export it with tools/blender/relight_export.py,
# analyse it with relight (the albedo must be the materials' colours: camera,
# light units and world agree), and bring relight's rig back into Blender.
#   cmake -DBLENDER=... -DRELIGHT=... -DSOURCE_DIR=... -DWORK=... -P blender_test.cmake
file(REMOVE_RECURSE "${WORK}")
file(MAKE_DIRECTORY "${WORK}")
set(exporter "${SOURCE_DIR}/tools/blender/relight_export.py")

# Run in WORK, so that the relative paths below are relative to it (as a user's would be).
function(run)
  execute_process(COMMAND ${ARGN} WORKING_DIRECTORY "${WORK}" RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "failed (${rc}): ${ARGN}\n${out}\n${err}")
  endif()
  message(STATUS "${out}")
endfunction()

set(blender "${BLENDER}" -b --factory-startup --python-exit-code 1)
run(${blender} --python "${SOURCE_DIR}/tools/blender/make_example_scene.py" -- scene.blend photo.exr --render 32)
# (Blender itself resolves a relative .blend against $PWD, which WORKING_DIRECTORY does not set.)
run("${BLENDER}" -b "${WORK}/scene.blend" --python-exit-code 1 --python "${exporter}" -- export --photo photo.exr)
run("${RELIGHT}" rig "${WORK}/export/scene.json" -o "${WORK}/rig.json")
run("${RELIGHT}" analyze "${WORK}/export/scene.json" -o "${WORK}/analysis" --spp 16)
run("${BLENDER}" -b "${WORK}/scene.blend" --python-exit-code 1 --python "${SOURCE_DIR}/tests/blender/check_export.py" --
    "${exporter}" "${WORK}/export" "${WORK}/rig.json" "${WORK}/analysis" "${RELIGHT}")
# From the command line a refused export is exit 2 and one line naming what is wrong.
execute_process(COMMAND "${BLENDER}" -b "${WORK}/scene.blend" --python-exit-code 1 --python "${exporter}" --
                        "${WORK}/refused" --photo "${WORK}/no-such-photo.exr"
                RESULT_VARIABLE rc OUTPUT_QUIET ERROR_VARIABLE err)
string(REGEX MATCHALL "relight_export: [^\n]*" lines "${err}")
list(LENGTH lines count)
if(NOT rc EQUAL 2 OR NOT count EQUAL 1 OR NOT err MATCHES "no-such-photo.exr does not exist" OR EXISTS "${WORK}/refused")
  message(FATAL_ERROR "a missing photo: exit ${rc}, stderr:\n${err}")
endif()

# An animated light exported as a rig's keys (tests/blender/animated_rig.py),
# rendered by relight frame by frame.
run(${blender} "${WORK}/scene.blend" --python "${SOURCE_DIR}/tests/blender/animated_rig.py" -- "${exporter}"
    "${WORK}/animated.json")
run("${RELIGHT}" render "${WORK}/export/scene.json" --analysis "${WORK}/analysis" --rig "${WORK}/animated.json"
    --frames 1-3 -o "${WORK}/frames/relit.##.exr")
foreach(frame 01 02 03)
  if(NOT EXISTS "${WORK}/frames/relit.${frame}.exr" OR NOT EXISTS "${WORK}/frames/relit.${frame}.png")
    message(FATAL_ERROR "relight render --frames 1-3 wrote no frame ${frame}")
  endif()
endforeach()

# A tracked shot (tests/blender/tracked_shot.py): the camera dollied over
# three Cycles frames and exported with --shot, then analysed by relight
# (the albedo fused over the frames) and re-lit frame by frame.
run(${blender} "${WORK}/scene.blend" --python "${SOURCE_DIR}/tests/blender/tracked_shot.py" -- "${exporter}"
    "${WORK}/shot")
run("${RELIGHT}" analyze "${WORK}/shot/scene.json" -o "${WORK}/shot_analysis" --spp 8)
run("${RELIGHT}" render "${WORK}/shot/scene.json" --analysis "${WORK}/shot_analysis" --rig "${WORK}/rig.json"
    -o "${WORK}/shot_relit/relit.####.exr")
foreach(frame 0001 0002 0003)
  if(NOT EXISTS "${WORK}/shot_relit/relit.${frame}.exr")
    message(FATAL_ERROR "relight render of the tracked shot wrote no frame ${frame}")
  endif()
endforeach()
