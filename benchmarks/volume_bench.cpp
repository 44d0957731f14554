// Volume backends timed on the same poses: volume/<case>/<method>.
#include <benchmark/benchmark.h>

BENCHMARK_MAIN();
