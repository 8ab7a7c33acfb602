# subdivbench pictures as a user runs it (-DSUBDIVBENCH=... -DOUT=...): without a Vulkan driver it
# writes the manifest saying so and exits 0; a bad scheme exits 2 with one line, writing nothing.
file(REMOVE_RECURSE ${OUT})

execute_process(
  COMMAND ${CMAKE_COMMAND} -E env --unset=VK_DRIVER_FILES --unset=VK_ADD_DRIVER_FILES VK_ICD_FILENAMES=/nonexistent
          ${SUBDIVBENCH} pictures --out ${OUT}/none
  RESULT_VARIABLE rc OUTPUT_VARIABLE stdout ERROR_VARIABLE stderr)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "without a driver: exit code ${rc}, expected 0\n${stdout}${stderr}")
endif()
file(READ ${OUT}/none/pictures/pictures.json manifest)
string(JSON available GET "${manifest}" available)
string(JSON reason GET "${manifest}" reason)
string(JSON pictures LENGTH "${manifest}" pictures)
if(available OR NOT reason MATCHES "^no Vulkan device" OR NOT pictures EQUAL 0)
  message(FATAL_ERROR "without a driver the manifest should say so:\n${manifest}")
endif()
if(NOT stdout MATCHES "no pictures: no Vulkan device")
  message(FATAL_ERROR "without a driver the verb should say so:\n${stdout}")
endif()

execute_process(
  COMMAND ${SUBDIVBENCH} pictures --out ${OUT}/bad --scheme no-such-scheme
  RESULT_VARIABLE rc OUTPUT_VARIABLE stdout ERROR_VARIABLE stderr)
string(STRIP "${stderr}" stderr)
if(NOT rc EQUAL 2 OR NOT stderr MATCHES "^subdivbench: no-such-scheme: no such scheme" OR stderr MATCHES "\n")
  message(FATAL_ERROR "a bad scheme: exit code ${rc} (expected 2), stderr:\n${stderr}")
endif()
if(EXISTS ${OUT}/bad)
  message(FATAL_ERROR "a bad scheme left ${OUT}/bad behind")
endif()
message(STATUS "pictures: no driver -> manifest and exit 0; bad scheme -> exit 2")
