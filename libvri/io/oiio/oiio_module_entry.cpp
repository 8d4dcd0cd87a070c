// libvri-oiio.so's one exported symbol: the table of its functions (oiio_module.h).
#include "libvri/io/oiio/oiio_functions.h"

extern "C" __attribute__((visibility("default"))) const vri::detail::OiioModule* vri_oiio_module_2() {
    static const vri::detail::OiioModule module{vri::detail::oiio::readImage, vri::detail::oiio::readImageMetadata,
                                                vri::detail::oiio::encodeImage, vri::detail::oiio::readTiffStack};
    return &module;
}
