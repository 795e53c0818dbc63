# ctest -N over the build, then -N with every label excluded: the tests left
# have no label (a labelled run, e.g. tools/test --sanitize's `-L sanitize`,
# would silently skip them). Fails naming them.
execute_process(COMMAND ${CTEST} -N -LE "^(unit|sumo|study|sanitize-unit|sanitize-sumo)$"
                WORKING_DIRECTORY ${BUILD} OUTPUT_VARIABLE out RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "ctest -N failed (${rc}): ${out}")
endif()
string(REGEX MATCHALL "Test +#[0-9]+: [^\n]+" unlabelled "${out}")
# This test itself is labelled; a target not built shows as <target>_NOT_BUILT.
if(unlabelled)
  string(REPLACE ";" "\n" list "${unlabelled}")
  message(FATAL_ERROR "tests without a unit/sumo/study/sanitize-unit/sanitize-sumo label (tests/CMakeLists.txt):\n${list}")
endif()
string(REGEX MATCH "Total Tests: ([0-9]+)" total "${out}")
message(STATUS "every test labelled (${total} unlabelled)")
