# Writes OUTPUT (a C++ header) with the version `git describe` gives for SOURCE_DIR, rewritten
# only when it changes, so a build records the commit it was built from without recompiling
# anything else. Run at every build (a custom target).
execute_process(COMMAND git describe --always --dirty --tags
                WORKING_DIRECTORY ${SOURCE_DIR}
                OUTPUT_VARIABLE version OUTPUT_STRIP_TRAILING_WHITESPACE
                ERROR_QUIET RESULT_VARIABLE failed)
if(failed OR version STREQUAL "")
  set(version "unknown (not built from a git checkout)")
endif()
file(WRITE ${OUTPUT}.tmp "// Generated at build time by cmake/git_version.cmake.\n#define REPOSE_VERSION \"${version}\"\n")
file(COPY_FILE ${OUTPUT}.tmp ${OUTPUT} ONLY_IF_DIFFERENT)
