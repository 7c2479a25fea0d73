# Closed colon surfaces made the way the pipeline makes them: ColonPhantom (no fluid) ->
# ColonSegmentation -> ColonSurface, supine and prone, in OUT.
# cmake -DPHANTOM=.. -DSEGMENTATION=.. -DSURFACE=.. -DOUT=.. -DSPACING=2 -DSEED=2 -P MakeLandmarksData.cmake
file(MAKE_DIRECTORY ${OUT})
function(run)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_QUIET ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${ARGN}: ${rc} ${err}")
  endif()
endfunction()
run(${PHANTOM} --outputDirectory ${OUT} --spacing ${SPACING},${SPACING},${SPACING} --seed ${SEED} --noFluid)
foreach(p supine prone)
  run(${SEGMENTATION} ${OUT}/${p}.nrrd ${OUT}/${p}_label.nrrd)
  run(${SURFACE} --referenceCT ${OUT}/${p}.nrrd --targetFaces 40000 ${OUT}/${p}_label.nrrd ${OUT}/${p}_surface.vtp)
endforeach()
