# Runs two programs with the same arguments and fails unless both succeed with the same output.
#   cmake -DFIRST=... -DSECOND=... -DARGS=... -P same_output.cmake
foreach(program FIRST SECOND)
    execute_process(COMMAND ${${program}} ${ARGS} OUTPUT_VARIABLE ${program}_output RESULT_VARIABLE ${program}_status)
    if(NOT ${program}_status EQUAL 0)
        message(FATAL_ERROR "${${program}} failed (${${program}_status})")
    endif()
endforeach()
if(NOT FIRST_output STREQUAL SECOND_output)
    message(FATAL_ERROR "the outputs differ:\n${FIRST}:\n${FIRST_output}\n${SECOND}:\n${SECOND_output}")
endif()
message(STATUS "the same output:\n${FIRST_output}")
