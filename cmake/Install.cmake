# Installation (`cmake --install build [--prefix P]`) and the Debian package (`cpack -G DEB`,
# run in the build folder). What goes where, under the prefix P:
#   bin/seqmassage                                   the command line
#   <python dir>/seqmassage*.so, seqmassage.pyi      the Python module and its type stubs
#   <python dir>/seqmassage-stubs/__init__.pyi       the stubs again, as a PEP 561 stub package
#   share/seqmassage/seqmassage_blender.zip          the Blender add-on (Edit > Preferences >
#                                                    Add-ons > Install...)
#   share/man/man1/seqmassage.1                      the man page (docs/seqmassage.1)
#   share/bash-completion/completions/seqmassage     bash completion
#   share/doc/seqmassage/                            README, CHANGELOG, LICENSE, docs/, configs/
# <python dir> is decided when installing, from the prefix: lib/python3/dist-packages for a prefix
# ending in /usr (Debian's place for packaged modules: the .deb, `--prefix /usr`), else
# lib/python3.X/dist-packages on Debian (found by /usr/local's Python) or lib/python3.X/
# site-packages elsewhere; SEQMASSAGE_PYTHON_INSTALL_DIR (relative to the prefix) overrides it.
# The installed program reads nothing from the source or build tree.
include(GNUInstallDirs)
# Installing (and cpack) takes what is built and builds nothing: `cmake --build build` first.
# Otherwise cpack would build every test and tool before packaging.
set(CMAKE_SKIP_INSTALL_ALL_DEPENDENCY ON)

install(TARGETS seqmassage RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})

install(FILES ${PROJECT_SOURCE_DIR}/docs/seqmassage.1 DESTINATION ${CMAKE_INSTALL_MANDIR}/man1)
install(FILES ${PROJECT_SOURCE_DIR}/tools/completion/seqmassage.bash
        DESTINATION ${CMAKE_INSTALL_DATADIR}/bash-completion/completions RENAME seqmassage)
install(FILES ${PROJECT_SOURCE_DIR}/README.md ${PROJECT_SOURCE_DIR}/CHANGELOG.md
              ${PROJECT_SOURCE_DIR}/LICENSE
        DESTINATION ${CMAKE_INSTALL_DOCDIR})
# Debian's place for the licence of a package's files.
install(FILES ${PROJECT_SOURCE_DIR}/LICENSE DESTINATION ${CMAKE_INSTALL_DOCDIR} RENAME copyright)
install(DIRECTORY ${PROJECT_SOURCE_DIR}/docs/ DESTINATION ${CMAKE_INSTALL_DOCDIR}/docs
        FILES_MATCHING PATTERN "*.md" PATTERN "*.png" PATTERN "*.svg")
install(DIRECTORY ${PROJECT_SOURCE_DIR}/configs/ DESTINATION ${CMAKE_INSTALL_DOCDIR}/configs
        FILES_MATCHING PATTERN "*.json")

