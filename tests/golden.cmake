# Image regression against the lavapipe reference, with the targets of golden/thresholds.csv:
# - default scenes against the committed lavapipe renders in golden/ (golden_<scene>);
# - default scenes against a live lavapipe render (live_<scene>);
# - the hard cases of scenes/hard/ against a live lavapipe render (hard_<scene>); where a scene
#   has a twin <scene>.reference.json, lavapipe renders the twin (the same image in exact
#   arithmetic, without a precision problem of lavapipe's: docs/accuracy.md);
# - the external gapi-task suite, when it sits beside the checkout, against a live lavapipe
#   render (gapi_<scene>).
# Each check renders its scene with sgapi-render --compare, which also writes a heat map.
set(CHECK_OUT ${CMAKE_CURRENT_BINARY_DIR}/image_checks)
set(DEFAULT_SCENES ${PROJECT_SOURCE_DIR}/scenes/default.json)
set(GAPI_TASK ${PROJECT_SOURCE_DIR}/../shared/gapi-task/scenes.json)
set(HARD_DIR ${PROJECT_SOURCE_DIR}/scenes/hard)

file(STRINGS ${PROJECT_SOURCE_DIR}/golden/thresholds.csv ROWS REGEX "^[^#]")
set(HARD_REF_FILES)
foreach(row ${ROWS})
  if(row MATCHES "^hard,([^,]+),")
    set(file ${HARD_DIR}/${CMAKE_MATCH_1}.json)
    if(EXISTS ${HARD_DIR}/${CMAKE_MATCH_1}.reference.json)
      set(file ${HARD_DIR}/${CMAKE_MATCH_1}.reference.json)
    endif()
    list(APPEND HARD_REF_FILES ${file})
  endif()
endforeach()

# The live checks need sgapi-ref; without it (-DSGAPI_BUILD_REFERENCE=OFF, as in the sanitizer
# build, where Mesa is not instrumented) only the checks against golden/ remain.
if(TARGET sgapi-ref)
  add_test(NAME ref_default_scenes COMMAND sgapi-ref ${DEFAULT_SCENES} -o ${CHECK_OUT}/ref_default)
  set_tests_properties(ref_default_scenes PROPERTIES FIXTURES_SETUP ref_default)
  if(EXISTS ${GAPI_TASK})
    add_test(NAME ref_gapi_task COMMAND sgapi-ref ${GAPI_TASK} -o ${CHECK_OUT}/ref_gapi_task)
    set_tests_properties(ref_gapi_task PROPERTIES FIXTURES_SETUP ref_gapi_task)
  endif()
  add_test(NAME ref_hard_cases COMMAND sgapi-ref ${HARD_REF_FILES} -o ${CHECK_OUT}/ref_hard)
  set_tests_properties(ref_hard_cases PROPERTIES FIXTURES_SETUP ref_hard)
endif()

# One check: render `scene` of `file` with sgapi and compare it with `ref_dir`/<scene>.png.
function(sg_image_check name file scene ref_dir out_dir fixture)
  add_test(NAME ${name}
    COMMAND sgapi-render ${file} --scene ${scene} -o ${out_dir} --compare ${ref_dir}
            --min-psnr ${ARGV6} --max-over2 ${ARGV7} --max-coverage ${ARGV8})
  if(fixture)
    set_tests_properties(${name} PROPERTIES FIXTURES_REQUIRED ${fixture})
  endif()
endfunction()

foreach(row ${ROWS})
  string(REPLACE "," ";" f "${row}")
  list(GET f 0 suite)
  list(GET f 1 scene)
  list(GET f 2 psnr)
  list(GET f 3 over2)
  list(GET f 4 cov)
  if(suite STREQUAL "default")
    sg_image_check(golden_${scene} ${DEFAULT_SCENES} ${scene} ${PROJECT_SOURCE_DIR}/golden
                   ${CHECK_OUT}/golden "" ${psnr} ${over2} ${cov})
    if(TARGET sgapi-ref)
      sg_image_check(live_${scene} ${DEFAULT_SCENES} ${scene} ${CHECK_OUT}/ref_default
                     ${CHECK_OUT}/live ref_default ${psnr} ${over2} ${cov})
    endif()
  elseif(suite STREQUAL "hard")
    if(TARGET sgapi-ref)
      sg_image_check(hard_${scene} ${HARD_DIR}/${scene}.json ${scene} ${CHECK_OUT}/ref_hard
                     ${CHECK_OUT}/hard ref_hard ${psnr} ${over2} ${cov})
    else() # rendered unchecked, so that the sanitizer build runs every hard case too
      add_test(NAME hard_${scene} COMMAND sgapi-render ${HARD_DIR}/${scene}.json -o ${CHECK_OUT}/hard)
    endif()
  elseif(suite STREQUAL "gapi-task" AND EXISTS ${GAPI_TASK} AND TARGET sgapi-ref)
    sg_image_check(gapi_${scene} ${GAPI_TASK} ${scene} ${CHECK_OUT}/ref_gapi_task
                   ${CHECK_OUT}/gapi_task ref_gapi_task ${psnr} ${over2} ${cov})
  endif()
endforeach()

# Without the reference, the external suite is still rendered (unchecked), so that the sanitizer
# build runs its scenes too.
if(EXISTS ${GAPI_TASK} AND NOT TARGET sgapi-ref)
  add_test(NAME render_gapi_task COMMAND sgapi-render ${GAPI_TASK} -o ${CHECK_OUT}/gapi_task)
endif()
