# `pip install .` into a fresh virtual environment that sees Debian's packages, offline (no
# index, no pip configuration of the machine), then imports tessera from it and meshes a sphere:
# the set-up of docs/python.md, end to end. The CMake build goes where `pip install .` puts it,
# build-pip/ beside build/: at the same depth under the repository, so that ccache (also with a
# base_dir) finds the main build's objects and only the module is linked again.
file(REMOVE_RECURSE ${WORK_DIR})
execute_process(COMMAND ${PYTHON} -m venv --system-site-packages ${WORK_DIR}/venv
                RESULT_VARIABLE result OUTPUT_QUIET ERROR_QUIET)
if(NOT result EQUAL 0)
  message("tessera-skip: ${PYTHON} -m venv failed (Debian's python3-venv is not installed)")
  return()
endif()
set(ENV{PIP_CONFIG_FILE} /dev/null)
execute_process(COMMAND ${WORK_DIR}/venv/bin/python -m pip install --no-index --no-cache-dir
                        --disable-pip-version-check ${SOURCE_DIR}
                RESULT_VARIABLE result)
if(NOT result EQUAL 0)
  message(FATAL_ERROR "pip install --no-index ${SOURCE_DIR} failed")
endif()
execute_process(COMMAND ${WORK_DIR}/venv/bin/python -c "
import pathlib, sys, tessera
assert pathlib.Path(tessera.__file__).is_relative_to(sys.prefix), tessera.__file__
m = tessera.mesh('sphere', tolerance=1e-2)
assert m.summary['topology']['euler_characteristic'] == 2, m.summary['topology']
print('tessera from', tessera.__file__, m.vertices.shape)"
                WORKING_DIRECTORY ${WORK_DIR} RESULT_VARIABLE result)
if(NOT result EQUAL 0)
  message(FATAL_ERROR "the installed tessera failed to import or to mesh the sphere")
endif()
