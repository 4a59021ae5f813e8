# `cmake --install` (make install) and the Debian package (make package).
# Layout: <prefix>/bin/ballista; <prefix>/share/ballista/{data,tools,examples}; the docs in
# <prefix>/share/doc/ballista. The binary finds data/ and tools/ from its own location
# (src/core/data_dir.hpp: <prefix>/bin/.. /share/ballista), so an installed or packaged ballista
# does not read the source tree it was built from.
include(GNUInstallDirs)
set(BALLISTA_SHARE_DIR ${CMAKE_INSTALL_DATADIR}/ballista)

install(TARGETS ballista RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(FILES ${PROJECT_SOURCE_DIR}/data/materials.yaml ${PROJECT_SOURCE_DIR}/data/validation_catalogue.yaml
        DESTINATION ${BALLISTA_SHARE_DIR}/data)
# The tools the commands run (figures, the verify report) and the output reader; not the
# developer tools (build comparison, fuzzers).
install(PROGRAMS
        ${PROJECT_SOURCE_DIR}/tools/plot_fragment_sweep.py
        ${PROJECT_SOURCE_DIR}/tools/jet_table.py
        ${PROJECT_SOURCE_DIR}/tools/plot_fragments.py
        ${PROJECT_SOURCE_DIR}/tools/plot_penetration.py
        ${PROJECT_SOURCE_DIR}/tools/plot_sweep_penetration.py
        ${PROJECT_SOURCE_DIR}/tools/read_output.py
        ${PROJECT_SOURCE_DIR}/tools/validate.py
        ${PROJECT_SOURCE_DIR}/tools/verify_report.py
        DESTINATION ${BALLISTA_SHARE_DIR}/tools)
install(DIRECTORY ${PROJECT_SOURCE_DIR}/examples/ DESTINATION ${BALLISTA_SHARE_DIR}/examples)
install(FILES ${PROJECT_SOURCE_DIR}/README.md DESTINATION ${CMAKE_INSTALL_DOCDIR})
install(DIRECTORY ${PROJECT_SOURCE_DIR}/docs/ DESTINATION ${CMAKE_INSTALL_DOCDIR})

# Debian package: `make package` (cpack -G DEB in build/). The shared libraries' packages are
# found by dpkg-shlibdeps (Debian's dpkg-dev) from what the binary links; the Python packages the
# figure and report tools import, and mpirun for several ranks, are declared here.
set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGE_NAME ballista)
set(CPACK_PACKAGE_VENDOR "Ballista developers")
set(CPACK_PACKAGE_CONTACT "Ballista developers")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY
    "Simulator for solids under extreme deformation (MPM, peridynamics, OTM)")
set(CPACK_PACKAGE_INSTALL_DIRECTORY ballista)
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_SECTION science)
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
set(CPACK_DEBIAN_PACKAGE_DEPENDS "python3, python3-numpy, python3-matplotlib, python3-h5py, openmpi-bin")
set(CPACK_STRIP_FILES ON)
include(CPack)
