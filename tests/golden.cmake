# Image regression against the lavapipe reference, with the targets of golden/thresholds.csv:
# - the project's scene files (suite = file stem: scenes/<suite>.json, e.g. default,
#   transparency) against the committed lavapipe renders in golden/ (golden_<scene>);
# - the same scenes against a live lavapipe render (live_<scene>);
# - the hard cases of scenes/hard/ against a live lavapipe render (hard_<scene>); where a scene
#   has a twin <scene>.reference.json, lavapipe renders the twin (the same image in exact
#   arithmetic, without a precision problem of lavapipe's: docs/accuracy.md);
# - the external gapi-task suite, when it sits beside the checkout, against a live lavapipe
#   render (gapi_<scene>).
# Each check renders its scene with sgapi-render --compare --thresholds golden/thresholds.csv (the
# scene's row: suite = the file's stem, or its folder's name for scenes/hard/ and the external
# suite), which also writes a heat map.
# Then one run of every scene file and hard case together writes the regression report of
# `make test` to build/report/ (index.html, results.json) and its JUnit file to build/junit.xml.
set(CHECK_OUT ${CMAKE_CURRENT_BINARY_DIR}/image_checks)
# Debian's interpreter (another python3 may come first on PATH).
find_program(PYTHON3 NAMES python3 PATHS /usr/bin NO_DEFAULT_PATH)
set(GAPI_TASK ${PROJECT_SOURCE_DIR}/../shared/gapi-task/scenes.json)
set(HARD_DIR ${PROJECT_SOURCE_DIR}/scenes/hard)

file(STRINGS ${PROJECT_SOURCE_DIR}/golden/thresholds.csv ROWS REGEX "^[^#]")
set(HARD_REF_FILES)
set(HARD_FILES)
set(SUITES)
set(THRESHOLDS ${PROJECT_SOURCE_DIR}/golden/thresholds.csv)
foreach(row ${ROWS})
  if(row MATCHES "^([^,]+),")
    set(suite ${CMAKE_MATCH_1})
    if(NOT suite STREQUAL "hard" AND NOT suite STREQUAL "gapi-task" AND NOT suite IN_LIST SUITES)
      list(APPEND SUITES ${suite})
    endif()
  endif()
  if(row MATCHES "^hard,([^,]+),")
    set(file ${HARD_DIR}/${CMAKE_MATCH_1}.json)
    if(EXISTS ${HARD_DIR}/${CMAKE_MATCH_1}.reference.json)
      set(file ${HARD_DIR}/${CMAKE_MATCH_1}.reference.json)
    endif()
    list(APPEND HARD_REF_FILES ${file})
    list(APPEND HARD_FILES ${HARD_DIR}/${CMAKE_MATCH_1}.json)
  endif()
endforeach()

# The live checks need sgapi-ref; without it (-DSGAPI_BUILD_REFERENCE=OFF, as in the sanitizer
# build, where Mesa is not instrumented) only the checks against golden/ remain.
if(TARGET sgapi-ref)
  foreach(suite ${SUITES})
    add_test(NAME ref_${suite}_scenes
      COMMAND sgapi-ref ${PROJECT_SOURCE_DIR}/scenes/${suite}.json -o ${CHECK_OUT}/ref_${suite}
              --strict)
    set_tests_properties(ref_${suite}_scenes PROPERTIES FIXTURES_SETUP ref_${suite})
  endforeach()
  if(EXISTS ${GAPI_TASK})
    add_test(NAME ref_gapi_task COMMAND sgapi-ref ${GAPI_TASK} -o ${CHECK_OUT}/ref_gapi_task)
    set_tests_properties(ref_gapi_task PROPERTIES FIXTURES_SETUP ref_gapi_task)
  endif()
  add_test(NAME ref_hard_cases COMMAND sgapi-ref ${HARD_REF_FILES} -o ${CHECK_OUT}/ref_hard --strict)
  set_tests_properties(ref_hard_cases PROPERTIES FIXTURES_SETUP ref_hard)
endif()

