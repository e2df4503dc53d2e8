# Fails when the test cases compiled into test_e2e differ from the list
# registered with CTest in CMakeLists.txt.
#   cmake -DTEST_BINARY=path/to/test_e2e -DEXPECTED=A.x,B.y -P check_test_list.cmake
execute_process(COMMAND ${TEST_BINARY} --gtest_list_tests
                OUTPUT_VARIABLE listing RESULT_VARIABLE result)
if(NOT result EQUAL 0)
  message(FATAL_ERROR "${TEST_BINARY} --gtest_list_tests failed (${result})")
endif()

set(compiled "")
string(REPLACE "\n" ";" lines "${listing}")
foreach(line IN LISTS lines)
  if(line MATCHES "^([A-Za-z0-9_]+)\\.$")
    set(suite ${CMAKE_MATCH_1})
  elseif(line MATCHES "^  ([A-Za-z0-9_]+)")
    list(APPEND compiled "${suite}.${CMAKE_MATCH_1}")
  endif()
endforeach()
string(REPLACE "," ";" registered "${EXPECTED}")

list(SORT compiled)
list(SORT registered)
if(NOT compiled STREQUAL registered)
  set(missing ${compiled})
  list(REMOVE_ITEM missing ${registered})
  set(stale ${registered})
  list(REMOVE_ITEM stale ${compiled})
  message(FATAL_ERROR "tests/e2e/CMakeLists.txt and test_e2e disagree.\n"
                      "  compiled but not registered: ${missing}\n"
                      "  registered but not compiled: ${stale}")
endif()
list(LENGTH compiled count)
message(STATUS "all ${count} e2e test cases are registered")
