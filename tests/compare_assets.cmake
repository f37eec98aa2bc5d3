# Regenerates the default scenes and compares them byte for byte with the committed ones.
#
#   cmake -DASSETS_TOOL=<sgapi-assets> -DOUT=<scratch dir> -DREF=<scenes dir> -P compare_assets.cmake
#
# Fails naming every file that differs, that the generator wrote but is not committed, or that is
# committed under assets/ but no longer generated.
cmake_minimum_required(VERSION 3.16)

foreach(var ASSETS_TOOL OUT REF)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "compare_assets: -D${var}=... is required")
  endif()
endforeach()

file(REMOVE_RECURSE "${OUT}")
execute_process(COMMAND "${ASSETS_TOOL}" "${OUT}" RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "compare_assets: ${ASSETS_TOOL} failed (${rc})")
endif()

file(GLOB_RECURSE generated LIST_DIRECTORIES false RELATIVE "${OUT}" "${OUT}/*")
list(SORT generated)
list(LENGTH generated count)
if(count EQUAL 0)
  message(FATAL_ERROR "compare_assets: ${ASSETS_TOOL} wrote nothing")
endif()

set(bad "")
foreach(f IN LISTS generated)
  if(NOT EXISTS "${REF}/${f}")
    list(APPEND bad "${f} (generated, not committed)")
  else()
    execute_process(COMMAND "${CMAKE_COMMAND}" -E compare_files "${OUT}/${f}" "${REF}/${f}"
                    RESULT_VARIABLE differs OUTPUT_QUIET ERROR_QUIET)
    if(NOT differs EQUAL 0)
      list(APPEND bad "${f} (differs)")
    endif()
  endif()
endforeach()

file(GLOB_RECURSE committed LIST_DIRECTORIES false RELATIVE "${REF}" "${REF}/assets/*")
foreach(f IN LISTS committed)
  if(NOT f IN_LIST generated)
    list(APPEND bad "${f} (committed, no longer generated)")
  endif()
endforeach()

if(bad)
  list(JOIN bad "\n  " lines)
  message(FATAL_ERROR "compare_assets: regenerated scenes do not match ${REF}:\n  ${lines}\n"
                      "Run sgapi-assets on that folder and review the change.")
endif()
message(STATUS "compare_assets: ${count} files identical")
