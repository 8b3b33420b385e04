# The reference pages keep up with the program:
# - every key the scene and rig loaders accept (each list given to
#   warn_unknown_keys in src/) is documented in docs/formats.md, as `key`
#   (or a dotted path ending in it, `camera.key`);
# - every option `relight --help` and `relight CMD --help` list is in
#   docs/commands.md: a command's options in its own section ("## relight CMD"),
#   the options of every command in the page's opening part, before the first
#   section;
# - every option `relight-studio --help` lists is in docs/studio.md (where
#   STUDIO is given).
# It fails with the list of what is missing.
#   cmake -DRELIGHT=... [-DSTUDIO=...] -DSOURCE_DIR=... -P docs_test.cmake
set(missing "")

# ---- keys
file(READ "${SOURCE_DIR}/docs/formats.md" formats)
file(GLOB_RECURSE sources "${SOURCE_DIR}/src/*.cpp")
set(keys "")
foreach(source IN LISTS sources)
  file(READ "${source}" text)
  string(REGEX MATCHALL "warn_unknown_keys\\([^{};]*\\{[^}]*\\}" calls "${text}")
  foreach(call IN LISTS calls)
    string(REGEX MATCHALL "\"[A-Za-z0-9_]+\"" quoted "${call}")
    foreach(key IN LISTS quoted)
      string(REPLACE "\"" "" key "${key}")
      list(APPEND keys "${key}")
    endforeach()
  endforeach()
endforeach()
list(REMOVE_DUPLICATES keys)
list(LENGTH keys key_count)
if(key_count LESS 20)
  message(FATAL_ERROR "found only ${key_count} keys in the loaders' warn_unknown_keys lists: has the code changed?")
endif()
foreach(key IN LISTS keys)
  if(NOT formats MATCHES "`([a-z_]+\\.)*${key}`")
    list(APPEND missing "docs/formats.md: the key `${key}` (accepted by the loader)")
  endif()
endforeach()

# ---- options
file(READ "${SOURCE_DIR}/docs/commands.md" commands)
string(FIND "${commands}" "\n## " first_section)
string(SUBSTRING "${commands}" 0 ${first_section} opening)

# The options a --help text lists (lines "  -x,--name ..." or "  --name ..."),
# each as "--name" or "--name/-x" (documented under either name).
function(listed_options help out)
  string(REPLACE ";" "," help "${help}")
  string(REPLACE "\n" ";" lines "${help}")
  set(options "")
  foreach(line IN LISTS lines)
    if(line MATCHES "^  (-[A-Za-z0-9], ?)?(--[a-z0-9][a-z0-9-]*)")
      set(long "${CMAKE_MATCH_2}")
      string(REGEX REPLACE "[, ]" "" short "${CMAKE_MATCH_1}")
      if(short)
        string(PREPEND short "/")
      endif()
      if(NOT long STREQUAL "--help")
        list(APPEND options "${long}${short}")
      endif()
    endif()
  endforeach()
  set(${out} "${options}" PARENT_SCOPE)
endfunction()

function(documented option text out)
  string(REPLACE "/" ";" names "${option}")
  set(${out} FALSE PARENT_SCOPE)
  foreach(name IN LISTS names)
    if(text MATCHES "(^|[^a-z0-9-])${name}([^a-z0-9-]|$)")
      set(${out} TRUE PARENT_SCOPE)
    endif()
  endforeach()
endfunction()

# Runs PROGRAM... --help; each option it lists that `text` does not mention is
# added to `missing` as "WHERE: OPTION". The help text is left in help_text.
function(check_help where text)
  execute_process(COMMAND ${ARGN} --help OUTPUT_VARIABLE help RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    list(JOIN ARGN " " command)
    message(FATAL_ERROR "${command} --help: exit ${rc}")
  endif()
  listed_options("${help}" options)
  foreach(option IN LISTS options)
    documented("${option}" "${text}" ok)
    if(NOT ok)
      list(APPEND missing "${where}: ${option}")
    endif()
  endforeach()
  set(missing "${missing}" PARENT_SCOPE)
  set(help_text "${help}" PARENT_SCOPE)
endfunction()

check_help("docs/commands.md, the opening part: relight" "${opening}" "${RELIGHT}")
string(REGEX MATCH "\nSubcommands:\n(  [^\n]*\n)+" block "${help_text}")
string(REGEX MATCHALL "\n  [a-z][a-z0-9-]*" names "${block}")
list(LENGTH names command_count)
if(command_count LESS 5)
  message(FATAL_ERROR "found only ${command_count} commands in relight --help:\n${help_text}")
endif()
foreach(name IN LISTS names)
  string(STRIP "${name}" command)
  string(FIND "${commands}" "\n## relight ${command} " start)
  if(start EQUAL -1)
    list(APPEND missing "docs/commands.md: a section \"## relight ${command} ...\"")
    continue()
  endif()
  string(SUBSTRING "${commands}" ${start} -1 section)
  string(SUBSTRING "${section}" 1 -1 rest)
  string(FIND "${rest}" "\n## " end)
  if(NOT end EQUAL -1)
    string(SUBSTRING "${section}" 0 ${end} section)
  endif()
  check_help("docs/commands.md, relight ${command}" "${section}\n${opening}" "${RELIGHT}" ${command})
endforeach()

if(STUDIO)
  file(READ "${SOURCE_DIR}/docs/studio.md" studio_page)
  check_help("docs/studio.md: relight-studio" "${studio_page}" "${STUDIO}")
endif()

if(missing)
  list(JOIN missing "\n  " lines)
  message(FATAL_ERROR "undocumented:\n  ${lines}")
endif()
message(STATUS "${key_count} keys in docs/formats.md; ${command_count} commands' options in docs/commands.md")
