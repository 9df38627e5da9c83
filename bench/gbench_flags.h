// Google Benchmark's own flags, as its Initialize() parsed them. Version 1.7
// (Debian 12's libbenchmark-dev) exports these variables but declares them
// only in a private header (src/commandlineflags.h, BM_DECLARE_*): declared
// here with the same types, so raycast-bench reads the library's parse
// instead of parsing the command line a second time.
#pragma once
#include <cstdint>
#include <string>

namespace benchmark {
extern bool FLAGS_benchmark_list_tests;
extern double FLAGS_benchmark_min_time;
extern std::string FLAGS_benchmark_format;
extern std::string FLAGS_benchmark_out;
extern std::string FLAGS_benchmark_out_format;
}  // namespace benchmark
