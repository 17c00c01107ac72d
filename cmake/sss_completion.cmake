# The bash completion script of the sss tool, generated from its option tables (`sss completion bash`).
# Included from CMakeLists.txt: builds sss-completion.bash next to the tool after every build of it and
# installs it as share/bash-completion/completions/sss (where bash-completion loads it on demand).
# Run as a script (cmake -DSSS=... -DOUT=... -P), it writes the file and fails when the tool does.
if(CMAKE_SCRIPT_MODE_FILE)
  execute_process(COMMAND ${SSS} completion bash OUTPUT_FILE ${OUT} RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    file(REMOVE ${OUT})
    message(FATAL_ERROR "sss completion bash failed: ${rc}")
  endif()
  return()
endif()

set(sss_completion_file ${CMAKE_CURRENT_BINARY_DIR}/sss-completion.bash)
add_custom_command(OUTPUT ${sss_completion_file}
                   COMMAND ${CMAKE_COMMAND} -DSSS=$<TARGET_FILE:sss_cli> -DOUT=${sss_completion_file}
                           -P ${CMAKE_CURRENT_LIST_FILE}
                   DEPENDS sss_cli ${CMAKE_CURRENT_LIST_FILE}
                   COMMENT "Generating the bash completion of sss" VERBATIM)
add_custom_target(sss_completion ALL DEPENDS ${sss_completion_file})
install(FILES ${sss_completion_file} DESTINATION ${CMAKE_INSTALL_DATADIR}/bash-completion/completions RENAME sss)
