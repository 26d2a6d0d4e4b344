# The Debian package of the install rules: `cpack -G DEB` in a build configured by
# scripts/package.sh. dpkg-shlibdeps computes Depends from the libraries the executable links.
set(CLMARCH_PACKAGE_MAINTAINER "clmarch maintainers <maintainers@users.noreply.h-seed-b87d1f95.example>"
    CACHE STRING "The Maintainer field of the Debian package")
set(CPACK_PACKAGE_NAME clmarch)
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "sphere tracer of signed distance fields on OpenCL")
# CPack puts the summary above it as the first line of Description.
set(CPACK_DEBIAN_PACKAGE_DESCRIPTION
    "clmarch renders scenes of signed distance fields (primitives, boolean and
smooth operators, transforms, fractals, terrains) described in YAML files.
It generates OpenCL C specialised to each scene and runs it on any OpenCL
device (PoCL on the CPU, GPU drivers), and has a double-precision CPU
reference renderer to check the results against.")
set(CPACK_DEBIAN_PACKAGE_MAINTAINER "${CLMARCH_PACKAGE_MAINTAINER}")
set(CPACK_DEBIAN_PACKAGE_SECTION graphics)
set(CPACK_DEBIAN_PACKAGE_PRIORITY optional)
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
# libOpenCL is only the ICD loader: an OpenCL driver renders (`--backend reference` needs none).
set(CPACK_DEBIAN_PACKAGE_RECOMMENDS "pocl-opencl-icd | opencl-icd")
# clmarch_0.3.0_amd64.deb
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_STRIP_FILES ON)
set(CPACK_GENERATOR DEB)

# Debian policy's copyright and changelog files go into the package only (the component `debian`,
# left out of a plain `cmake --install`). The changelog is the Debian kind, one entry that points
# to CHANGELOG.md, dated by CHANGELOG.md's heading of this version so that the package's bytes
# follow its sources.
file(STRINGS ${PROJECT_SOURCE_DIR}/CHANGELOG.md CLMARCH_RELEASE_HEADING
     REGEX "^## \\[${PROJECT_VERSION}\\] - [0-9]+-[0-9]+-[0-9]+")
if(CLMARCH_RELEASE_HEADING MATCHES "([0-9]+-[0-9]+-[0-9]+)")
  execute_process(COMMAND date -u -R -d "${CMAKE_MATCH_1}" OUTPUT_VARIABLE CLMARCH_RELEASE_DATE
                  OUTPUT_STRIP_TRAILING_WHITESPACE COMMAND_ERROR_IS_FATAL ANY)
else()
  message(WARNING "CHANGELOG.md has no heading '## [${PROJECT_VERSION}] - YYYY-MM-DD': the package's changelog is dated now")
  string(TIMESTAMP CLMARCH_RELEASE_DATE "%a, %d %b %Y %H:%M:%S +0000" UTC)
endif()
set(CLMARCH_DEBIAN_DIR ${PROJECT_BINARY_DIR}/debian)
file(WRITE ${CLMARCH_DEBIAN_DIR}/changelog
     "clmarch (${PROJECT_VERSION}) unstable; urgency=medium\n\n"
     "  * Release ${PROJECT_VERSION}: see /usr/share/doc/clmarch/CHANGELOG.md.\n\n"
     " -- ${CLMARCH_PACKAGE_MAINTAINER}  ${CLMARCH_RELEASE_DATE}\n")
execute_process(COMMAND gzip -9nc ${CLMARCH_DEBIAN_DIR}/changelog OUTPUT_FILE ${CLMARCH_DEBIAN_DIR}/changelog.gz
                COMMAND_ERROR_IS_FATAL ANY)
install(FILES ${CLMARCH_DEBIAN_DIR}/changelog.gz ${PROJECT_SOURCE_DIR}/cmake/debian/copyright
        DESTINATION ${CMAKE_INSTALL_DOCDIR} COMPONENT debian EXCLUDE_FROM_ALL)
set(CPACK_COMPONENTS_ALL Unspecified debian)
set(CPACK_COMPONENTS_GROUPING ALL_COMPONENTS_IN_ONE)
set(CPACK_DEB_COMPONENT_INSTALL ON)
include(CPack)
