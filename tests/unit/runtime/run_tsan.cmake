# Configure + build runtime_test with ThreadSanitizer, run the concurrent
# hand-off tests. Invoked by ctest (runtime_tsan) with -DSRC= -DBIN=.
execute_process(
  COMMAND ${CMAKE_COMMAND} -S ${SRC} -B ${BIN} -G Ninja -DXR_SANITIZE=thread -DXR_BUILD_BENCH=OFF
          -DCMAKE_BUILD_TYPE=RelWithDebInfo
  RESULT_VARIABLE rc OUTPUT_QUIET)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "TSan configure failed (${rc})")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} --build ${BIN} -j2 --target runtime_test RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "TSan build of runtime_test failed (${rc})")
endif()
# setarch -R: TSan's shadow mapping breaks with the high mmap ASLR entropy of
# recent kernels.
find_program(SETARCH setarch)
set(prefix)
if(SETARCH)
  set(prefix ${SETARCH} -R)
endif()
set(ENV{TSAN_OPTIONS} "halt_on_error=1 second_deadlock_stack=1")
execute_process(
  COMMAND ${prefix} ${BIN}/tests/unit/runtime/runtime_test
          --gtest_filter=*Concurrent*:EventPump.*:ControlLoop.*:ControlCycle.*
  RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "runtime_test under ThreadSanitizer failed (${rc})")
endif()
