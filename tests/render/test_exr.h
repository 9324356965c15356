// An EXR read back as floats with its channel names, for render tests that compare AOVs.
#pragma once

#include <string>
#include <vector>

#include <OpenImageIO/imagebuf.h>

namespace citygen::test {

struct Exr {
    int width = 0, height = 0, channels = 0;
    std::vector<std::string> names;
    std::vector<float> pixels;
    int channel(const std::string& name) const {
        for (size_t i = 0; i < names.size(); ++i)
            if (names[i] == name) return static_cast<int>(i);
        return -1;
    }
    float at(int pixel, int c) const { return pixels[static_cast<size_t>(pixel) * channels + c]; }
};

// An empty Exr (width 0) when the file cannot be read.
inline Exr read_exr(const std::string& path) {
    OIIO::ImageBuf buf(path);
    Exr exr;
    if (!buf.read(0, 0, true, OIIO::TypeDesc::FLOAT)) return exr;
    const OIIO::ImageSpec& spec = buf.spec();
    exr.width = spec.width;
    exr.height = spec.height;
    exr.channels = spec.nchannels;
    exr.names = spec.channelnames;
    exr.pixels.resize(static_cast<size_t>(exr.width) * exr.height * exr.channels);
    buf.get_pixels(OIIO::ROI::All(), OIIO::TypeDesc::FLOAT, exr.pixels.data());
    return exr;
}

}  // namespace citygen::test
