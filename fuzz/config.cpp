// libFuzzer entry for fuzz::config() (see FuzzTargets.h).
#include "FuzzTargets.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t *data, std::size_t size)
{
    meshgap::fuzz::config(data, size);
    return 0;
}
