// libFuzzer entry for fuzz::distance() (see FuzzTargets.h).
#include "FuzzTargets.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t *data, std::size_t size)
{
    meshgap::fuzz::distance(data, size);
    return 0;
}
