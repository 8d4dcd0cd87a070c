#include "python_option_text.h"

#include "libvri/util/error.h"
#include "libvri/util/format.h"

namespace py = pybind11;

namespace vri {

namespace {

std::string scalarText(py::handle value, const std::string& what) {
    if (py::isinstance<py::bool_>(value)) return value.cast<bool>() ? "true" : "false";
    if (py::isinstance<py::int_>(value)) return py::str(value).cast<std::string>();
    if (py::isinstance<py::float_>(value)) return exactNumber(value.cast<double>());
    if (py::isinstance<py::str>(value)) return value.cast<std::string>();
    // NumPy scalars (np.float32(0.5), np.int64(3)) are neither of the above.
    if (py::hasattr(value, "dtype") && py::hasattr(value, "item") && py::len(value.attr("shape")) == 0)
        return scalarText(value.attr("item")(), what);
    throw Error(what + ": expected a number, text, or a sequence of numbers, got " +
                py::str(py::type::handle_of(value).attr("__name__")).cast<std::string>());
}

}  // namespace

std::string optionText(py::handle value, const std::string& what) {
    if (py::isinstance<py::str>(value) || !py::isinstance<py::sequence>(value)) {
        if (!py::isinstance<py::str>(value) && py::hasattr(value, "tolist") && py::len(value.attr("shape")) > 0)
            return optionText(value.attr("tolist")(), what);  // a NumPy array: its elements
        return scalarText(value, what);
    }
    std::string text;
    for (py::handle element : value.cast<py::sequence>()) {
        if (!text.empty()) text += ',';
        text += scalarText(element, what);
    }
    return text;
}

}  // namespace vri
