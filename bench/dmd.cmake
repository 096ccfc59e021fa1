if(EXISTS ${CMAKE_CURRENT_SOURCE_DIR}/bench_event_queue.cpp)
    terrace_bench(bench_event_queue.cpp terrace_dmd)
endif()
