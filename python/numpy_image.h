#pragma once
// vri's images as NumPy arrays and back: (height, width, channels), row 0 at the top, the layout of
// Image::pixels, so the conversion is one copy of the floats and changes no bit.
#include <string>
#include <vector>

#include <pybind11/numpy.h>

#include "libvri/core/image.h"

namespace vri {

pybind11::array_t<float> toNumpy(const Image& image);
// float64 values (the exact reference's, before rounding to float) in the same layout.
pybind11::array_t<double> toNumpy(const std::vector<double>& values, int width, int height, int channels);
// A (height, width, channels) array of any real type, converted to float (float32 arrays bit for bit),
// channels named as Image(w, h, n) names them. Throws vri::Error "<what>: ..." for another shape.
Image fromNumpy(pybind11::handle array, const std::string& what);

}  // namespace vri
