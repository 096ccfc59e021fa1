terrace_bench(bench_smd.cpp terrace_smd)
