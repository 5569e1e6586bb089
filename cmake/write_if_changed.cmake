# cutbench_write_if_changed(<file> <text> [TOUCH]): write <text> to <file> only when it differs, so
# that a generated source that did not change rebuilds nothing. TOUCH: bring an unchanged file's
# time stamp up to date (for a custom command's OUTPUT whose DEPENDS changed).
function(cutbench_write_if_changed file text)
  set(old "")
  if(EXISTS "${file}")
    file(READ "${file}" old)
  endif()
  if(NOT old STREQUAL text)
    file(WRITE "${file}" "${text}")
  elseif(ARGN STREQUAL "TOUCH")
    file(TOUCH_NOCREATE "${file}")
  endif()
endfunction()
