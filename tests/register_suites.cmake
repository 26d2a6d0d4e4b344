# Registers the test executable's tests with ctest a process per group (run by ctest through
# TEST_INCLUDE_FILES, after the executable is built): the tests of one suite run in one process, so
# that they share its OpenCL context and the programs it built (cl/device_program.hpp), instead of
# starting the driver and loading programs once per test. A suite of more than MAX_GROUP tests is
# split into groups of consecutive tests, so that the two cores stay busy to the end.
#   TEST_EXECUTABLE  the gtest executable       OUTPUT     the ctest file to write
#   SERIAL           suites (regex) that run alone
#   MAX_GROUP        most tests in one process  TIMEOUT    seconds a group may take
#   COSTS            suite_costs.txt: a group's seconds, its ctest COST (the costliest start first)
#   COVERAGE_DIR     (coverage builds) where each group's gcov counts go, a folder per group
#                    (GCOV_PREFIX), for scripts/coverage-report.py
execute_process(
  COMMAND "${TEST_EXECUTABLE}" --gtest_list_tests
  OUTPUT_VARIABLE listing
  RESULT_VARIABLE listed)
if(NOT listed EQUAL 0)
  message(FATAL_ERROR "register_suites.cmake: ${TEST_EXECUTABLE} --gtest_list_tests failed: ${listed}")
endif()
string(REPLACE "\n" ";" lines "${listing}")
set(suites "")
foreach(line IN LISTS lines)
  # "Suite.", "Prefix/Suite.  # TypeParam = ...", "  Test", "  Test/0  # GetParam() = ..."
  string(REGEX REPLACE "  #.*$" "" line "${line}")
  if(line MATCHES "^([^ ].*)\\.$")
    set(suite "${CMAKE_MATCH_1}")
    list(APPEND suites "${suite}")
    string(MAKE_C_IDENTIFIER "${suite}" var)
    set(tests_${var} "")
  elseif(line MATCHES "^  (.+)$")
    list(APPEND tests_${var} "${CMAKE_MATCH_1}")
  endif()
endforeach()

file(STRINGS "${COSTS}" cost_lines REGEX "^[^#]")
foreach(line IN LISTS cost_lines)
  if(NOT line MATCHES "^([^ ]+) ([0-9]+)$")
    message(FATAL_ERROR "register_suites.cmake: ${COSTS}: not 'group seconds': ${line}")
  endif()
  string(MAKE_C_IDENTIFIER "${CMAKE_MATCH_1}" var)
  set(cost_${var} ${CMAKE_MATCH_2})
endforeach()
# The properties of the group named name: properties, and its COST where suite_costs.txt lists it.
function(group_properties name properties out)
  string(MAKE_C_IDENTIFIER "${name}" var)
  if(DEFINED cost_${var})
    string(APPEND properties " COST ${cost_${var}}")
  endif()
  set(${out} "${properties}" PARENT_SCOPE)
endfunction()

set(script "")
foreach(suite IN LISTS suites)
  string(MAKE_C_IDENTIFIER "${suite}" var)
  list(LENGTH tests_${var} count)
  set(properties "TIMEOUT ${TIMEOUT}")
  if(suite MATCHES "${SERIAL}")
    string(APPEND properties " RUN_SERIAL TRUE")
  endif()
  if(COVERAGE_DIR)
    string(MAKE_C_IDENTIFIER "${suite}" folder)
    string(APPEND properties " ENVIRONMENT [=[GCOV_PREFIX=${COVERAGE_DIR}/${folder}]=]")
  endif()
  if(count LESS_EQUAL MAX_GROUP)
    group_properties("${suite}" "${properties}" suite_properties)
    string(APPEND script "add_test([=[${suite}]=] \"${TEST_EXECUTABLE}\" [=[--gtest_filter=${suite}.*]=])\n"
           "set_tests_properties([=[${suite}]=] PROPERTIES ${suite_properties})\n")
    continue()
  endif()
  math(EXPR groups "(${count} + ${MAX_GROUP} - 1) / ${MAX_GROUP}")
  math(EXPR last "${groups} - 1")
  foreach(group RANGE ${last})
    math(EXPR first "${group} * ${count} / ${groups}")
    math(EXPR end "(${group} + 1) * ${count} / ${groups} - 1")
    set(filter "")
    foreach(i RANGE ${first} ${end})
      list(GET tests_${var} ${i} test)
      string(APPEND filter "${suite}.${test}:")
    endforeach()
    set(this_group_properties "${properties}")
    if(COVERAGE_DIR)
      string(REPLACE "]=]" "_${group}]=]" this_group_properties "${properties}")
    endif()
    group_properties("${suite}#${group}" "${this_group_properties}" this_group_properties)
    string(APPEND script "add_test([=[${suite}#${group}]=] \"${TEST_EXECUTABLE}\" [=[--gtest_filter=${filter}]=])\n"
           "set_tests_properties([=[${suite}#${group}]=] PROPERTIES ${this_group_properties})\n")
  endforeach()
endforeach()
file(WRITE "${OUTPUT}" "${script}")
