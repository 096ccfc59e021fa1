terrace_bench(bench_event_queue.cpp terrace_dmd)
terrace_bench(bench_dmd.cpp terrace_dmd)
terrace_bench(bench_body_layout.cpp terrace_dmd)
