if(EXISTS ${CMAKE_CURRENT_SOURCE_DIR}/bench_free_motion.cpp)
    terrace_bench(bench_free_motion.cpp terrace_core)
endif()
