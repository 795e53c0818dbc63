# ctest docs.api_reference: runs Doxygen as the `docs` target does and checks
# that it warns about nothing and that the key entry points have their pages
# with their comments.
execute_process(COMMAND ${DOXYGEN} ${DOXYFILE} WORKING_DIRECTORY ${SOURCE_DIR}
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "doxygen failed (${rc}): ${err}")
endif()
file(READ ${OUT}/warnings.log warnings)
if(NOT warnings STREQUAL "")
  message(FATAL_ERROR "doxygen warnings:\n${warnings}")
endif()
file(GLOB_RECURSE pages ${OUT}/html/*.html)
set(all "")
foreach(p ${pages})
  file(READ ${p} text)
  string(APPEND all "${text}")
endforeach()
foreach(needle "DesignTaebp" "SolveTrustAwarePersuasion" "MinimalNudge" "RunPolicy"
               "RunExperiment" "RunSweep" "LoadExperimentConfig"
               "the minimal nudge that makes" "as one set")
  string(FIND "${all}" "${needle}" at)
  if(at EQUAL -1)
    message(FATAL_ERROR "the API reference does not mention '${needle}'")
  endif()
endforeach()
list(LENGTH pages n)
message(STATUS "API reference: ${n} pages in ${OUT}/html")
