# Installs the build into a fresh prefix and checks what lands there:
#   cmake -DBUILD_DIR=... -DPREFIX=... -DVERSION=... -DWITH_STUDIO=0|1 -P install_test.cmake
file(REMOVE_RECURSE "${PREFIX}")
execute_process(COMMAND "${CMAKE_COMMAND}" --install "${BUILD_DIR}" --prefix "${PREFIX}"
                RESULT_VARIABLE rc OUTPUT_QUIET)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "cmake --install failed (${rc})")
endif()

set(expected bin/relight share/doc/relight/README.md share/doc/relight/commands.md share/doc/relight/formats.md
             share/doc/relight/tutorial.md share/doc/relight/images/demo.png share/relight/blender/relight_export.py)
if(WITH_STUDIO)
  list(APPEND expected bin/relight-studio share/applications/relight-studio.desktop)
endif()
foreach(f IN LISTS expected)
  if(NOT EXISTS "${PREFIX}/${f}")
    message(FATAL_ERROR "not installed: ${f}")
  endif()
endforeach()
if(WITH_STUDIO)
  file(READ "${PREFIX}/share/applications/relight-studio.desktop" entry)
  if(NOT entry MATCHES "\nExec=relight-studio")
    message(FATAL_ERROR "the desktop entry does not start relight-studio")
  endif()
endif()

# The installed formats page is the whole contract: the base scene and rig
# formats, not only relight's extensions.
file(READ "${PREFIX}/share/doc/relight/formats.md" formats)
foreach(part "## The scene: `scene.json`" "### Camera" "### Lights" "### Light probes" "## The rig: `rig.json`")
  string(FIND "${formats}" "${part}" at)
  if(at EQUAL -1)
    message(FATAL_ERROR "the installed formats.md has no \"${part}\"")
  endif()
endforeach()

# The installed program runs from its new place and knows its version.
execute_process(COMMAND "${PREFIX}/bin/relight" --version RESULT_VARIABLE rc OUTPUT_VARIABLE out
                OUTPUT_STRIP_TRAILING_WHITESPACE)
if(NOT rc EQUAL 0 OR NOT out STREQUAL "relight ${VERSION}")
  message(FATAL_ERROR "installed relight --version: exit ${rc}, printed '${out}', expected 'relight ${VERSION}'")
endif()
message(STATUS "installed into ${PREFIX}: ${expected}; ${out}")
