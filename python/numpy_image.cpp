#include "numpy_image.h"

#include <algorithm>
#include <limits>

#include "libvri/util/error.h"

namespace py = pybind11;

namespace vri {

namespace {

template <class T>
py::array_t<T> imageArray(const T* values, int width, int height, int channels) {
    py::array_t<T> array({py::ssize_t(height), py::ssize_t(width), py::ssize_t(channels)});
    std::copy_n(values, std::size_t(width) * height * channels, array.mutable_data());
    return array;
}

}  // namespace

py::array_t<float> toNumpy(const Image& image) {
    return imageArray(image.pixels.data(), image.width, image.height, image.channels);
}

py::array_t<double> toNumpy(const std::vector<double>& values, int width, int height, int channels) {
    return imageArray(values.data(), width, height, channels);
}

Image fromNumpy(py::handle object, const std::string& what) {
    const auto array = py::array_t<float, py::array::c_style | py::array::forcecast>::ensure(object);
    if (!array) throw Error(what + ": expected an image array of numbers, (height, width, channels)");
    const auto fits = [&](int axis) { return array.shape(axis) >= 1 && array.shape(axis) <= std::numeric_limits<int>::max(); };
    if (array.ndim() != 3 || !fits(0) || !fits(1) || !fits(2))
        throw Error(what + ": expected an image array of shape (height, width, channels)");
    Image image(int(array.shape(1)), int(array.shape(0)), int(array.shape(2)));  // checks the size's limit
    std::copy_n(array.data(), image.pixels.size(), image.pixels.begin());
    return image;
}

}  // namespace vri