# The Blender add-on as an installable zip, its bl_info version set from project(VERSION).
set(seqmassage_addon_zip ${PROJECT_BINARY_DIR}/blender/seqmassage_blender.zip)
file(GLOB seqmassage_addon_sources CONFIGURE_DEPENDS
     ${PROJECT_SOURCE_DIR}/blender/seqmassage_blender/*.py)
add_custom_command(
  OUTPUT ${seqmassage_addon_zip}
  COMMAND ${CMAKE_COMMAND} -DSOURCE=${PROJECT_SOURCE_DIR}/blender/seqmassage_blender
          -DSTAGE=${PROJECT_BINARY_DIR}/blender/stage -DZIP=${seqmassage_addon_zip}
          -DVERSION=${PROJECT_VERSION} -P ${PROJECT_SOURCE_DIR}/cmake/addon_zip.cmake
  DEPENDS ${seqmassage_addon_sources} ${PROJECT_SOURCE_DIR}/cmake/addon_zip.cmake
  COMMENT "Blender add-on zip (bl_info version ${PROJECT_VERSION})")
add_custom_target(seqmassage_blender_zip ALL DEPENDS ${seqmassage_addon_zip})
install(FILES ${seqmassage_addon_zip} DESTINATION ${CMAKE_INSTALL_DATADIR}/seqmassage)

if(SEQMASSAGE_PYTHON)
  set(SEQMASSAGE_PYTHON_INSTALL_DIR "" CACHE STRING
      "Where the Python module goes, relative to the prefix (empty: decided from the prefix)")
  execute_process(
    COMMAND ${Python3_EXECUTABLE} -c
            "import sys; print(any(p.endswith('/dist-packages') for p in sys.path))"
    OUTPUT_VARIABLE seqmassage_debian_python OUTPUT_STRIP_TRAILING_WHITESPACE)
  set(seqmassage_versioned_dir
      "lib/python${Python3_VERSION_MAJOR}.${Python3_VERSION_MINOR}/site-packages")
  if(seqmassage_debian_python STREQUAL "True")
    set(seqmassage_versioned_dir
        "lib/python${Python3_VERSION_MAJOR}.${Python3_VERSION_MINOR}/dist-packages")
  endif()
  set(seqmassage_stubs ${PROJECT_SOURCE_DIR}/src/python/seqmassage.pyi)
  install(CODE "
    set(dir \"${SEQMASSAGE_PYTHON_INSTALL_DIR}\")
    if(NOT dir)
      set(dir \"${seqmassage_versioned_dir}\")
      if(CMAKE_INSTALL_PREFIX MATCHES \"/usr/?$\" AND \"${seqmassage_debian_python}\" STREQUAL \"True\")
        set(dir lib/python3/dist-packages)
      endif()
    endif()
    file(INSTALL \"$<TARGET_FILE:seqmassage_python>\" DESTINATION \"\${CMAKE_INSTALL_PREFIX}/\${dir}\")
    file(INSTALL \"${seqmassage_stubs}\" DESTINATION \"\${CMAKE_INSTALL_PREFIX}/\${dir}\")
    file(INSTALL \"${seqmassage_stubs}\" DESTINATION \"\${CMAKE_INSTALL_PREFIX}/\${dir}/seqmassage-stubs\"
         RENAME __init__.pyi)")
endif()

# The Debian package: seqmassage_<version>_<arch>.deb, its Depends from the shared libraries the
# program and the module link (dpkg-shlibdeps) plus the Python the module was built for.
set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGE_NAME seqmassage)
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
# No public address yet: a reserved .invalid one, so that nobody is mailed by mistake.
set(CPACK_PACKAGE_CONTACT "seqmassage contributors <maintainers@seqmassage.invalid>")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY
    "Mesh Massage: remove texture swimming from animated triangle-mesh sequences")
set(CPACK_PACKAGE_DESCRIPTION
    "seqmassage moves the vertices of every frame of an animated mesh sequence so its triangles "
    "take a template's shapes while the surface stays where it is (Winkler, Hormann, Gotsman, "
    "Mesh Massage). It reads OBJ/PLY/OFF frame folders, glTF animations and PC2/MDD point "
    "caches. Includes the Python module and the Blender add-on (zip).")
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)  # seqmassage_<version>_<arch>.deb
set(CPACK_DEBIAN_PACKAGE_SECTION science)
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
if(SEQMASSAGE_PYTHON)
  # The module is built for one Python minor version (its file name says which).
  math(EXPR seqmassage_next_minor "${Python3_VERSION_MINOR} + 1")
  set(CPACK_DEBIAN_PACKAGE_DEPENDS
      "python3 (>= ${Python3_VERSION_MAJOR}.${Python3_VERSION_MINOR}), python3 (<< ${Python3_VERSION_MAJOR}.${seqmassage_next_minor}), python3-numpy")
endif()
set(CPACK_STRIP_FILES ON)
include(CPack)
