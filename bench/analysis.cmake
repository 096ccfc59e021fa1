# Cost per sample of the analysis a run accumulates (bench/bench_analysis.cpp).
terrace_bench(bench_analysis.cpp terrace_analysis)
