// libFuzzer target: the `lodopt metrics A B` input path (image read, channel and size
// matching, every metric). Input layout in fuzz_metrics_input.hpp; seed corpus in
// tests/fuzz/corpus/metrics_input/. Run by scripts/fuzz.sh.
#include "fuzz_metrics_input.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    lodopt::fuzz::runMetricsInput(data, size);
    return 0;
}