# One check: render `scene` of `file` with sgapi and compare it with `ref_dir`/<scene>.png, against
# the scene's row of golden/thresholds.csv. The project's own files are read with --strict: an
# unknown key in them fails the check.
function(sg_image_check name file scene ref_dir out_dir fixture)
  set(strict)
  if(NOT file STREQUAL GAPI_TASK)
    set(strict --strict)
  endif()
  add_test(NAME ${name}
    COMMAND sgapi-render ${file} --scene ${scene} -o ${out_dir} --compare ${ref_dir}
            --thresholds ${THRESHOLDS} ${strict})
  if(fixture)
    set_tests_properties(${name} PROPERTIES FIXTURES_REQUIRED ${fixture})
  endif()
endfunction()

foreach(row ${ROWS})
  string(REPLACE "," ";" f "${row}")
  list(GET f 0 suite)
  list(GET f 1 scene)
  if(suite IN_LIST SUITES)
    set(file ${PROJECT_SOURCE_DIR}/scenes/${suite}.json)
    sg_image_check(golden_${scene} ${file} ${scene} ${PROJECT_SOURCE_DIR}/golden
                   ${CHECK_OUT}/golden "")
    if(TARGET sgapi-ref)
      sg_image_check(live_${scene} ${file} ${scene} ${CHECK_OUT}/ref_${suite}
                     ${CHECK_OUT}/live ref_${suite})
    endif()
    # Lines: every pixel whose coverage differs from lavapipe's must be one of the kinds
    # docs/accuracy.md explains (tools/line-mismatch.py sorts them; any other fails).
    if(suite STREQUAL "lines" AND PYTHON3)
      set_tests_properties(golden_${scene} PROPERTIES FIXTURES_SETUP golden_${scene}_image)
      add_test(NAME lines_explained_${scene}
        COMMAND ${PYTHON3} ${PROJECT_SOURCE_DIR}/tools/line-mismatch.py ${file} ${scene}
                ${CHECK_OUT}/golden/${scene}.png ${PROJECT_SOURCE_DIR}/golden/${scene}.png)
      set_tests_properties(lines_explained_${scene} PROPERTIES
        FIXTURES_REQUIRED golden_${scene}_image)
    endif()
  elseif(suite STREQUAL "hard")
    if(TARGET sgapi-ref)
      sg_image_check(hard_${scene} ${HARD_DIR}/${scene}.json ${scene} ${CHECK_OUT}/ref_hard
                     ${CHECK_OUT}/hard ref_hard)
    else() # rendered unchecked, so that the sanitizer build runs every hard case too
      add_test(NAME hard_${scene}
        COMMAND sgapi-render ${HARD_DIR}/${scene}.json -o ${CHECK_OUT}/hard --strict)
    endif()
  elseif(suite STREQUAL "gapi-task" AND EXISTS ${GAPI_TASK} AND TARGET sgapi-ref)
    sg_image_check(gapi_${scene} ${GAPI_TASK} ${scene} ${CHECK_OUT}/ref_gapi_task
                   ${CHECK_OUT}/gapi_task ref_gapi_task)
  endif()
endforeach()

# Without the reference, the external suite is still rendered (unchecked), so that the sanitizer
# build runs its scenes too.
if(EXISTS ${GAPI_TASK} AND NOT TARGET sgapi-ref)
  add_test(NAME render_gapi_task COMMAND sgapi-render ${GAPI_TASK} -o ${CHECK_OUT}/gapi_task)
endif()

# The regression report of `make test`: the project's scene files against golden/ and the hard
# cases against their live lavapipe renders, in one run, so one page and one JUnit file hold
# them all (build/report/index.html, build/junit.xml; .ci/run prints where they are).
set(REPORT_FILES)
foreach(suite ${SUITES})
  list(APPEND REPORT_FILES ${PROJECT_SOURCE_DIR}/scenes/${suite}.json)
endforeach()
set(REPORT_REFS ${PROJECT_SOURCE_DIR}/golden)
if(TARGET sgapi-ref)
  list(APPEND REPORT_FILES ${HARD_FILES})
  list(APPEND REPORT_REFS ${CHECK_OUT}/ref_hard)
endif()
add_test(NAME regression_report
  COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/make_report.sh $<TARGET_FILE:sgapi-render>
          ${THRESHOLDS} ${PROJECT_BINARY_DIR} "${REPORT_REFS}" ${REPORT_FILES})
if(TARGET sgapi-ref)
  set_tests_properties(regression_report PROPERTIES FIXTURES_REQUIRED ref_hard)
endif()
