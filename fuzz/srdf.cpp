// libFuzzer entry for fuzz::srdf() (see FuzzTargets.h).
#include "FuzzTargets.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t *data, std::size_t size)
{
    meshgap::fuzz::srdf(data, size);
    return 0;
}
