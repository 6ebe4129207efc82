// libFuzzer entry for fuzz::urdf() (see FuzzTargets.h).
#include "FuzzTargets.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t *data, std::size_t size)
{
    meshgap::fuzz::urdf(data, size);
    return 0;
}
