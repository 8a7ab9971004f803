// NumPy .npy files through eval::readNpyImage, the reader of `shadowkit score`'s float masks:
// any bytes give an image within the limits or a one-line error, never a crash, a hang or an
// allocation past the limits. (Its header was once parsed with std::regex, whose recursion a
// 60,000-character dtype drove off the stack.) npy.cpp is compiled into this target, so that
// libFuzzer sees its coverage without instrumenting the rest of libs/eval.
#include "fuzz_support.h"

#include "shadowkit/eval/npy.h"
#include "shadowkit/scene/image.h"

#include <cstdlib>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const auto file = shadowkit::fuzz::writeInput(data, size, ".npy");
    const auto image = shadowkit::eval::readNpyImage(file);
    if (image) {
        if (image->width < 1 || image->height < 1 ||
            int64_t(image->width) * image->height > shadowkit::scene::kMaxImageTexels ||
            image->values.size() != size_t(image->width) * size_t(image->height))
            std::abort();
    } else if (image.error().find('\n') != std::string::npos) {
        std::abort(); // errors are one line
    }
    return 0;
}
