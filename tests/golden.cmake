# Image regression: render scenes/default.json once (a fixture), then compare each scene with its
# reviewed image in golden/, with the tolerance of golden/thresholds.csv.
set(GOLDEN_OUT ${CMAKE_CURRENT_BINARY_DIR}/golden_check)
add_test(NAME render_default_scenes
  COMMAND sgapi-render ${PROJECT_SOURCE_DIR}/scenes/default.json -o ${GOLDEN_OUT})
set_tests_properties(render_default_scenes PROPERTIES FIXTURES_SETUP default_renders)

file(STRINGS ${PROJECT_SOURCE_DIR}/golden/thresholds.csv GOLDEN_ROWS REGEX "^[^#]")
foreach(row ${GOLDEN_ROWS})
  string(REPLACE "," ";" f "${row}")
  list(GET f 0 scene)
  list(GET f 1 min_psnr)
  list(GET f 2 max_over2)
  list(GET f 3 max_cov)
  add_test(NAME golden_${scene}
    COMMAND sgapi-diff ${GOLDEN_OUT}/${scene}.png ${PROJECT_SOURCE_DIR}/golden/${scene}.png
            --min-psnr ${min_psnr} --max-over2 ${max_over2} --max-coverage ${max_cov})
  set_tests_properties(golden_${scene} PROPERTIES FIXTURES_REQUIRED default_renders)
endforeach()

# The external gapi-task suite, when it sits beside the checkout: every scene must render.
set(GAPI_TASK ${PROJECT_SOURCE_DIR}/../shared/gapi-task/scenes.json)
if(EXISTS ${GAPI_TASK})
  add_test(NAME render_gapi_task
    COMMAND sgapi-render ${GAPI_TASK} -o ${CMAKE_CURRENT_BINARY_DIR}/gapi_task)
endif()
