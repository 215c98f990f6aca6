# The Python package (pytest, Debian's /usr/bin/python3): bindings against the pcr tool's JSON bit for
# bit, errors, paths, the workspace sampler, the examples (Dask LocalCluster, matplotlib) and the blocks
# of docs/python.md.
if(PCR_BUILD_PYTHON)
  add_test(NAME test_python COMMAND ${Python3_EXECUTABLE} -m pytest -q -p no:cacheprovider
                                    ${CMAKE_CURRENT_LIST_DIR}/python)
  set_tests_properties(test_python PROPERTIES LABELS "robots;python" ENVIRONMENT
                       "PYTHONPATH=${PROJECT_BINARY_DIR}/python;PCR_TOOL=$<TARGET_FILE:pcr>;PCR_MODEL_DIR=${PROJECT_SOURCE_DIR}/models;MPLBACKEND=Agg")
endif()
