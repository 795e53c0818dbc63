# ctest helper: regenerate the plain files with default arguments into a temp dir and
# compare them byte for byte with the committed ones.
# Usage: cmake -DPYTHON=... -DSCRIPT=... -DSRC_DIR=... -DTMP_DIR=... -P check_in_sync.cmake
file(REMOVE_RECURSE "${TMP_DIR}")
file(MAKE_DIRECTORY "${TMP_DIR}")
execute_process(COMMAND "${PYTHON}" "${SCRIPT}" --out-dir "${TMP_DIR}" RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "make_figure8.py failed (${rc})")
endif()
set(failed "")
foreach(f figure8.nod.xml figure8.edg.xml figure8.con.xml)
  execute_process(COMMAND "${CMAKE_COMMAND}" -E compare_files "${SRC_DIR}/${f}" "${TMP_DIR}/${f}"
                  RESULT_VARIABLE diff)
  if(NOT diff EQUAL 0)
    list(APPEND failed ${f})
  endif()
endforeach()
if(failed)
  message(FATAL_ERROR "sumo_net/${failed} differ from `python3 sumo_net/make_figure8.py` output "
                      "(regenerate with: python3 sumo_net/make_figure8.py)")
endif()
message(STATUS "sumo_net plain files are in sync with make_figure8.py")
