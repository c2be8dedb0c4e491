# Writes OUT with the commit the build is made from (MFV_GIT_COMMIT) and the
# build's git description (MFV_GIT_DESCRIBE: `git describe --tags --always`,
# the nearest tag, commits since it and the commit, for `mfv --version`), at every build (not at
# configure time, which left a stale id in results files after later
# commits). "-dirty" when tracked files other than results/ differ from it.
# Rewrites OUT only when the text changes, so an unchanged commit rebuilds
# nothing.
execute_process(COMMAND git -C ${SOURCE_DIR} rev-parse --short HEAD
                OUTPUT_VARIABLE commit OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET)
execute_process(COMMAND git -C ${SOURCE_DIR} describe --tags --always --abbrev=7
                OUTPUT_VARIABLE describe OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET)
if(NOT commit)
  set(commit "unknown")
  set(describe "unknown")
else()
  execute_process(COMMAND git -C ${SOURCE_DIR} status --porcelain --untracked-files=no -- . ":(exclude)results"
                  OUTPUT_VARIABLE changes ERROR_QUIET)
  if(changes)
    string(APPEND commit "-dirty")
    string(APPEND describe "-dirty")
  endif()
endif()
set(text "// Generated at build time by cmake/GitCommit.cmake.\n#pragma once\n#define MFV_GIT_COMMIT \"${commit}\"\n#define MFV_GIT_DESCRIBE \"${describe}\"\n")
set(old "")
if(EXISTS ${OUT})
  file(READ ${OUT} old)
endif()
if(NOT old STREQUAL text)
  file(WRITE ${OUT} "${text}")
endif()
