# Cost of the correlation analysis of one run (analysis/bench/bench_analysis.cpp).
add_executable(bench_analysis ${PROJECT_SOURCE_DIR}/analysis/bench/bench_analysis.cpp)
target_link_libraries(bench_analysis PRIVATE terrace_analysis benchmark::benchmark)
